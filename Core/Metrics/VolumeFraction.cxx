#include "Metrics/VolumeFraction.h"

#include "Util/MemoryBudget.h"
#include "Util/Threads.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <vector>

namespace fiberpli
{
namespace
{

std::int64_t wrap(std::int64_t k, std::int64_t n) { return ((k % n) + n) % n; }

/// One capsule's entry in a voxel layer: the capsule shifted by a lattice vector (zero without a cell).
struct LayerEntry
{
  std::size_t capsule;
  Vec3 shift;
};

} // namespace

double voxelCount(const Vec3& lo, const Vec3& hi, double h)
{
  double total = 1.0;
  for (int i = 0; i < 3; ++i)
  {
    total *= std::max(1.0, std::ceil((hi[i] - lo[i]) / h - 1e-9));
  }
  return total;
}

VolumeFractionResult volumeFraction(const CapsuleSet& set, const Vec3& lo, const Vec3& hi,
  double voxelSize, const PeriodicCell& cell, int numberOfThreads, const ProgressFn& progress)
{
  VolumeFractionResult result;
  std::int64_t n[3];
  for (int i = 0; i < 3; ++i)
  {
    n[i] = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil((hi[i] - lo[i]) / voxelSize - 1e-9)));
    result.voxel[i] = (hi[i] - lo[i]) / static_cast<double>(n[i]);
  }
  const double margin = 0.5 * norm(result.voxel); // half a voxel diagonal
  const Vec3 size = hi - lo;

  // Bin capsules into the z layers they can reach (capsule box grown by r + margin); in a periodic
  // cell a capsule reaching past the cell's faces enters the wrapped layers with a lattice shift.
  std::vector<std::vector<LayerEntry>> layers(static_cast<std::size_t>(n[2]));
  std::size_t entries = 0;
  for (std::size_t c = 0; c < set.capsules.size(); ++c)
  {
    const Capsule& cap = set.capsules[c];
    const double grow = cap.r + margin;
    Vec3 bmin, bmax;
    bool outside = false;
    for (int i = 0; i < 3; ++i)
    {
      bmin[i] = std::min(cap.a[i], cap.b[i]) - grow;
      bmax[i] = std::max(cap.a[i], cap.b[i]) + grow;
      outside = outside || (!cell.enabled && (bmax[i] < lo[i] || bmin[i] > hi[i]));
    }
    if (outside)
    {
      continue;
    }
    std::int64_t k0 = static_cast<std::int64_t>(std::floor((bmin.z - lo.z) / result.voxel.z));
    std::int64_t k1 = static_cast<std::int64_t>(std::floor((bmax.z - lo.z) / result.voxel.z));
    if (!cell.enabled)
    {
      k0 = std::max<std::int64_t>(k0, 0);
      k1 = std::min<std::int64_t>(k1, n[2] - 1);
    }
    for (std::int64_t k = k0; k <= k1; ++k)
    {
      const std::int64_t layer = cell.enabled ? wrap(k, n[2]) : k;
      // Shifting the capsule by −(whole periods) puts unwrapped layer k onto the stored layer.
      const double periods = static_cast<double>((k - layer) / n[2]);
      layers[static_cast<std::size_t>(layer)].push_back({ c, Vec3{ 0.0, 0.0, -periods * size.z } });
      ++entries;
    }
  }
  const int threads = resolveThreadCount(numberOfThreads);
  const double planeBytes = static_cast<double>(n[0] * n[1]) * sizeof(double) * threads;
  const std::string budget = checkMemoryBudget(planeBytes + entries * sizeof(LayerEntry), "FiberMetrics volume fraction");
  if (!budget.empty())
  {
    result.error = budget;
    return result;
  }

  std::int64_t inside = 0, certain = 0, possible = 0;
  const std::int64_t block = std::max<std::int64_t>(1, 4 * threads);
  for (std::int64_t begin = 0; begin < n[2]; begin += block)
  {
    const std::int64_t end = std::min(n[2], begin + block);
#pragma omp parallel num_threads(threads) reduction(+ : inside, certain, possible)
    {
      std::vector<double> plane(static_cast<std::size_t>(n[0] * n[1]));
#pragma omp for schedule(dynamic, 1)
      for (std::int64_t k = begin; k < end; ++k)
      {
        std::fill(plane.begin(), plane.end(), std::numeric_limits<double>::infinity());
        const double z = lo.z + (static_cast<double>(k) + 0.5) * result.voxel.z;
        for (const LayerEntry& e : layers[static_cast<std::size_t>(k)])
        {
          const Capsule& cap = set.capsules[e.capsule];
          const Vec3 a = cap.a + e.shift, b = cap.b + e.shift;
          const double grow = cap.r + margin;
          std::int64_t range[2][2];
          for (int i = 0; i < 2; ++i)
          {
            range[i][0] = static_cast<std::int64_t>(std::floor((std::min(a[i], b[i]) - grow - lo[i]) / result.voxel[i]));
            range[i][1] = static_cast<std::int64_t>(std::floor((std::max(a[i], b[i]) + grow - lo[i]) / result.voxel[i]));
            if (!cell.enabled)
            {
              range[i][0] = std::max<std::int64_t>(range[i][0], 0);
              range[i][1] = std::min<std::int64_t>(range[i][1], n[i] - 1);
            }
          }
          for (std::int64_t j = range[1][0]; j <= range[1][1]; ++j)
          {
            const double y = lo.y + (static_cast<double>(j) + 0.5) * result.voxel.y;
            const std::int64_t row = (cell.enabled ? wrap(j, n[1]) : j) * n[0];
            for (std::int64_t i = range[0][0]; i <= range[0][1]; ++i)
            {
              const Vec3 centre{ lo.x + (static_cast<double>(i) + 0.5) * result.voxel.x, y, z };
              double& s = plane[static_cast<std::size_t>(row + (cell.enabled ? wrap(i, n[0]) : i))];
              s = std::min(s, pointSegmentDistance(centre, a, b) - cap.r);
            }
          }
        }
        for (double s : plane)
        {
          inside += s <= 0.0 ? 1 : 0;
          certain += s <= -margin ? 1 : 0;
          possible += s < margin ? 1 : 0;
        }
      }
    }
    if (!reportProgress(progress, static_cast<double>(end) / static_cast<double>(n[2])))
    {
      result.aborted = true;
      return result;
    }
  }
  const double total = static_cast<double>(n[0]) * static_cast<double>(n[1]) * static_cast<double>(n[2]);
  result.fraction = static_cast<double>(inside) / total;
  result.errorBound = static_cast<double>(std::max(inside - certain, possible - inside)) / total;
  return result;
}

} // namespace fiberpli
