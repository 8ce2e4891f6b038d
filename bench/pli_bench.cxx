// PLI simulation benchmark (bench/README.md "3D-PLI simulation" and its fastPLI table): the
// 2-population 1000-fiber cube, section x, y in [-15, 15] um, 60 um thick, axon core + radial
// myelin, 9 rotations, 5 views, pixel 1 um, blur 0.71 px, gain 3.
// Usage: pli_bench [voxel_um=0.25] [threads=1] [model.dat]
// With a model path: read it; if it does not exist, generate the cube, solve it with the Core
// collision solver (defaults, MinCurvatureRadius 4) and cache it there. Without a path the cube is
// generated and NOT solved (overlaps remain); the output says so. Run one configuration per
// process: peak RSS is per process.
#include "IO/FiberFile.h"
#include "PLI/PLIPipeline.h"
#include "Solver/CollisionSolver.h"
#include "Tissue/CubeGenerator.h"

#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

using namespace fiberpli;

namespace
{
// The reference model (bench/README.md): generateCube (2 populations, 1000 fibers, seed 42) solved
// by the Core collision solver with default options and MinCurvatureRadius 4 (bit-identical for any
// thread count), cached as fastPLI .dat so the ~2.5 min solve runs once.
bool solvedCube(const std::string& cache, FiberModel& model, std::string& source)
{
  FiberReadResult r = readFiberFile(cache, 1.0);
  if (r.ok())
  {
    model = std::move(r.model);
    source = "solved 2-population cube read from " + cache;
    return true;
  }
  CubeOptions c;
  c.populations = 2;
  c.numberOfFibers = 1000;
  c.seed = 42;
  model = generateCube(c);
  CollisionSolverOptions so;
  so.minCurvatureRadius = 4.0;
  so.numberOfThreads = 0;
  const auto t0 = std::chrono::steady_clock::now();
  const CollisionSolverResult res = solveCollisions(model, so);
  const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!res.error.empty())
  {
    std::fprintf(stderr, "solver error: %s\n", res.error.c_str());
    return false;
  }
  std::printf(
    "solved the cube: %d steps, %zu collisions left, %.1f s (all threads); cached in %s\n",
    res.steps, res.collisions, t, cache.c_str());
  const std::string err = writeFiberFile(cache, model);
  if (!err.empty())
    std::fprintf(stderr, "warning: cannot cache the model: %s\n", err.c_str());
  source = std::string("generateCube 2 populations, 1000 fibers, seed 42, solved (") +
    (res.solved ? "0" : std::to_string(res.collisions)) + " collisions left), cached in " + cache;
  return true;
}
} // namespace

int main(int argc, char** argv)
{
  const double voxel = argc > 1 ? std::atof(argv[1]) : 0.25;
  const int threads = argc > 2 ? std::atoi(argv[2]) : 1;
  FiberModel model;
  std::string source;
  if (argc > 3)
  {
    if (!solvedCube(argv[3], model, source))
      return 1;
  }
  else
  {
    CubeOptions c;
    c.populations = 2;
    c.numberOfFibers = 1000;
    c.seed = 42;
    model = generateCube(c);
    source = "generateCube 2 populations, 1000 fibers, seed 42, UNSOLVED (no collision solver in "
             "this build)";
  }

  pli::PLIOptions o;
  const double voi[6] = { -15, 15, -15, 15, -30, 30 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  o.voxelSize = voxel;
  o.pixelSize = 1.0;
  o.numberOfRotations = 9;
  o.tiltAngle = 5.5;
  o.layers = "0.666 0 5 b; 1 0.004 1 r";
  o.opticalSigma = 0.71;
  o.noiseGain = 3;
  o.seed = 1;
  o.numberOfThreads = threads;

  const auto t0 = std::chrono::steady_clock::now();
  pli::PLIImage img;
  const fiberpli::Status st = pli::runPLI(model, o, fiberpli::GridRange{}, img);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!st.ok())
  {
    std::fprintf(stderr, "error: %s\n", st.error.c_str());
    return 1;
  }
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  const double rssMB = static_cast<double>(ru.ru_maxrss) / 1024.0;
  const auto& n = img.plan.lattice.n;
  const double voxels = static_cast<double>(n[0] * n[1] * n[2]);
  const double views = static_cast<double>(img.plan.views.size());

  // fastPLI on the solved cube (bench/README.md): tissue s, simulate s, peak RSS MB.
  double refTissue = 0, refSim = 0, refRss = 0;
  if (std::abs(voxel - 0.1) < 1e-9)
  {
    refTissue = threads == 1 ? 5.08 : 2.97;
    refSim = threads == 1 ? 49.96 : 27.20;
    refRss = 1223;
  }
  else if (std::abs(voxel - 0.25) < 1e-9)
  {
    refTissue = threads == 1 ? 0.43 : 0.16;
    refSim = threads == 1 ? 3.20 : 1.73;
    refRss = 259;
  }
  const double tVox = img.voxeliseCpuSeconds / threads, tProp = img.propagateCpuSeconds / threads;
  std::printf("model: %s (%zu fibers)\n", source.c_str(), model.fibers.size());
  std::printf("grid %lldx%lldx%lld voxels of %.3f um, %d rotations, %.0f views, threads %d\n",
    static_cast<long long>(n[0]), static_cast<long long>(n[1]), static_cast<long long>(n[2]), voxel,
    o.numberOfRotations, views, threads);
  std::printf("voxelise   %.3f s (CPU %.3f s over threads, incl. tile halos)\n", tVox,
    img.voxeliseCpuSeconds);
  std::printf("propagate  %.3f s (CPU %.3f s), %lld ray steps\n", tProp, img.propagateCpuSeconds,
    static_cast<long long>(img.raySteps));
  std::printf("optics     %.3f s\n", img.opticsSeconds);
  std::printf("total wall %.3f s\n", wall);
  std::printf("voxel-views per second (propagation, wall) %.3g\n", voxels * views / tProp);
  std::printf("peak RSS %.1f MB (tile buffers %zu B/voxel, estimate %.1f MB)\n", rssMB,
    img.plan.bytesPerVoxel, static_cast<double>(img.peakTissueBytes) / 1048576.0);
  if (!img.views.empty())
  {
    double mean = 0;
    for (double v : img.views[0].data)
      mean += v / static_cast<double>(img.views[0].data.size());
    std::printf("mean untilted intensity %.2f, empty section %d, warnings %zu\n", mean,
      img.emptySection ? 1 : 0, st.warnings.size());
  }
  if (refSim > 0)
    std::printf("ratio to fastPLI reference: voxelise %.2f, propagate %.2f, total %.2f, RSS %.2f "
                "(goal <= 0.5 time, <= 0.25 RSS)\n",
      tVox / refTissue, tProp / refSim, (tVox + tProp) / (refTissue + refSim), rssMB / refRss);
  return 0;
}
