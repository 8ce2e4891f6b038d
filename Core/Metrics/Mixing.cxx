#include "Metrics/Mixing.h"

#include "Metrics/CapsuleCells.h"
#include "Util/Random.h"
#include "Util/Threads.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>

namespace fiberpli
{

MixingResult measureMixing(const FiberModel& model, const CapsuleSet& set, const Vec3& lo,
  const Vec3& hi, std::int64_t samples, std::uint64_t seed, const PeriodicCell& cell,
  int numberOfThreads, const ProgressFn& progress)
{
  const double NaN = std::numeric_limits<double>::quiet_NaN();
  MixingResult result;
  if (samples < 1)
  {
    result.error = "Samples " + std::to_string(samples) + " must be >= 1";
    return result;
  }
  std::map<int, std::size_t> index;
  for (const Fiber& f : model.fibers)
  {
    index.emplace(f.bundle, 0);
  }
  for (auto& entry : index)
  {
    entry.second = result.bundles.size();
    result.bundles.push_back(entry.first);
  }
  const std::size_t populations = result.bundles.size();
  std::vector<std::size_t> capsulePopulation(set.capsules.size());
  for (std::size_t c = 0; c < set.capsules.size(); ++c)
  {
    capsulePopulation[c] = index[model.fibers[set.capsules[c].fiber].bundle];
  }
  const CapsuleCells cells(set, lo, hi, cell);
  if (!cells.error().empty())
  {
    result.error = cells.error();
    return result;
  }
  const std::size_t bins = MixingResult::kSubCubes * populations;
  std::vector<std::int64_t> counts(bins, 0);
  const std::int64_t chunk = 65536;
  const std::int64_t chunks = (samples + chunk - 1) / chunk;
  const int threads = resolveThreadCount(numberOfThreads);
  const std::int64_t block = 8 * threads;
  const Vec3 size = hi - lo;
  for (std::int64_t begin = 0; begin < chunks; begin += block)
  {
    const std::int64_t end = std::min(chunks, begin + block);
#pragma omp parallel num_threads(threads)
    {
      // Integer counts: summing them in any order gives the same totals for any thread count.
      std::vector<std::int64_t> local(bins, 0);
#pragma omp for schedule(dynamic, 1)
      for (std::int64_t c = begin; c < end; ++c)
      {
        RandomStream rng(seed, static_cast<std::uint64_t>(c));
        const std::int64_t count = std::min(chunk, samples - c * chunk);
        for (std::int64_t k = 0; k < count; ++k)
        {
          const Vec3 p{ rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z) };
          const std::size_t capsule = cells.find(p);
          if (capsule == CapsuleCells::npos)
          {
            continue;
          }
          int sub[3];
          for (int a = 0; a < 3; ++a)
          {
            sub[a] = std::clamp(static_cast<int>(std::floor(3.0 * (p[a] - lo[a]) / size[a])), 0, 2);
          }
          const auto s = static_cast<std::size_t>((sub[2] * 3 + sub[1]) * 3 + sub[0]);
          ++local[s * populations + capsulePopulation[capsule]];
        }
      }
#pragma omp critical(fiberpli_mixing_counts)
      for (std::size_t b = 0; b < bins; ++b)
      {
        counts[b] += local[b];
      }
    }
    if (!reportProgress(progress, static_cast<double>(end) / static_cast<double>(chunks)))
    {
      result.aborted = true;
      return result;
    }
  }

  result.share.assign(bins, NaN);
  result.minShare.assign(populations, NaN);
  result.volumeShare.assign(populations, NaN);
  std::vector<std::int64_t> perPopulation(populations, 0);
  for (int s = 0; s < MixingResult::kSubCubes; ++s)
  {
    std::int64_t total = 0;
    for (std::size_t p = 0; p < populations; ++p)
    {
      total += counts[s * populations + p];
      perPopulation[p] += counts[s * populations + p];
    }
    if (total == 0)
    {
      continue;
    }
    for (std::size_t p = 0; p < populations; ++p)
    {
      const double share =
        static_cast<double>(counts[s * populations + p]) / static_cast<double>(total);
      result.share[s * populations + p] = share;
      result.minShare[p] =
        std::isnan(result.minShare[p]) ? share : std::min(result.minShare[p], share);
    }
    result.fiberSamples += total;
  }
  result.minimum = NaN;
  for (std::size_t p = 0; p < populations; ++p)
  {
    if (result.fiberSamples > 0)
    {
      result.volumeShare[p] =
        static_cast<double>(perPopulation[p]) / static_cast<double>(result.fiberSamples);
    }
    if (!std::isnan(result.minShare[p]))
    {
      result.minimum = std::isnan(result.minimum) ? result.minShare[p]
                                                  : std::min(result.minimum, result.minShare[p]);
    }
  }
  return result;
}

} // namespace fiberpli
