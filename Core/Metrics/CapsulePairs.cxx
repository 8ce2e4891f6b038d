#include "Metrics/CapsulePairs.h"

#include "Util/Threads.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace fiberpli
{
namespace
{

/// Capsule midpoints binned into cells of edge >= `reach` (counting sort), so that every pair whose
/// midpoints are at most `reach` apart lies in the same or a neighbouring cell.
class MidpointHash
{
public:
  MidpointHash(const std::vector<Vec3>& mid, double reach, const PeriodicCell& cell)
    : cell_(cell)
  {
    if (cell.enabled())
    {
      lo_ = cell.lo;
      extent_ = cell.edge();
    }
    else
    {
      lo_ = hi_ = mid.empty() ? Vec3{} : mid[0];
      for (const Vec3& m : mid)
      {
        for (int i = 0; i < 3; ++i)
        {
          lo_[i] = std::min(lo_[i], m[i]);
          hi_[i] = std::max(hi_[i], m[i]);
        }
      }
      extent_ = hi_ - lo_;
    }
    // Never more cells than capsules: a coarser grid is still correct, only slower. Counted in
    // double with each axis capped at the capsule count, so that spread-out models (extent/reach
    // ~1e7 per axis) cannot overflow the product.
    const double cap = static_cast<double>(mid.size()) + 1.0;
    double edge = reach;
    for (;;)
    {
      double total = 1.0;
      for (int i = 0; i < 3; ++i)
      {
        double k = std::floor(extent_[i] / edge);
        k = k >= 1.0 ? std::min(k, cap) : 1.0; // also NaN (zero extent and reach) → 1
        n_[i] = static_cast<std::int64_t>(k);
        total *= k;
      }
      if (total <= cap)
      {
        break;
      }
      edge *= 1.5;
    }
    for (int i = 0; i < 3; ++i)
    {
      edge_[i] = n_[i] > 1 ? extent_[i] / static_cast<double>(n_[i])
                           : std::numeric_limits<double>::infinity();
    }
    start_.assign(static_cast<std::size_t>(n_[0] * n_[1] * n_[2] + 1), 0);
    std::vector<std::int64_t> cellOf(mid.size());
    for (std::size_t c = 0; c < mid.size(); ++c)
    {
      cellOf[c] = index(coords(mid[c]));
      ++start_[static_cast<std::size_t>(cellOf[c]) + 1];
    }
    for (std::size_t k = 1; k < start_.size(); ++k)
    {
      start_[k] += start_[k - 1];
    }
    order_.resize(mid.size());
    std::vector<std::int64_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t c = 0; c < mid.size(); ++c)
    {
      order_[static_cast<std::size_t>(fill[static_cast<std::size_t>(cellOf[c])]++)] = c;
    }
  }

  /// True when the grid is a single cell: every pair is compared.
  bool single() const { return n_[0] * n_[1] * n_[2] == 1; }

  std::array<std::int64_t, 3> coords(const Vec3& p) const
  {
    std::array<std::int64_t, 3> c{};
    for (int i = 0; i < 3; ++i)
    {
      std::int64_t k =
        n_[i] > 1 ? static_cast<std::int64_t>(std::floor((p[i] - lo_[i]) / edge_[i])) : 0;
      if (cell_.enabled())
      {
        k = ((k % n_[i]) + n_[i]) % n_[i];
      }
      c[static_cast<std::size_t>(i)] = std::clamp<std::int64_t>(k, 0, n_[i] - 1);
    }
    return c;
  }

  std::int64_t index(const std::array<std::int64_t, 3>& c) const
  {
    return (c[2] * n_[1] + c[1]) * n_[0] + c[0];
  }

  /// The distinct cells around c (itself included), wrapped in a periodic cell, written into
  /// `cells` in ascending order (no allocation: this runs once per capsule); returns their count.
  std::size_t neighbours(
    const std::array<std::int64_t, 3>& c, std::array<std::int64_t, 27>& cells) const
  {
    std::size_t count = 0;
    for (std::int64_t dz = -1; dz <= 1; ++dz)
    {
      for (std::int64_t dy = -1; dy <= 1; ++dy)
      {
        for (std::int64_t dx = -1; dx <= 1; ++dx)
        {
          std::array<std::int64_t, 3> k = { c[0] + dx, c[1] + dy, c[2] + dz };
          bool inside = true;
          for (std::size_t i = 0; i < 3; ++i)
          {
            if (cell_.enabled())
            {
              k[i] = ((k[i] % n_[i]) + n_[i]) % n_[i];
            }
            inside = inside && k[i] >= 0 && k[i] < n_[i];
          }
          if (inside)
          {
            cells[count++] = index(k);
          }
        }
      }
    }
    std::sort(cells.begin(), cells.begin() + static_cast<std::ptrdiff_t>(count));
    return static_cast<std::size_t>(
      std::unique(cells.begin(), cells.begin() + static_cast<std::ptrdiff_t>(count)) -
      cells.begin());
  }

  template <class F>
  void forEachIn(std::int64_t cellIndex, F&& f) const
  {
    const auto c = static_cast<std::size_t>(cellIndex);
    for (std::int64_t k = start_[c]; k < start_[c + 1]; ++k)
    {
      f(order_[static_cast<std::size_t>(k)]);
    }
  }

private:
  PeriodicCell cell_;
  Vec3 lo_, hi_, extent_, edge_;
  std::int64_t n_[3] = { 1, 1, 1 };
  std::vector<std::int64_t> start_;
  std::vector<std::size_t> order_;
};

struct Pass
{
  std::int64_t collisions = 0;
  double minGap = std::numeric_limits<double>::infinity();
  bool complete = false; ///< every pair was compared
  bool aborted = false;
};

/// One sweep with a hash whose cells cover midpoint distances up to 2·robustReach + margin: every
/// pair of ordinary capsules with a gap <= margin is compared. Oversize capsules (reach above
/// robustReach: a few long links) stay out of the hash and are compared with every capsule, as
/// the solver's collision grid keeps its oversize list, so one long link cannot coarsen the grid.
Pass sweep(const CapsuleSet& set, const std::vector<Vec3>& mid, const std::vector<double>& reach,
  double robustReach, double margin, const PeriodicCell& cell, int threads,
  const ProgressFn& progress)
{
  const std::vector<Capsule>& caps = set.capsules;
  const MidpointHash hash(mid, 2.0 * robustReach + margin, cell);
  std::vector<std::size_t> oversize;
  for (std::size_t c = 0; c < caps.size(); ++c)
  {
    if (reach[c] > robustReach)
    {
      oversize.push_back(c);
    }
  }
  const auto isOversize = [&](std::size_t c) { return reach[c] > robustReach; };
  Pass pass;
  pass.complete = hash.single();
  const auto compare = [&](std::size_t i, std::size_t j, std::int64_t& collisions, double& minGap)
  {
    const Capsule &p = caps[i], &q = caps[j];
    // The lattice vector that brings q's midpoint nearest to p's (zero without a cell).
    const Vec3 shift = cell.enabled() ? cell.imageShift(mid[j] - mid[i]) : Vec3{};
    // Lower bound on the gap from the midpoints: skip pairs that can change neither result.
    const double bound = distance(mid[i], mid[j] + shift) - reach[i] - reach[j];
    if ((bound >= 0.0 && bound >= minGap) || chainNeighbours(p, q, set))
    {
      return;
    }
    const double gap = segmentDistance(p.a, p.b, q.a + shift, q.b + shift) - p.r - q.r;
    collisions += gap < 0.0 ? 1 : 0;
    minGap = std::min(minGap, gap);
  };
  const auto n = static_cast<std::int64_t>(caps.size());
  const auto work = n + static_cast<std::int64_t>(oversize.size());
  const std::int64_t block = 4096;
  for (std::int64_t begin = 0; begin < n && !pass.aborted; begin += block)
  {
    const std::int64_t end = std::min(n, begin + block);
    std::int64_t collisions = 0;
    double minGap = pass.minGap;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 64) reduction(+ : collisions) reduction(min : minGap)
    for (std::int64_t i = begin; i < end; ++i)
    {
      const auto pi = static_cast<std::size_t>(i);
      if (isOversize(pi))
      {
        continue;
      }
      std::array<std::int64_t, 27> cells;
      const std::size_t count = hash.neighbours(hash.coords(mid[pi]), cells);
      for (std::size_t k = 0; k < count; ++k)
      {
        hash.forEachIn(cells[k],
          [&](std::size_t j)
          {
            if (j > pi && !isOversize(j))
            {
              compare(pi, j, collisions, minGap);
            }
          });
      }
    }
    pass.collisions += collisions;
    pass.minGap = std::min(pass.minGap, minGap);
    pass.aborted = !reportProgress(progress, static_cast<double>(end) / static_cast<double>(work));
  }
  for (std::size_t o = 0; o < oversize.size() && !pass.aborted; ++o)
  {
    const std::size_t i = oversize[o];
    std::int64_t collisions = 0;
    double minGap = pass.minGap;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : collisions) reduction(min : minGap)
    for (std::int64_t j = 0; j < n; ++j)
    {
      const auto pj = static_cast<std::size_t>(j);
      if (pj != i && (!isOversize(pj) || pj > i))
      {
        compare(i, pj, collisions, minGap);
      }
    }
    pass.collisions += collisions;
    pass.minGap = std::min(pass.minGap, minGap);
    pass.aborted = !reportProgress(progress,
      static_cast<double>(n + static_cast<std::int64_t>(o) + 1) / static_cast<double>(work));
  }
  return pass;
}

} // namespace

