/// ShapeOptions: the realism knobs both tissue sources share (docs/tissue-models.md §10): smooth
/// undulation to a target tortuosity, orientation dispersion, beading (radius varying along a
/// fiber) and myelin (an inner radius beside the outer one). Every default is "off" and leaves the
/// generators' output bit-identical: a knob that is off draws no random number. The features draw
/// from their own streams (shapeStream), never from a fiber's main stream.
#pragma once

#include "Util/EnumCode.h"
#include "Util/Random.h"

#include <cstdint>
#include <string>

namespace fiberpli
{

/// `GRatioModel` property: api strings "Constant" and "Lee2019" (Myelin.h).
enum class GRatioModel
{
  Constant = 0, ///< inner radius = GRatio · outer radius
  Lee2019 = 1   ///< myelin thickness 0.35 + 0.006·d + 0.024·ln d µm, d the inner diameter in µm
};

/// The api string of a g-ratio model.
const char* gRatioModelName(GRatioModel model);

/// The `GRatioModel` code as the enum (Util/EnumCode.h): "" or the message naming the code.
inline std::string gRatioModelFromCode(int code, GRatioModel& model)
{
  return enumFromCode(code, static_cast<int>(GRatioModel::Lee2019), "GRatioModel",
    "0 (Constant) or 1 (Lee2019)", model);
}

struct ShapeOptions
{
  /// Target path length / end-to-end distance of every fiber (>= 1; 1 = straight, no undulation).
  double tortuosity = 1.0;
  /// µm, the typical wavelength of the undulation (> 0).
  double undulationWavelength = 20.0;
  /// Target ⟨cos²⟩ of the fibers' end-to-end directions about their population's axis, in
  /// (1/3, 1]; 1 = every fiber along the axis (off).
  double dispersionC2 = 1.0;
  /// Coefficient of variation of the radius along each fiber (>= 0, at most kMaxBeadingCV; 0 =
  /// off).
  double beadingCV = 0.0;
  /// µm, the correlation length of the radius variation (> 0).
  double beadingLength = 5.0;
  /// 0 = no myelin; in (0, 1): myelin on (Constant: the ratio inner / outer radius).
  double gRatio = 0.0;
  GRatioModel gRatioModel = GRatioModel::Constant;

  bool undulating() const { return tortuosity > 1.0; }
  bool dispersed() const { return dispersionC2 < 1.0; }
  bool beaded() const { return beadingCV > 0.0; }
  bool myelinated() const { return gRatio > 0.0; }
  /// Any knob that changes the fibers' points or radii (myelin only adds an array).
  bool shapesFibers() const { return undulating() || dispersed() || beaded(); }
};

/// The largest accepted BeadingCV: beyond it the log-normal profile is mostly thin thread with a
/// few huge beads, which no tissue shows and no solve separates.
constexpr double kMaxBeadingCV = 1.0;

/// Empty when usable, else a message naming the property and its value: Tortuosity < 1 or not
/// finite; UndulationWavelength <= 0 (when Tortuosity > 1); DispersionC2 outside (1/3, 1];
/// BeadingCV < 0 or > kMaxBeadingCV; BeadingLength <= 0 (when BeadingCV > 0); GRatio outside
/// (0, 1) unless 0; GRatioModel not Constant or Lee2019.
std::string validateShapeOptions(const ShapeOptions& options);

/// Empty, or a warning about usable but doubtful values: an UndulationWavelength below four
/// SegmentLengths, whose waves the points cannot follow (the polyline zig-zags instead).
std::string shapeWarnings(const ShapeOptions& options, double segmentLength);

/// The shape features that draw random numbers, each from its own stream.
enum class ShapeFeature : std::uint64_t
{
  Undulation = 0,
  Dispersion = 1,
  Beading = 2,
  Jitter = 3,    ///< the point displacements of a shaped fiber (its point count differs from the
                 ///< straight one's)
  Placement = 4, ///< the cube: the along-axis start of a fiber of a crossing-angle population
  Stratum =
    5 ///< the cube: the order in which a population's fibers fill the strata (one stream a round)
};

/// The index of the one stream of a group that is not a fiber's: its draws are shared by the whole
/// group (the dispersion quantiles' offset).
constexpr std::uint64_t kGroupStream = ~std::uint64_t{ 0 };

/// The first key of a shape feature's streams for `group` (the cube's population or the bundle's
/// cross-section): 1000 + 16·feature + group. Keys >= 1000 never meet the generators' own streams
/// (population / cross-section 0..3, lattice 3..8).
constexpr std::uint64_t shapeStreamKey(ShapeFeature feature, std::uint64_t group)
{
  return 1000 + 16 * static_cast<std::uint64_t>(feature) + group;
}

/// The stream of a shape feature for fiber `index` of `group`: (seed, shapeStreamKey, index).
inline RandomStream shapeStream(
  std::uint64_t seed, ShapeFeature feature, std::uint64_t group, std::uint64_t index)
{
  return RandomStream(seed, shapeStreamKey(feature, group), index);
}

} // namespace fiberpli
