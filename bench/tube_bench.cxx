// Tube meshing speed: N fibers of 30 points (1000 of them should take well under a second),
// 12 sides, capped; 1 and 2 threads; prints seconds, triangles per second and peak RSS.
#include "BenchUtil.h"
#include "Mesh/TubeMesher.h"
#include "Tissue/CubeGenerator.h"

#include <cstdio>
#include <cstdlib>

int main(int argc, char* argv[])
{
  using namespace fiberpli;
  const int fibers = argc > 1 ? std::atoi(argv[1]) : 1000;
  CubeOptions cube;
  cube.populations = 3;
  cube.numberOfFibers = fibers;
  cube.segmentLength = 2.0;
  cube.edgeLength = 58.0; // 30 points per fiber
  const FiberModel model = generateCube(cube);
  std::printf("fibers %d, points per fiber %zu\n", fibers, model.fibers[0].points.size());
  for (int threads : { 1, 2 })
  {
    TubeOptions options;
    options.numberOfThreads = threads;
    const double t0 = bench::seconds();
    const TubeMesh mesh = meshTubes(model, options);
    const double dt = bench::seconds() - t0;
    std::printf("threads %d: %.4f s, %zu triangles, %.1f M triangles/s, peak RSS %.0f MB\n",
      threads, dt, mesh.numberOfTriangles(), mesh.numberOfTriangles() / dt / 1e6,
      bench::peakRssMB());
  }
  return 0;
}
