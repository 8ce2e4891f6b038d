#include "Model/PeriodicTiling.h"

#include "Util/MemoryBudget.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace fiberpli
{

namespace
{
using ShiftRanges = std::array<std::array<long, 2>, 3>;

// Lattice indices [first, last] along one axis for which [lo, hi] + k·e overlaps [bmin, bmax].
std::array<long, 2> shifts(double lo, double hi, double bmin, double bmax, double e)
{
  return { static_cast<long>(std::ceil((bmin - hi) / e)),
    static_cast<long>(std::floor((bmax - lo) / e)) };
}

// The translates of `fib` whose bounds, grown by the radii, overlap box (tileModel's rule).
ShiftRanges tilingRanges(const Fiber& fib, const Vec3& e, const double box[6])
{
  Vec3 lo{ HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi{ -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (std::size_t i = 0; i < fib.size(); ++i)
  {
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = std::min(lo[d], fib.points[i][d] - fib.radii[i]);
      hi[d] = std::max(hi[d], fib.points[i][d] + fib.radii[i]);
    }
  }
  ShiftRanges r;
  for (int d = 0; d < 3; ++d)
  {
    r[d] = shifts(lo[d], hi[d], box[2 * d], box[2 * d + 1], e[d]);
  }
  return r;
}

// The shifts (one more on each side, against rounding) of link k whose bounds, grown as
// linkReaches grows them, overlap the reach box.
ShiftRanges linkShiftRanges(const Fiber& fib, std::size_t k, const Vec3& e, const TileReach& reach)
{
  const double grow = reach.radiusScale * fib.linkRadius(k);
  ShiftRanges r;
  for (int d = 0; d < 3; ++d)
  {
    const double lo = std::min(fib.points[k][d], fib.points[k + 1][d]) - grow;
    const double hi = std::max(fib.points[k][d], fib.points[k + 1][d]) + grow;
    const std::array<long, 2> s = shifts(lo, hi, reach.box[2 * d], reach.box[2 * d + 1], e[d]);
    r[d] = { s[0] - 1, s[1] + 1 };
  }
  return r;
}

// The tiling's ranges, narrowed (when reach is given) to the hull of the links' shift ranges;
// linkReaches then decides per translate.
ShiftRanges candidateRanges(
  const Fiber& fib, const Vec3& e, const double box[6], const TileReach* reach)
{
  ShiftRanges r = tilingRanges(fib, e, box);
  if (reach)
  {
    ShiftRanges hull{ { { 0, -1 }, { 0, -1 }, { 0, -1 } } };
    for (std::size_t k = 0; k + 1 < fib.size(); ++k)
    {
      const ShiftRanges s = linkShiftRanges(fib, k, e, *reach);
      for (int d = 0; d < 3; ++d)
      {
        hull[d] = k == 0
          ? s[d]
          : std::array<long, 2>{ std::min(hull[d][0], s[d][0]), std::max(hull[d][1], s[d][1]) };
      }
    }
    for (int d = 0; d < 3; ++d)
    {
      r[d] = { std::max(r[d][0], hull[d][0]), std::min(r[d][1], hull[d][1]) };
    }
  }
  return r;
}

Vec3 translation(long i, long j, long k, const Vec3& e)
{
  return { static_cast<double>(i) * e.x, static_cast<double>(j) * e.y,
    static_cast<double>(k) * e.z };
}
} // namespace

std::string tileModel(
  FiberModel& model, const PeriodicCell& cell, const double box[6], const TileReach* reach)
{
  const Vec3 e = cell.edge();
  std::int64_t maxId = 0;
  for (const Fiber& f : model.fibers)
  {
    maxId = std::max(maxId, f.id);
  }
  auto kept = [&](const Fiber& fib, long i, long j, long k)
  { return !reach || linkReaches(fib, *reach, translation(i, j, k, e)); };
  // Pass 1: the ranges per fiber and the point count, checked before anything is copied.
  std::vector<ShiftRanges> ranges(model.fibers.size());
  double points = 0.0;
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fib = model.fibers[f];
    const ShiftRanges& r = ranges[f] = candidateRanges(fib, e, box, reach);
    double copies = 1.0;
    for (int d = 0; d < 3; ++d)
    {
      copies *= std::max(0.0, static_cast<double>(r[d][1] - r[d][0] + 1));
    }
    if (reach && copies > 0.0)
    {
      copies = 0.0;
      for (long i = r[0][0]; i <= r[0][1]; ++i)
        for (long j = r[1][0]; j <= r[1][1]; ++j)
          for (long k = r[2][0]; k <= r[2][1]; ++k)
            copies += kept(fib, i, j, k) ? 1.0 : 0.0;
    }
    points += copies * static_cast<double>(fib.size());
  }
  const std::string tooBig =
    checkMemoryBudget(points * 64.0, "the periodic tiling of the volume of interest");
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
          if (!kept(fib, i, j, k))
          {
            continue;
          }
          Fiber copy = fib;
          const Vec3 t = translation(i, j, k, e);
          for (Vec3& p : copy.points)
          {
            p += t;
          }
          // A distinct id per translate; the cell's own copy keeps its id.
          const std::int64_t serial =
            (i == 0 && j == 0 && k == 0) ? 0 : 1 + static_cast<std::int64_t>(tiled.fibers.size());
          copy.id = fib.id + serial * (maxId + 1);
          tiled.fibers.push_back(std::move(copy));
        }
  }
  model = std::move(tiled);
  return {};
}

bool periodicTranslateReaches(const Fiber& fib, const TileReach& reach)
{
  if (reach.empty() || !reach.cell.enabled())
  {
    return false;
  }
  const Vec3 e = reach.cell.edge();
  const ShiftRanges tiling = tilingRanges(fib, e, reach.tiling);
  for (std::size_t k = 0; k + 1 < fib.size(); ++k)
  {
    const ShiftRanges s = linkShiftRanges(fib, k, e, reach);
    bool some = true;
    for (int d = 0; d < 3 && some; ++d)
    {
      some = std::max(s[d][0], tiling[d][0]) <= std::min(s[d][1], tiling[d][1]);
    }
    if (some)
    {
      return true;
    }
  }
  return false;
}

std::string tileSection(
  FiberModel& model, const PeriodicCell& cell, const double volume[6], const TileReach* reach)
{
  return tileModel(model, cell, volume, reach);
}

void sectionTiling(TileReach& reach, const PeriodicCell& cell, const double volume[6])
{
  reach.periodic = true;
  reach.cell = cell;
  std::copy(volume, volume + 6, reach.tiling);
}

} // namespace fiberpli
