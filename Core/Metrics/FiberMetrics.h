/// FiberMetrics: what a fiber model is like, measured independently of the code that built or
/// solved it — volume fraction in a box or periodic cell, colliding pairs and the smallest surface
/// gap, orientation order and mean direction per bundle, tortuosity, link length and radius ranges,
/// and the realism of the model (Realism.h, Mixing.h; myelin, axon and extra-axonal volume).
#pragma once

#include "Metrics/CapsulePairs.h"
#include "Metrics/Capsules.h"
#include "Metrics/FiberShape.h"
#include "Metrics/Mixing.h"
#include "Metrics/Realism.h"
#include "Metrics/VolumeFraction.h"
#include "Model/FiberModel.h"
#include "Model/InnerRadii.h"
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
  /// When enabled: volume fraction over the whole cell (the box is ignored) and pairs by minimum
  /// image.
  PeriodicCell cell;
  /// Voxel edge of the volume fraction (µm); 0 = automatic: an eighth of the smallest radius,
  /// coarsened if that would need more than automaticVoxelLimit voxels.
  double voxelSize = 0.0;
  double automaticVoxelLimit = 2e8;
  double voxelLimit = 2e10; ///< more voxels is an error (it would run for hours)
  /// Monte Carlo instead of voxels: `samples` random points from `seed`; the error is then the
  /// standard error instead of a bound.
  bool monteCarlo = false;
  std::int64_t samples = 1000000;
  std::uint64_t seed = 0;
  bool volumeFraction = true;
  bool pairs = true;
  /// The mixing figure of the populations (Mixing.h) by Monte Carlo with `samples` points from
  /// `seed`, in the volume fraction's region; with fewer than two populations it is 1 unsampled.
  bool mixing = true;
  std::int64_t histogramBins = 20; ///< bins of the realism histograms, >= 1
  int numberOfThreads = 0;         ///< 0 = all cores
};

/// error non-empty: a bad option, naming it and its value.
struct MetricsResult : Status
{
  std::size_t fibers = 0, points = 0, links = 0;
  Vec3 regionLo, regionHi;     ///< where the volume fraction was measured
  VolumeFractionResult volume; ///< fraction NaN when not computed
  PairResult pairs;            ///< collisions −1 / minGap NaN when not computed
  ShapeResult shape;
  RealismResult realism;
  MixingResult mixing; ///< minimum NaN when not computed
  /// With inner radii (on any fiber) and the volume fraction on: the union of the inner capsules
  /// (the axons) measured like `volume` (same method, region, voxels or samples); myelin = volume −
  /// axon, extra-axonal = 1 − volume. NaN otherwise.
  VolumeFractionResult axonVolume;
  double myelinFraction = 0.0, extraAxonalFraction = 0.0;
};

/// Validates the options (box with zero thickness, non-positive cell, negative voxel size, too many
/// voxels, HistogramBins < 1, inner radii not fitting their fiber → error naming the value) and
/// measures; fibers with inner radii (Fiber::innerRadii) are myelinated. An empty model gives
/// zeros and NaNs, no error.
MetricsResult computeFiberMetrics(
  const FiberModel& model, const MetricsOptions& options, const ProgressFn& progress);

} // namespace fiberpli
