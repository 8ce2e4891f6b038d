#include "Metrics/CapsuleCells.h"

#include "Util/MemoryBudget.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{
namespace
{

std::int64_t wrap(std::int64_t k, std::int64_t n)
{
  return ((k % n) + n) % n;
}

} // namespace

CapsuleCells::CapsuleCells(
  const CapsuleSet& set, const Vec3& lo, const Vec3& hi, const PeriodicCell& cell)
  : set_(set)
  , lo_(lo)
  , periodic_(cell.enabled())
{
  const Vec3 size = hi - lo;
  // Cells about one capsule wide (the 99th percentile, so that a few long links do not make
  // the cells coarse and every query scan all capsules; a long link is merely listed in more
  // cells), but never more than 4 per capsule or 2^24 in all.
  std::vector<double> widths;
  widths.reserve(set.capsules.size());
  for (const Capsule& c : set.capsules)
  {
    widths.push_back(distance(c.a, c.b) + 2.0 * c.r);
  }
  double reach = 0.0;
  if (!widths.empty())
  {
    const std::size_t q = std::min(widths.size() - 1, (widths.size() * 99) / 100);
    std::nth_element(widths.begin(), widths.begin() + static_cast<std::ptrdiff_t>(q), widths.end());
    reach = widths[q];
  }
  const double volume = size.x * size.y * size.z;
  const double cap = std::min(4.0 * static_cast<double>(set.capsules.size()) + 1.0, 16777216.0);
  const double edge = std::max(reach, std::cbrt(volume / cap));
  for (int i = 0; i < 3; ++i)
  {
    n_[i] = std::max<std::int64_t>(1, static_cast<std::int64_t>(size[i] / edge));
    edge_[i] = size[i] / static_cast<double>(n_[i]);
  }
  // The cells each capsule's box covers; entries counted before any is stored (a long
  // unwrapped fiber in a periodic cell covers very many).
  const auto cover = [&](const Capsule& cap, std::int64_t range[3][2])
  {
    for (int i = 0; i < 3; ++i)
    {
      range[i][0] = static_cast<std::int64_t>(
        std::floor((std::min(cap.a[i], cap.b[i]) - cap.r - lo[i]) / edge_[i]));
      range[i][1] = static_cast<std::int64_t>(
        std::floor((std::max(cap.a[i], cap.b[i]) + cap.r - lo[i]) / edge_[i]));
      if (!periodic_)
      {
        range[i][0] = std::max<std::int64_t>(range[i][0], 0);
        range[i][1] = std::min<std::int64_t>(range[i][1], n_[i] - 1);
      }
      if (range[i][0] > range[i][1])
      {
        return false;
      }
    }
    return true;
  };
  const double cells = static_cast<double>(n_[0] * n_[1] * n_[2]);
  double entries = 0.0;
  for (const Capsule& cap : set.capsules)
  {
    std::int64_t range[3][2];
    if (cover(cap, range))
    {
      entries += static_cast<double>(range[0][1] - range[0][0] + 1) *
        static_cast<double>(range[1][1] - range[1][0] + 1) *
        static_cast<double>(range[2][1] - range[2][0] + 1);
    }
  }
  // Entries are held twice (per-cell lists, then the flat copy).
  error_ = checkMemoryBudget(2.0 * entries * sizeof(LayerEntry) +
      cells * (sizeof(std::vector<LayerEntry>) + sizeof(std::size_t)),
    "FiberMetrics MonteCarlo volume fraction");
  if (!error_.empty())
  {
    return;
  }
  std::vector<std::vector<LayerEntry>> lists(static_cast<std::size_t>(cells));
  for (std::size_t c = 0; c < set.capsules.size(); ++c)
  {
    const Capsule& cap = set.capsules[c];
    std::int64_t range[3][2];
    if (!cover(cap, range))
    {
      continue;
    }
    for (std::int64_t k = range[2][0]; k <= range[2][1]; ++k)
    {
      for (std::int64_t j = range[1][0]; j <= range[1][1]; ++j)
      {
        for (std::int64_t i = range[0][0]; i <= range[0][1]; ++i)
        {
          const std::int64_t idx[3] = { i, j, k };
          Vec3 shift;
          std::int64_t w[3];
          for (int a = 0; a < 3; ++a)
          {
            w[a] = periodic_ ? wrap(idx[a], n_[a]) : idx[a];
            // The capsule image that covers stored cell w: shifted by −(whole periods).
            shift[a] = -static_cast<double>((idx[a] - w[a]) / n_[a]) * size[a];
          }
          lists[static_cast<std::size_t>((w[2] * n_[1] + w[1]) * n_[0] + w[0])].push_back(
            { c, shift });
        }
      }
    }
  }
  start_.assign(lists.size() + 1, 0);
  for (std::size_t k = 0; k < lists.size(); ++k)
  {
    start_[k + 1] = start_[k] + lists[k].size();
  }
  entries_.reserve(start_.back());
  for (const auto& l : lists)
  {
    entries_.insert(entries_.end(), l.begin(), l.end());
  }
}

std::size_t CapsuleCells::find(const Vec3& p) const
{
  std::int64_t idx[3];
  for (int i = 0; i < 3; ++i)
  {
    idx[i] =
      std::clamp<std::int64_t>(static_cast<std::int64_t>((p[i] - lo_[i]) / edge_[i]), 0, n_[i] - 1);
  }
  const auto cellIndex = static_cast<std::size_t>((idx[2] * n_[1] + idx[1]) * n_[0] + idx[0]);
  for (std::size_t e = start_[cellIndex]; e < start_[cellIndex + 1]; ++e)
  {
    const Capsule& c = set_.capsules[entries_[e].capsule];
    if (pointSegmentDistance(p, c.a + entries_[e].shift, c.b + entries_[e].shift) <= c.r)
    {
      return entries_[e].capsule;
    }
  }
  return npos;
}

} // namespace fiberpli
