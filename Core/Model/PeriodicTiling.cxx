#include "Model/PeriodicTiling.h"

#include "Util/MemoryBudget.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace fiberpli
{

namespace
{
// Lattice indices [first, last] along one axis for which [lo, hi] + k·e overlaps [bmin, bmax].
std::array<long, 2> shifts(double lo, double hi, double bmin, double bmax, double e)
{
  return { static_cast<long>(std::ceil((bmin - hi) / e)), static_cast<long>(std::floor((bmax - lo) / e)) };
}
} // namespace

std::string tileModel(FiberModel& model, const PeriodicCell& cell, const double box[6])
{
  const Vec3 e = cell.edge();
  std::int64_t maxId = 0;
  for (const Fiber& f : model.fibers)
  {
    maxId = std::max(maxId, f.id);
  }
  // Pass 1: the ranges per fiber and the point count, checked before anything is copied.
  std::vector<std::array<std::array<long, 2>, 3>> ranges(model.fibers.size());
  double points = 0.0;
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fib = model.fibers[f];
    Vec3 lo{ HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi{ -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
    for (std::size_t i = 0; i < fib.size(); ++i)
    {
      for (int d = 0; d < 3; ++d)
      {
        lo[d] = std::min(lo[d], fib.points[i][d] - fib.radii[i]);
        hi[d] = std::max(hi[d], fib.points[i][d] + fib.radii[i]);
      }
    }
    double copies = 1.0;
    for (int d = 0; d < 3; ++d)
    {
      ranges[f][d] = shifts(lo[d], hi[d], box[2 * d], box[2 * d + 1], e[d]);
      copies *= std::max(0.0, static_cast<double>(ranges[f][d][1] - ranges[f][d][0] + 1));
    }
    points += copies * static_cast<double>(fib.size());
  }
  const std::string tooBig = checkMemoryBudget(points * 64.0, "the periodic tiling of the volume of interest");
  if (!tooBig.empty())
  {
    return tooBig;
  }
  FiberModel tiled;
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fib = model.fibers[f];
    const auto& r = ranges[f];
    for (long i = r[0][0]; i <= r[0][1]; ++i)
      for (long j = r[1][0]; j <= r[1][1]; ++j)
        for (long k = r[2][0]; k <= r[2][1]; ++k)
        {
          Fiber copy = fib;
          const Vec3 t{ static_cast<double>(i) * e.x, static_cast<double>(j) * e.y, static_cast<double>(k) * e.z };
          for (Vec3& p : copy.points)
          {
            p += t;
          }
          // A distinct id per translate; the cell's own copy keeps its id.
          const std::int64_t serial = (i == 0 && j == 0 && k == 0) ? 0 : 1 + static_cast<std::int64_t>(tiled.fibers.size());
          copy.id = fib.id + serial * (maxId + 1);
          tiled.fibers.push_back(std::move(copy));
        }
  }
  model = std::move(tiled);
  return {};
}

} // namespace fiberpli
