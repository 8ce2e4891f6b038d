/// FiberMetrics: what a fiber model is like, measured independently of the code that built or
/// solved it — volume fraction in a box or periodic cell, colliding pairs and the smallest surface
/// gap, orientation order and mean direction per bundle, tortuosity, link length and radius ranges.
#pragma once

#include "Metrics/CapsulePairs.h"
#include "Metrics/Capsules.h"
#include "Metrics/FiberShape.h"
#include "Metrics/VolumeFraction.h"
#include "Model/FiberModel.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <cstdint>
#include <string>

namespace fiberpli
{

struct MetricsOptions
{
  /// Box of the volume fraction, [lo, hi]; any lo > hi means the bounds of the fiber points.
  Vec3 boxLo{ 1.0, 1.0, 1.0 }, boxHi{ -1.0, -1.0, -1.0 };
  /// When enabled: volume fraction over the whole cell (the box is ignored) and pairs by minimum image.
  PeriodicCell cell;
  /// Voxel edge of the volume fraction (µm); 0 = automatic: an eighth of the smallest radius,
  /// coarsened if that would need more than automaticVoxelLimit voxels.
  double voxelSize = 0.0;
  double automaticVoxelLimit = 2e8;
  double voxelLimit = 2e10;      ///< more voxels is an error (it would run for hours)
  /// Monte Carlo instead of voxels: `samples` random points from `seed`; the error is then the
  /// standard error instead of a bound.
  bool monteCarlo = false;
  std::int64_t samples = 1000000;
  std::uint64_t seed = 0;
  bool volumeFraction = true;
  bool pairs = true;
  int numberOfThreads = 0;       ///< 0 = all cores
};

/// error non-empty: a bad option, naming it and its value.
struct MetricsResult : Status
{
  std::size_t fibers = 0, points = 0, links = 0;
  Vec3 regionLo, regionHi;       ///< where the volume fraction was measured
  VolumeFractionResult volume;   ///< fraction NaN when not computed
  PairResult pairs;              ///< collisions −1 / minGap NaN when not computed
  ShapeResult shape;
};

/// Validates the options (box with zero thickness, non-positive cell, negative voxel size, too many
/// voxels → error naming the value) and measures. An empty model gives zeros and NaNs, no error.
MetricsResult computeFiberMetrics(const FiberModel& model, const MetricsOptions& options,
  const ProgressFn& progress);

} // namespace fiberpli
