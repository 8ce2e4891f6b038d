/// Mixing: how well populations (bundle_id) are interwoven. The region (box or periodic cell) is
/// cut into 3 × 3 × 3 sub-cubes of a third of its edges; in each, every population's share of the
/// fiber volume there is estimated by Monte Carlo (points inside a capsule, every periodic image
/// counted, each point given to the population of the first capsule found to contain it). The
/// mixing figure is the smallest share over sub-cubes and populations: 0 for populations in
/// separate halves, 1/P for P populations interwoven evenly.
#pragma once

#include "Metrics/Capsules.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <cstdint>
#include <vector>

namespace fiberpli
{

struct MixingResult : Status
{
  static constexpr int kSubCubes = 27;
  std::vector<int> bundles; ///< the populations, increasing bundle id
  /// share[s · bundles.size() + p]: population p's share of the fiber volume in sub-cube s
  /// (s = (k·3 + j)·3 + i, i along x); NaN where the sub-cube holds no sampled fiber volume.
  std::vector<double> share;
  std::vector<double> minShare;    ///< per population, over the sub-cubes holding fiber volume
  std::vector<double> volumeShare; ///< per population, of the fiber volume of the whole region
  double minimum = 0.0;            ///< over all populations (NaN without any fiber volume sampled)
  std::int64_t fiberSamples = 0;   ///< samples that fell inside a capsule
};

/// `samples` (>= 1) uniform points of [lo, hi] drawn in chunks of 65536 from
/// RandomStream(seed, chunk), as monteCarloVolumeFraction does, so the result is the same for any
/// thread count. `model` gives each capsule's bundle.
MixingResult measureMixing(const FiberModel& model, const CapsuleSet& set, const Vec3& lo,
  const Vec3& hi, std::int64_t samples, std::uint64_t seed, const PeriodicCell& cell,
  int numberOfThreads, const ProgressFn& progress);

} // namespace fiberpli
