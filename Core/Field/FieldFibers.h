/// FieldFibers: fills the region of one or two orientation fields with fibers that follow them
/// (docs/field-source.md). Seeds are drawn uniformly over the part of the region where the fiber's
/// field is not empty, every fiber is traced through its seed (Field/FieldTracer.h) and fibers are
/// added until the fiber volume Σ π r² · length reaches the target fraction of the non-empty
/// volume, or until a given count. With two fields (two crossing populations) each field is one
/// population, bundle = field index.
#pragma once

#include "Field/FieldTracer.h"
#include "Field/OrientationField.h"
#include "Model/FiberModel.h"
#include "Tissue/RadiusDistribution.h"
#include "Tissue/ShapeOptions.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

struct FieldFiberOptions
{
  /// Target Σ π r² · length over the non-empty volume, in (0, 0.9]; used when numberOfFibers is 0.
  double volumeFraction = 0.3;
  /// > 0: exactly this many fibers (split by populationShares), volumeFraction is then ignored.
  int numberOfFibers = 0;
  double fiberRadius = 0.8; ///< µm (median or mean with a spread, Tissue/RadiusDistribution.h)
  double radiusSpread = 0.0;
  RadiusDistribution radiusDistribution = RadiusDistribution::Constant;
  TraceOptions trace; ///< segment length, scheme, length cap
  std::uint64_t seed = 42;
  /// Candidate lines per fiber, in [1, 64]: each fiber draws this many seeds, traces each and
  /// keeps the line that overlaps the fibers placed before it least (Field/OccupancyGrid.h), so
  /// that a dense model starts with fewer collisions. 1 = the first seed, as drawn.
  int seedCandidates = 1;
  /// Threads tracing the candidate lines (>= 1); the fibers do not depend on it.
  int threads = 1;
  /// Relative shares of the populations (of the volume, or of the count), one per field, each > 0.
  /// Empty: equal shares.
  std::vector<double> populationShares;
  /// Realism (Tissue/ShapeOptions.h): beading (the radius varying along each traced fiber) and
  /// myelin (inner radii); the field sets the fibers' course, so tortuosity and dispersion must
  /// stay off. Defaults: off.
  ShapeOptions realism;
};

struct FieldFiberResult : Status
{
  FiberModel model;               ///< fiber ids 0..N-1 in the order added, bundle = field index
  double regionVolume = 0.0;      ///< µm³, the box volume × the share of non-empty grid points
  double volumeFraction = 0.0;    ///< Σ π r² · length / regionVolume reached
  std::size_t discardedSeeds = 0; ///< seeds whose line was shorter than a third of a segment
};

/// Empty when the options (with `fields` fields of `field`'s grid) are usable, else a message
/// naming the property and its value; includes the memory estimate of the model.
std::string validateFieldFiberOptions(
  const FieldFiberOptions& options, const OrientationField& field, int fields);

/// The non-empty volume of the fields: the box volume × the share of grid points where at least
/// one field is not empty (all fields share one grid).
double fieldRegionVolume(const std::vector<const OrientationField*>& fields);

/// Generates the fibers. All fields must have the same grid, each already normalised
/// (normalizeOrientationField). Fiber k-th drawn of population p takes its draws from the stream
/// (seed, p, k): the seed position (three uniforms per try, until one falls on the non-empty
/// field; with seedCandidates c, c such positions one after the other), then the radius; with
/// beading its profile along the traced points comes from the stream shapeStream(seed, Beading, p,
/// k). A fiber's volume is Σ over links of π · (r_i² + r_i+1²)/2 · link length (π r² · length
/// without beading). Volume mode adds each fiber to the population furthest below its share of the
/// target volume and stops at the first fiber that reaches the target. With myelin every fiber gets
/// its inner radii. Progress is reported every 64 fibers; when it returns false the result is
/// `aborted` with an empty model.
FieldFiberResult generateFieldFibers(const std::vector<const OrientationField*>& fields,
  const FieldFiberOptions& options, const ProgressFn& progress = {});

} // namespace fiberpli
