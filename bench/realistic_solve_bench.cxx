// The corpus-callosum-like periodic cell of bench/realistic_bench.py ("cc-dense") on the Core
// alone, with a line of timings every N steps, so that a large cell's solve can be followed and
// profiled (perf) without ParaView. Same source and solver options as the pvpython bench's case:
// FiberCubeSource periodic, Lattice seeding, radii Gamma (mean 1 µm, spread 0.5), SegmentLength 2,
// Displacement 0, undulation 1.03 at 10 µm with coherence 5 µm, beading CV 0.16 over 16 µm;
// FiberCollisionSolver SegmentLength 2, MaxDisplacement 0.4, SeparationSpeed 0.0125, Tortuosity as
// the source's, TortuosityWavelength 15 µm. Usage:
// fiberpli_realistic_solve_bench [--edge 40] [--threads 2] [--volume-fraction 0.89]
//        [--tortuosity 1.03] [--solver-tortuosity T (the source's)] [--tortuosity-wavelength 15]
//        [--separation-speed 0.0125] [--max-steps 20000] [--every 100]
//        [--seed 42] [--coherence 5] [--beading-cv 0.16] [--beading-length 16]
//        [--drag 0 --drag-steps 0] [--max-displacement 0.4]
#include "BenchSolve.h"
#include "Solver/SolverState.h"
#include "Tissue/CubeGenerator.h"

#include <cstdio>
#include <cstdlib>
#include <string>

using namespace fiberpli;

int main(int argc, char** argv)
{
  CubeOptions c;
  c.populations = 1;
  c.edgeLength = 40.0;
  c.fiberRadius = 1.0;
  c.radiusSpread = 0.5;
  c.radiusDistribution = RadiusDistribution::Gamma;
  c.segmentLength = 2.0;
  c.displacement = 0.0;
  c.seed = 42;
  c.periodic = true;
  c.seeding = CubeSeeding::Lattice;
  c.volumeFraction = 0.89;
  c.undulationCoherence = 5.0;
  c.realism.tortuosity = 1.03;
  c.realism.undulationWavelength = 10.0;
  c.realism.beadingCV = 0.16;
  c.realism.beadingLength = 16.0;
  CollisionSolverOptions o;
  o.segmentLength = 2.0;
  o.maxSteps = 20000;
  o.maxDisplacement = 0.4;
  o.separationSpeed = 0.0125;
  o.tortuosityWavelength = 15.0;
  o.numberOfThreads = 2;
  int every = 100;
  double solverTortuosity = -1.0; // < 0: the source's
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    const auto next = [&]() { return i + 1 < argc ? argv[++i] : "0"; };
    if (a == "--edge")
      c.edgeLength = std::atof(next());
    else if (a == "--threads")
      o.numberOfThreads = std::atoi(next());
    else if (a == "--volume-fraction")
      c.volumeFraction = std::atof(next());
    else if (a == "--tortuosity")
      c.realism.tortuosity = std::atof(next());
    else if (a == "--solver-tortuosity")
      solverTortuosity = std::atof(next());
    else if (a == "--tortuosity-wavelength")
      o.tortuosityWavelength = std::atof(next());
    else if (a == "--separation-speed")
      o.separationSpeed = std::atof(next());
    else if (a == "--max-steps")
      o.maxSteps = std::atoi(next());
    else if (a == "--every")
      every = std::atoi(next());
    else if (a == "--seed")
      c.seed = static_cast<std::uint64_t>(std::atoll(next()));
    else if (a == "--coherence")
      c.undulationCoherence = std::atof(next());
    else if (a == "--beading-length")
      c.realism.beadingLength = std::atof(next());
    else if (a == "--drag")
      o.drag = std::atof(next());
    else if (a == "--drag-steps")
      o.dragSteps = std::atoi(next());
    else if (a == "--max-displacement")
      o.maxDisplacement = std::atof(next());
    else if (a == "--beading-cv")
      c.realism.beadingCV = std::atof(next());
    else
    {
      std::fprintf(stderr, "unknown argument %s\n", argv[i]);
      return 2;
    }
  }
  o.tortuosity = solverTortuosity < 0.0 ? c.realism.tortuosity : solverTortuosity;
  const std::string invalid = validateCubeOptions(c, 1);
  if (!invalid.empty())
  {
    std::fprintf(stderr, "%s\n", invalid.c_str());
    return 2;
  }
  double t0 = bench::seconds();
  std::string warning;
  FiberModel model = generateCube(c, 0, 1, &warning);
  if (!warning.empty())
    std::printf("warning: %s\n", warning.c_str());
  o.periodicCell = cubeCell(c);
  std::printf("generate %.1f s: %zu fibers, %zu points, hash %016llx\n", bench::seconds() - t0,
    model.fibers.size(), model.numberOfPoints(), bench::modelHash(model));
  CollisionSolverRun run(model, o);
  t0 = bench::seconds();
  const double c0 = bench::cpuSeconds();
  bench::stepWithTimings(run, every,
    [&](int s, double elapsed, double wall, double cpu)
    {
      std::printf("step %5d  %.1f s  %.4f s/step wall  %.4f s/step cpu  best %zu pairs  loud "
                  "%zu of %zu links\n",
        s, elapsed, wall, cpu, run.state().bestCollisions, run.loudLinks(), run.detectedLinks());
      std::fflush(stdout);
    });
  const CollisionSolverResult r = run.finish();
  std::printf("solve %.1f s wall, %.1f s cpu: %d steps, %zu collisions, volume fraction %.4f, "
              "peak RSS %.0f MB, hash %016llx%s%s\n",
    bench::seconds() - t0, bench::cpuSeconds() - c0, r.steps, r.collisions, r.volumeFraction,
    bench::peakRssMB(), bench::modelHash(model),
    r.error.empty() ? "" : " error: ", r.error.c_str());
  return r.error.empty() ? 0 : 1;
}
