// Dense periodic cells (bench/README.md, "Periodic cells"): generateCube with Periodic on and a
// VolumeFraction, solved with radius growth; φ measured independently by Monte Carlo over the
// cell with all 27 images of every capsule.
// Usage: fiberpli_periodic_bench [--edge 30] [--pops 1,2,3] [--phi 0.85,0.72,0.58] [--threads 1,2]
//        [--max-steps 20000] [--init-scale X] [--spread S] [--gamma] [--samples 1e6] [--seed 42]
//        [--curvature 4] [--cap SECONDS] [--overlap-push X] [--separation-speed X]
//        [--max-displacement X] [--displacement D (0.5, of the generated fibers)] [--drag X]
//        [--push-boost X]
//        [--lattice (Seeding Lattice instead of Random)] [--uniform (Uniform radii, mean 1 um)]
//        [--radius R (FiberRadius: 0.8 um, with --gamma / --uniform the mean 1 um)]
#include "BenchUtil.h"
#include "CapsuleCells.h"
#include "PushOverrides.h"
#include "Solver/CollisionSolver.h"
#include "Tissue/CubeGenerator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

using namespace fiberpli;

namespace
{
std::vector<double> list(char* s)
{
  std::vector<double> v;
  for (char* t = std::strtok(s, ","); t; t = std::strtok(nullptr, ","))
    v.push_back(std::atof(t));
  return v;
}

// Fraction of the cell [-L/2, L/2]³ inside any capsule image: every segment is placed with all its
// 27 lattice translates into a coarse cell list of the cell, then uniform points are tested.
double periodicFraction(const FiberModel& m, double L, long samples)
{
  const double half = 0.5 * L;
  const int nc = std::max(1, static_cast<int>(L / 2.0));
  bench::CapsuleCells cells(half, nc, L / nc);
  for (const Fiber& f : m.fibers)
  {
    for (std::size_t k = 0; k + 1 < f.points.size(); ++k)
    {
      // Wrap the segment's first point into the cell, then try every image.
      Vec3 a = f.points[k], b = f.points[k + 1];
      for (int d = 0; d < 3; ++d)
      {
        const double s = -L * std::floor((a[d] + half) / L);
        a[d] += s;
        b[d] += s;
      }
      const double r = std::max(f.radii[k], f.radii[k + 1]);
      for (int ix = -1; ix <= 1; ++ix)
        for (int iy = -1; iy <= 1; ++iy)
          for (int iz = -1; iz <= 1; ++iz)
          {
            const Vec3 t{ ix * L, iy * L, iz * L };
            cells.add(bench::BenchCapsule{ a + t, b + t, r });
          }
    }
  }
  return cells.hitFraction(samples);
}
} // namespace

