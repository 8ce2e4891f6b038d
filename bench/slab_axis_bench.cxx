// The distributed solver's boxes on a section strip (bench/README.md, "Slab axis on a section
// strip"): Examples/mpi_section.py's periodic cell (2 populations along x and y, 30 µm, volume
// fraction 0.3, seed 42) tiled along x and clipped to a thickness (each tile's fibers cut at its
// faces), solved for a few steps on 2 and 4 thread ranks (Core/Testing/ThreadComm.h, as the Core
// tests run the distributed solver). Prints the box grid the solver chooses and per rank: owned
// fibers, peak held links (own + halo), peak halo links, partners and the bytes sent per step,
// against the share of links.
// Usage: fiberpli_slab_axis_bench [steps 20] [cells along x 16] [thickness 10 (um)]
#include "PeriodicReference.h"
#include "Solver/CollisionSolver.h"
#include "Solver/Decomposition.h"
#include "ThreadComm.h"
#include "Tissue/CubeGenerator.h"

#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace fiberpli;

namespace
{
// The cell's fibers copied into `cells` tiles along x, each copy cut into the runs of points
// inside its tile of the strip [-15 + 30 t, 15 + 30 t] × [-15, 15] × [-thickness/2, thickness/2].
FiberModel strip(const FiberModel& cell, int cells, double thickness)
{
  const double half = 15.0;
  FiberModel out;
  for (int t = 0; t < cells; ++t)
  {
    for (const Fiber& f : cell.fibers)
    {
      Fiber run;
      const auto flush = [&]()
      {
        if (run.points.size() >= 2)
        {
          run.id = static_cast<std::int64_t>(out.fibers.size());
          out.fibers.push_back(run);
        }
        run = Fiber();
      };
      for (std::size_t i = 0; i < f.points.size(); ++i)
      {
        const Vec3& p = f.points[i];
        if (p.x < -half || p.x >= half || p.y < -half || p.y >= half || 2.0 * p.z < -thickness ||
          2.0 * p.z >= thickness)
        {
          flush();
          continue;
        }
        run.points.push_back({ p.x + 2.0 * half * t, p.y, p.z });
        run.radii.push_back(f.radii[i]);
      }
      flush();
    }
  }
  return out;
}
} // namespace

int main(int argc, char** argv)
{
  const int steps = argc > 1 ? std::atoi(argv[1]) : 20;
  const int cells = argc > 2 ? std::atoi(argv[2]) : 16;
  const double thickness = argc > 3 ? std::atof(argv[3]) : 10.0;
  const FiberModel model =
    strip(generateCube(fiberpli_test::periodicCube(2, 30.0, 0.3, 42)), cells, thickness);
  std::size_t links = 0;
  for (const Fiber& f : model.fibers)
    links += f.points.size() - 1;
  std::printf("strip %d x 30 x %g um: %zu fibers, %zu links\n", 30 * cells, thickness,
    model.fibers.size(), links);
  CollisionSolverOptions o;
  o.maxSteps = steps;
  o.numberOfThreads = 1;
  for (int ranks : { 2, 4 })
  {
    std::vector<FiberModel> pieces(static_cast<std::size_t>(ranks));
    std::vector<CollisionSolverResult> result(pieces.size());
    int grid[3] = { 1, 1, 1 };
    for (std::size_t r = 0; r < pieces.size(); ++r)
    {
      for (std::size_t f = model.fibers.size() * r / pieces.size();
           f < model.fibers.size() * (r + 1) / pieces.size(); ++f)
        pieces[r].fibers.push_back(model.fibers[f]);
    }
    fiberpli_test::runRanks(ranks,
      [&](Comm& comm)
      {
        const std::size_t r = static_cast<std::size_t>(comm.rank());
        const BoxLayout layout =
          BoxLayout::make(pieces[r], PeriodicCell{}, comm); // the solver's own choice
        if (r == 0)
          for (int d = 0; d < 3; ++d)
            grid[d] = layout.boxes(d);
        result[r] = solveCollisions(pieces[r], o, {}, {}, &comm);
      });
    std::printf("%d ranks, boxes %d x %d x %d, %d steps, share %.0f links:", ranks, grid[0],
      grid[1], grid[2], result[0].steps, static_cast<double>(links) / ranks);
    for (std::size_t r = 0; r < result.size(); ++r)
    {
      const CollisionSolverResult& s = result[r];
      std::printf(" [%zu fibers, held %zu, halo %zu, %zu partners, %.0f B/step]", s.rankFibers,
        s.peakHeldLinks, s.peakHaloLinks, s.peakPartners, s.haloBytesPerStep);
    }
    std::printf("\n");
  }
  return 0;
}
