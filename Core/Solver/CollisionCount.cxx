// Collision count and volume fraction of a model, outside a solve (Solver/CollisionSolver.h).
#include "Solver/CollisionSolver.h"

#include "Index/CollisionGrid.h"
#include "Index/PeriodicPairs.h"
#include "Solver/Decomposition.h"
#include "Solver/PairBound.h"
#include "Solver/SolverLinks.h"
#include "Util/MemoryBudget.h"
#include "Util/Threads.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fiberpli
{

std::size_t countCollisions(
  const FiberModel& model, double minimumGap, int numberOfThreads, const PeriodicCell& cell)
{
  std::vector<CapsuleLink> links;
  std::vector<CapsulePair> pairs;
  if (cell.enabled())
  {
    std::vector<char> closed(model.fibers.size(), 0);
    for (std::size_t f = 0; f < model.fibers.size(); ++f)
    {
      Vec3 t;
      closed[f] = isClosedFiber(model.fibers[f], cell, t);
    }
    buildLinks(model, nullptr, resolveThreadCount(numberOfThreads), links, nullptr, &closed);
  }
  else
  {
    buildLinks(model, nullptr, resolveThreadCount(numberOfThreads), links, nullptr);
  }
  const double limit = std::min(packingPairBound(links, minimumGap).pairs,
    std::max(0.0, memoryBudgetBytes()) / CollisionGrid::bytesPerPair());
  const auto maxPairs = static_cast<std::size_t>(limit);
  bool overflow = false;
  if (cell.enabled())
  {
    PeriodicPairs finder;
    if (!finder.findPairs(links, cell, minimumGap, numberOfThreads, pairs, maxPairs, &overflow)
           .empty())
    {
      return std::numeric_limits<std::size_t>::max(); // cell too small for its links: no count
    }
  }
  else
  {
    CollisionGrid grid;
    overflow = !grid.findPairs(links, minimumGap, numberOfThreads, pairs, maxPairs);
  }
  return overflow ? maxPairs + 1 : pairs.size();
}

double cellVolumeFraction(const FiberModel& model, const PeriodicCell& cell, Comm* comm)
{
  const double volume = capsuleVolume(model, comm);
  if (cell.enabled())
  {
    return volume / cell.volume();
  }
  Vec3 lo, hi;
  const bool any = modelBounds(model, true, lo, hi);
  if (comm)
  {
    std::vector<double> m(6, -HUGE_VAL);
    for (int d = 0; any && d < 3; ++d)
    {
      m[static_cast<std::size_t>(d)] = -lo[d];
      m[static_cast<std::size_t>(3 + d)] = hi[d];
    }
    comm->max(m);
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = -m[static_cast<std::size_t>(d)];
      hi[d] = m[static_cast<std::size_t>(3 + d)];
    }
    if (!(m[3] > -HUGE_VAL))
    {
      return 0.0;
    }
  }
  else if (!any)
  {
    return 0.0;
  }
  const Vec3 e = hi - lo;
  return e.x * e.y * e.z > 0.0 ? volume / (e.x * e.y * e.z) : 0.0;
}

} // namespace fiberpli
