/// Realism: how much a fiber model looks like white matter, per population (bundle_id) —
/// tortuosity, orientation dispersion of the fibers' end-to-end directions and of their links,
/// variation of the radius along each fiber (beading), g-ratio — and the histograms behind them.
/// The sampled figures (mixing of populations, myelin and axon volume) are in Mixing.h and
/// FiberMetrics.h.
#pragma once

#include "Metrics/FiberShape.h"
#include "Metrics/Histogram.h"
#include "Model/FiberModel.h"
#include "Model/InnerRadii.h"

#include <cstddef>
#include <vector>

namespace fiberpli
{

struct PopulationRealism
{
  int bundle = 0;
  std::size_t fibers = 0;
  Range tortuosity; ///< of the fibers with distinct ends (closed fibers: over their lattice vector)
  /// The population's axis: the principal eigenvector of the mean of e·eᵀ over the fibers' unit
  /// end-to-end directions e (sign: largest component positive).
  Vec3 axis;
  double c2EndToEnd; ///< ⟨(e·axis)²⟩ over the fibers (the largest eigenvalue of that mean)
  double c2Segments; ///< length-weighted ⟨(u·axis)²⟩ over the links, u the unit link direction
  double radiusCV;   ///< length-weighted mean over the fibers of their along-fiber radius CV
  double gRatio; ///< length-weighted mean of inner/outer radius over its fibers with inner radii
                 ///< (else NaN)
};

struct RealismResult
{
  std::vector<PopulationRealism> populations; ///< in increasing bundle id
  /// Per fiber: std/mean of the radius along the fiber, the radius taken linear along each link and
  /// both moments integrated over arc length (0 for a constant radius, NaN for a zero-length
  /// fiber).
  std::vector<double> fiberRadiusCV;
  std::vector<double>
    fiberGRatio; ///< arc-length mean of inner/outer radius; NaN for a fiber without inner radii
  double radiusCV, gRatio; ///< over all fibers, length-weighted as per population
  /// Bar-chart data: point radii (count), fiber tortuosities (count), point g-ratios (count; empty
  /// bins without inner radii), link angles to their population's axis in degrees, [0, 90]
  /// (count and summed link length).
  Histogram radiusHistogram, tortuosityHistogram, gRatioHistogram, segmentAngleHistogram;
};

/// Measures the model, whose inner radii are valid (validateInnerRadii); `shape` is fiberShape's
/// result for the same model (its per-fiber tortuosity and lengths are reused); bins >= 1.
RealismResult measureRealism(const FiberModel& model, const ShapeResult& shape, std::size_t bins);

} // namespace fiberpli
