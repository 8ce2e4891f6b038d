/// VolumeFraction: the fraction of a box (or of the periodic cell, counting every periodic image)
/// covered by the union of the capsules, by a deterministic voxel count with a rigorous error
/// bound.
#pragma once

#include "Metrics/Capsules.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <cstdint>
#include <string>

namespace fiberpli
{

/// error non-empty: nothing computed (the message names the value).
struct VolumeFractionResult : Status
{
  double fraction = 0.0;   ///< voxels whose centre lies inside a capsule / all voxels
  double errorBound = 0.0; ///< |fraction − true fraction| <= errorBound (see volumeFraction)
  Vec3 voxel;              ///< voxel edges used (the box divided into whole voxels)
};

/// The box [lo, hi] is divided into whole voxels of edge about `voxelSize` (each axis rounded so
/// that the voxels tile the box exactly). A voxel counts as fiber when its centre is inside a
/// capsule. Its true covered fraction can differ from that only if some capsule surface passes
/// within half a voxel diagonal m of its centre; counting those voxels (signed distance in
/// (−m, m)) bounds the error exactly: errorBound = max(estimate − certain, possible − estimate).
/// With cell.enabled(), [lo, hi] is the cell and voxels wrap around it, so every image counts.
VolumeFractionResult volumeFraction(const CapsuleSet& set, const Vec3& lo, const Vec3& hi,
  double voxelSize, const PeriodicCell& cell, int numberOfThreads, const ProgressFn& progress);

/// Monte Carlo alternative: `samples` uniform points of [lo, hi] (drawn in chunks of 65536 from
/// RandomStream(seed, chunk), so the result is the same for any thread count); fraction = share
/// inside a capsule (every periodic image with cell.enabled()), errorBound = its standard error
/// √(φ(1 − φ)/samples); voxel stays zero.
VolumeFractionResult monteCarloVolumeFraction(const CapsuleSet& set, const Vec3& lo, const Vec3& hi,
  std::int64_t samples, std::uint64_t seed, const PeriodicCell& cell, int numberOfThreads,
  const ProgressFn& progress);

/// Voxels of edge h in the box [lo, hi] (each axis rounded up to whole voxels), as a double.
double voxelCount(const Vec3& lo, const Vec3& hi, double h);

} // namespace fiberpli
