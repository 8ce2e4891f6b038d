/// Axis: fiber axes as undirected unit vectors (docs/pli-analysis.md §3.2 step 4, §5). One
/// canonical representative per axis, its (direction, inclination) angles, and the comparison
/// metrics of §5. Angles in radians.
#pragma once

#include "Geometry/Vec3.h"

namespace fiberpli
{

/// v = (cos α cos φ, cos α sin φ, sin α).
Vec3 axisFromAngles(double direction, double inclination);

/// §3.2 step 4: v normalised, then negated if v_y < 0, or v_y = 0 and v_x < 0, or v_x = v_y = 0
/// and v_z < 0. A zero vector stays zero.
Vec3 canonicalAxis(const Vec3& v);

/// Angles of the canonical form of v: direction = atan2(v_y, v_x) in [0, π), inclination =
/// asin(v_z) in [−π/2, π/2] (signed). A vertical axis has direction 0 and inclination +π/2.
/// A zero vector gives NaN for both.
void axisAngles(const Vec3& v, double& direction, double& inclination);

/// §5: Δdirection = min(|φa − φb| mod π, π − (|φa − φb| mod π)), in [0, π/2].
double directionDifference(double directionA, double directionB);

/// §5: angle between two axes, atan2(|va × vb|, |va · vb|), in [0, π/2]; axes given by angles.
double axisAngle(double directionA, double inclinationA, double directionB, double inclinationB);

/// §5: the axis angle minimised over the sign of the inclinations (for retardation-based
/// inclinations, whose sign is unknown).
double unsignedAxisAngle(
  double directionA, double inclinationA, double directionB, double inclinationB);

} // namespace fiberpli
