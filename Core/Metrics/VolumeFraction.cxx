#include "Metrics/VolumeFraction.h"

#include "Metrics/CapsuleCells.h"

#include "Util/MemoryBudget.h"
#include "Util/Random.h"
#include "Util/Threads.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace fiberpli
{
namespace
{

std::int64_t wrap(std::int64_t k, std::int64_t n)
{
  return ((k % n) + n) % n;
}

} // namespace

VolumeFractionResult monteCarloVolumeFraction(const CapsuleSet& set, const Vec3& lo, const Vec3& hi,
  std::int64_t samples, std::uint64_t seed, const PeriodicCell& cell, int numberOfThreads,
  const ProgressFn& progress)
{
  VolumeFractionResult result;
  if (samples < 1)
  {
    result.error = "Samples " + std::to_string(samples) + " must be >= 1";
    return result;
  }
  const CapsuleCells cells(set, lo, hi, cell);
  if (!cells.error().empty())
  {
    result.error = cells.error();
    return result;
  }
  const std::int64_t chunk = 65536;
  const std::int64_t chunks = (samples + chunk - 1) / chunk;
  const int threads = resolveThreadCount(numberOfThreads);
  std::int64_t hits = 0;
  const std::int64_t block = 8 * threads;
  for (std::int64_t begin = 0; begin < chunks; begin += block)
  {
    const std::int64_t end = std::min(chunks, begin + block);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1) reduction(+ : hits)
    for (std::int64_t c = begin; c < end; ++c)
    {
      RandomStream rng(seed, static_cast<std::uint64_t>(c));
      const std::int64_t count = std::min(chunk, samples - c * chunk);
      for (std::int64_t k = 0; k < count; ++k)
      {
        const Vec3 p{ rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z) };
        hits += cells.inside(p) ? 1 : 0;
      }
    }
    if (!reportProgress(progress, static_cast<double>(end) / static_cast<double>(chunks)))
    {
      result.aborted = true;
      return result;
    }
  }
  const double n = static_cast<double>(samples);
  result.fraction = static_cast<double>(hits) / n;
  result.errorBound = std::sqrt(result.fraction * (1.0 - result.fraction) / n);
  return result;
}

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
    n[i] = std::max<std::int64_t>(
      1, static_cast<std::int64_t>(std::ceil((hi[i] - lo[i]) / voxelSize - 1e-9)));
    result.voxel[i] = (hi[i] - lo[i]) / static_cast<double>(n[i]);
  }
  const double margin = 0.5 * norm(result.voxel); // half a voxel diagonal
  const Vec3 size = hi - lo;

  // Bin capsules into the z layers they can reach (capsule box grown by r + margin); in a periodic
  // cell a capsule reaching past the cell's faces enters the wrapped layers with a lattice shift.
  // Entries are counted before any is stored: a long unwrapped fiber in a small cell reaches
  // very many layers.
  const auto reach = [&](const Capsule& cap, std::int64_t& k0, std::int64_t& k1)
  {
    const double grow = cap.r + margin;
    Vec3 bmin, bmax;
    for (int i = 0; i < 3; ++i)
    {
      bmin[i] = std::min(cap.a[i], cap.b[i]) - grow;
      bmax[i] = std::max(cap.a[i], cap.b[i]) + grow;
      if (!cell.enabled() && (bmax[i] < lo[i] || bmin[i] > hi[i]))
      {
        return false;
      }
    }
    k0 = static_cast<std::int64_t>(std::floor((bmin.z - lo.z) / result.voxel.z));
    k1 = static_cast<std::int64_t>(std::floor((bmax.z - lo.z) / result.voxel.z));
    if (!cell.enabled())
    {
      k0 = std::max<std::int64_t>(k0, 0);
      k1 = std::min<std::int64_t>(k1, n[2] - 1);
    }
    return k1 >= k0;
  };
  double entries = 0.0;
  for (const Capsule& cap : set.capsules)
  {
    std::int64_t k0 = 0, k1 = -1;
    entries += reach(cap, k0, k1) ? static_cast<double>(k1 - k0 + 1) : 0.0;
  }
  const int threads = resolveThreadCount(numberOfThreads);
  const double planeBytes = static_cast<double>(n[0] * n[1]) * sizeof(double) * threads;
  const std::string budget = checkMemoryBudget(planeBytes + entries * sizeof(LayerEntry) +
      static_cast<double>(n[2]) * sizeof(std::vector<LayerEntry>),
    "FiberMetrics volume fraction");
  if (!budget.empty())
  {
    result.error = budget;
    return result;
  }
  std::vector<std::vector<LayerEntry>> layers(static_cast<std::size_t>(n[2]));
  for (std::size_t c = 0; c < set.capsules.size(); ++c)
  {
    std::int64_t k0 = 0, k1 = -1;
    if (!reach(set.capsules[c], k0, k1))
    {
      continue;
    }
    for (std::int64_t k = k0; k <= k1; ++k)
    {
      const std::int64_t layer = cell.enabled() ? wrap(k, n[2]) : k;
      // Shifting the capsule by −(whole periods) puts unwrapped layer k onto the stored layer.
      const double periods = static_cast<double>((k - layer) / n[2]);
      layers[static_cast<std::size_t>(layer)].push_back({ c, Vec3{ 0.0, 0.0, -periods * size.z } });
    }
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
            range[i][0] = static_cast<std::int64_t>(
              std::floor((std::min(a[i], b[i]) - grow - lo[i]) / result.voxel[i]));
            range[i][1] = static_cast<std::int64_t>(
              std::floor((std::max(a[i], b[i]) + grow - lo[i]) / result.voxel[i]));
            if (!cell.enabled())
            {
              range[i][0] = std::max<std::int64_t>(range[i][0], 0);
              range[i][1] = std::min<std::int64_t>(range[i][1], n[i] - 1);
            }
          }
          for (std::int64_t j = range[1][0]; j <= range[1][1]; ++j)
          {
            const double y = lo.y + (static_cast<double>(j) + 0.5) * result.voxel.y;
            const std::int64_t row = (cell.enabled() ? wrap(j, n[1]) : j) * n[0];
            for (std::int64_t i = range[0][0]; i <= range[0][1]; ++i)
            {
              const Vec3 centre{ lo.x + (static_cast<double>(i) + 0.5) * result.voxel.x, y, z };
              double& s =
                plane[static_cast<std::size_t>(row + (cell.enabled() ? wrap(i, n[0]) : i))];
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
  const double total =
    static_cast<double>(n[0]) * static_cast<double>(n[1]) * static_cast<double>(n[2]);
  result.fraction = static_cast<double>(inside) / total;
  result.errorBound = static_cast<double>(std::max(inside - certain, possible - inside)) / total;
  return result;
}

} // namespace fiberpli
