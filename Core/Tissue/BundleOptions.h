/// BundleOptions: the properties of FiberBundleSource (docs/api.md §3, docs/tissue-models.md §8)
/// and their validation.
#pragma once

#include "Geometry/Vec3.h"
#include "Tissue/RadiusDistribution.h"
#include "Tissue/ShapeOptions.h"
#include "Util/EnumCode.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

/// `Shape` property; api strings "Cylinder", "Trajectory", "Crossing", "YShape", "Chiasm".
enum class BundleShape
{
  Cylinder = 0,   ///< §8: axis along x from (−Length/2, 0, 0) to (+Length/2, 0, 0)
  Trajectory = 1, ///< §2: follows a user polyline
  Crossing = 2,   ///< §6.3: two bundles crossing at the origin at CrossingAngle
  YShape = 3,     ///< §6.4: trunk splitting into two half-disc branches at CrossingAngle
  Chiasm = 4 ///< §6.5: two nerves crossing, their lateral fibers turning back (UncrossedFraction)
};

/// The string of a shape (docs/api.md §1).
const char* bundleShapeName(BundleShape shape);
/// Parses a shape string (docs/api.md §1) (exact spelling); false if unknown.
bool parseBundleShape(const std::string& text, BundleShape& shape);
/// The `Shape` code as the enum (Util/EnumCode.h): "" or the message naming the code.
inline std::string bundleShapeFromCode(int code, BundleShape& shape)
{
  return enumFromCode(
    code, static_cast<int>(BundleShape::Chiasm), "Shape", "0 (Cylinder) to 4 (Chiasm)", shape);
}

/// FiberBundleSource properties, docs/tissue-models.md §8, units µm and degrees.
struct BundleOptions
{
  BundleShape shape = BundleShape::Cylinder;
  double bundleRadius = 10.0; ///< R, must be >= fiberRadius
  double length = 60.0;       ///< Cylinder/Crossing/Chiasm: full length 2H; YShape: trunk + branch;
                              ///< unused for Trajectory
  double fiberRadius = 0.8;   ///< nominal r
  double radiusSpread = 0.0;  ///< s >= 0 (§5.3), 0 = constant
  RadiusDistribution radiusDistribution = RadiusDistribution::LogNormal;
  double fiberSpacing = 2.0;  ///< triangular grid spacing d, used when numberOfFibers == 0
  int numberOfFibers = 0;     ///< > 0: that many random seeds per cross-section instead of the grid
  double segmentLength = 2.0; ///< l, point spacing along the trajectory
  double displacement = 0.2;  ///< D of U[−D, D]³ per point
  double crossingAngle =
    90.0; ///< Crossing: between bundles; YShape: opening; Chiasm: between nerves
  double uncrossedFraction =
    0.25; ///< Chiasm: fraction f of each nerve's fibers that stays on its side
  double ranvierSpacing = -1.0; ///< Λ; 0 = off; < 0 = shape default (Chiasm 20 µm, else off)
  double ranvierDepth = 0.3;    ///< in [0, 1)
  double ranvierLength = 1.0;   ///< w, with 2w <= Λ
  std::uint64_t seed = 42;
  /// Realism knobs (Tissue/ShapeOptions.h, docs/tissue-models.md §10); the defaults are off and
  /// leave the bundles bit-identical.
  ShapeOptions realism;
};

/// Λ after resolving the "shape default" sentinel: 20 µm for Chiasm, 0 otherwise (§8).
double effectiveRanvierSpacing(const BundleOptions& options);

/// Empty string when the options (and, for Shape = Trajectory, the polyline with its optional
/// scale) are usable, else a message naming the property and its value or the trajectory point:
/// non-finite values; FiberRadius <= 0; BundleRadius < FiberRadius; Length <= 0; RadiusSpread < 0
/// (or >= 1 for Uniform); FiberSpacing <= 0 with NumberOfFibers = 0; NumberOfFibers < 0;
/// SegmentLength <= 0; Displacement < 0; CrossingAngle outside (0, 180] (Crossing) or (0, 180)
/// (YShape, Chiasm); UncrossedFraction outside [0, 1]; with Ranvier on: RanvierDepth outside [0,
/// 1), RanvierLength <= 0 or 2·RanvierLength > RanvierSpacing; Trajectory without a polyline or a
/// bad polyline (validateTrajectory); a bad realism knob (validateShapeOptions); more fibers or
/// points than the memory budget allows (Util/MemoryBudget.h, with fiberModelBytes; the points of
/// one piece of `pieces`, the cross-sections of all fibers, which every piece draws).
std::string validateBundleOptions(const BundleOptions& options,
  const std::vector<Vec3>* trajectory = nullptr,
  const std::vector<double>* trajectoryScale = nullptr, int pieces = 1);

} // namespace fiberpli