int main(int argc, char** argv)
{
  double edge = 30.0;
  std::vector<double> pops{ 1, 2, 3 };
  std::vector<double> phis{ 0.85, 0.72, 0.58 };
  std::vector<double> threads{ 1, 2 };
  int maxSteps = 20000;
  double initScale = 0.0;
  double spread = 0.0;
  bool gamma = false;
  long samples = 1000000;
  int seed = 42;
  double curvature = 4.0;
  double cap = 1e9;
  bench::PushOverrides push;
  double displacement = 0.5;
  bool lattice = false;
  bool uniform = false;
  double radius = 0.0;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (i + 1 >= argc && a != "--gamma" && a != "--lattice" && a != "--uniform")
    {
      std::fprintf(stderr, "missing value after %s\n", a.c_str());
      return 2;
    }
    if (a == "--lattice")
      lattice = true;
    else if (a == "--uniform")
      uniform = true;
    else if (a == "--radius")
      radius = std::atof(argv[++i]);
    else if (a == "--edge")
      edge = std::atof(argv[++i]);
    else if (a == "--pops")
      pops = list(argv[++i]);
    else if (a == "--phi")
      phis = list(argv[++i]);
    else if (a == "--threads")
      threads = list(argv[++i]);
    else if (a == "--max-steps")
      maxSteps = std::atoi(argv[++i]);
    else if (a == "--init-scale")
      initScale = std::atof(argv[++i]);
    else if (a == "--spread")
      spread = std::atof(argv[++i]);
    else if (a == "--gamma")
      gamma = true;
    else if (a == "--samples")
      samples = static_cast<long>(std::atof(argv[++i]));
    else if (a == "--seed")
      seed = std::atoi(argv[++i]);
    else if (a == "--curvature")
      curvature = std::atof(argv[++i]);
    else if (a == "--cap")
      cap = std::atof(argv[++i]);
    else if (a == "--drag")
      push.drag = std::atof(argv[++i]);
    else if (a == "--push-boost")
      push.pushBoost = std::atof(argv[++i]);
    else if (a == "--displacement")
      displacement = std::atof(argv[++i]);
    else if (a == "--overlap-push")
      push.overlapPush = std::atof(argv[++i]);
    else if (a == "--separation-speed")
      push.separationSpeed = std::atof(argv[++i]);
    else if (a == "--max-displacement")
      push.maxDisplacement = std::atof(argv[++i]);
    else
    {
      std::fprintf(stderr, "unknown argument '%s'\n", a.c_str());
      return 2;
    }
  }
  std::printf("seeding: %s, displacement %.2f um\n", lattice ? "Lattice" : "Random", displacement);
  std::printf(
    "| cell [um] | pops | target phi | radii | threads | fibers | links | steps | solve [s] | CPU "
    "[s] | "
    "load after | peak RSS [MB] | solved | collisions | radius scale | phi solver | phi MC "
    "(27 images) | min gap [um] | generate [s] |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (std::size_t k = 0; k < pops.size(); ++k)
  {
    const double phi = phis[std::min(k, phis.size() - 1)];
    for (double t : threads)
    {
      CubeOptions c;
      c.populations = static_cast<int>(pops[k]);
      c.edgeLength = edge;
      c.periodic = true;
      c.displacement = displacement;
      c.volumeFraction = phi;
      c.seed = static_cast<std::uint64_t>(seed);
      c.radiusSpread = spread;
      c.seeding = lattice ? CubeSeeding::Lattice : CubeSeeding::Random;
      c.radiusDistribution = gamma ? RadiusDistribution::Gamma
        : uniform                  ? RadiusDistribution::Uniform
                                   : RadiusDistribution::LogNormal;
      if (gamma || uniform)
        c.fiberRadius = 1.0; // Gamma: α = 1/s², β = s² (µm): s = 0.5 is MEDUSA's α = 4, β = 0.25
      if (radius > 0.0)
        c.fiberRadius = radius;
      const std::string bad = validateCubeOptions(c);
      if (!bad.empty())
      {
        std::printf("error: %s\n", bad.c_str());
        return 1;
      }
      const double g0 = bench::seconds();
      FiberModel m = generateCube(c);
      const double generate = bench::seconds() - g0;
      CollisionSolverOptions o;
      o.segmentLength = 2.0;
      o.minCurvatureRadius = curvature;
      o.maxSteps = maxSteps;
      o.numberOfThreads = static_cast<int>(t);
      o.periodicCell = cubeCell(c);
      o.initialRadiusScale = initScale;
      push.apply(o);
      const double cpu0 = bench::cpuSeconds();
      const double t0 = bench::seconds();
      const CollisionSolverResult r =
        solveCollisions(m, o, [&](double) { return bench::seconds() - t0 < cap; });
      const double seconds = bench::seconds() - t0;
      const double cpu = bench::cpuSeconds() - cpu0;
      double load = -1.0;
      if (FILE* f = std::fopen("/proc/loadavg", "r"))
      {
        if (std::fscanf(f, "%lf", &load) != 1)
          load = -1.0;
        std::fclose(f);
      }
      if (!r.error.empty())
      {
        std::printf("error: %s\n", r.error.c_str());
        continue;
      }
      const double mc = periodicFraction(m, edge, samples);
      const char* radii = spread > 0.0 ? (gamma        ? "gamma"
                                             : uniform ? "uniform"
                                                       : "lognormal")
                                       : "0.8";
      std::printf("| %.0f | %d | %.3f | %s | %d | %zu | %zu | %d | %.1f | %.1f | %.1f | %.0f | "
                  "%d%s | %zu | %.3f | "
                  "%.1f %% | %.1f %% | %.4f | %.2f |\n",
        edge, c.populations, phi, radii, static_cast<int>(t), m.fibers.size(), m.numberOfLinks(),
        r.steps, seconds, cpu, load, bench::peakRssMB(), r.solved ? 1 : 0,
        r.aborted ? " (cap)" : "", r.collisions, r.radiusScale, 100.0 * r.volumeFraction,
        100.0 * mc, r.minGap, generate);
      for (const std::string& w : r.warnings)
        std::printf("  warning: %s\n", w.c_str());
      std::fflush(stdout);
    }
  }
  return 0;
}