PairResult compareCapsulePairs(
  const CapsuleSet& set, const PeriodicCell& cell, int numberOfThreads, const ProgressFn& progress)
{
  PairResult result;
  result.minGap = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Capsule>& caps = set.capsules;
  if (caps.size() < 2)
  {
    return result;
  }
  // reach: how far a capsule's surface extends from its midpoint.
  std::vector<Vec3> mid(caps.size());
  std::vector<double> reach(caps.size());
  for (std::size_t c = 0; c < caps.size(); ++c)
  {
    mid[c] = 0.5 * (caps[c].a + caps[c].b);
    reach[c] = 0.5 * distance(caps[c].a, caps[c].b) + caps[c].r;
  }
  // The hash is sized from a robust reach: twice the 99th percentile, so that at most ~1 % of the
  // capsules (the long links) go to the oversize list.
  std::vector<double> sorted(reach);
  const std::size_t q = std::min(sorted.size() - 1, (sorted.size() * 99) / 100);
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(q), sorted.end());
  const double robustReach = 2.0 * sorted[q];
  const int threads = resolveThreadCount(numberOfThreads);
  double margin = robustReach;
  for (int round = 0;; ++round)
  {
    // Later rounds only widen the search for the smallest gap; show them as the last tenth.
    const double from = round == 0 ? 0.0 : 0.9, to = round == 0 ? 0.9 : 1.0;
    const Pass pass = sweep(set, mid, reach, robustReach, margin, cell, threads,
      [&](double f) { return reportProgress(progress, from + (to - from) * f); });
    if (pass.aborted)
    {
      result.aborted = true;
      return result;
    }
    if (round == 0)
    {
      result.collisions = pass.collisions; // every overlapping pair is within any margin >= 0
    }
    if (pass.minGap <= margin || pass.complete)
    {
      if (std::isfinite(pass.minGap))
      {
        result.minGap = pass.minGap;
      }
      return result;
    }
    margin *= 4.0;
  }
}

} // namespace fiberpli
