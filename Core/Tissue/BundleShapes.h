/// BundleShapes: centre lines of the paper's models (docs/tissue-models.md §6.3–§6.5), in µm, in
/// the x–y plane. Each is a control polyline for resampleTrajectory.
#pragma once

#include "Geometry/Vec3.h"

#include <vector>

namespace fiberpli
{

/// Straight line from −H·d to +H·d, d = (cos a, sin a, 0) for angle a (radians): Cylinder (a = 0)
/// and the Crossing bundles (§6.3).
std::vector<Vec3> straightPath(double halfLength, double angle);

/// Y-shape branch, docs/tissue-models.md §6.4 [ours]: trunk from (0, −H, 0) to the fork (0, 0, 0),
/// then a circular arc of radius turnRadius from +y towards b = (∓sin(ω/2), cos(ω/2), 0) (left: −,
/// right:
/// +), then straight, the branch (arc + straight) of length H. If the arc alone is longer than H
/// it is cut at H. Sampled densely (links <= step) so the Catmull–Rom resampling follows the arc.
std::vector<Vec3> yBranchPath(
  double halfLength, double openingAngle, double turnRadius, bool left, double step);

/// Chiasm nerve direction d0 = (sin(ω/2), cos(ω/2), 0) (left nerve) or its mirror x → −x (right
/// nerve), docs/tissue-models.md §6.5.
Vec3 chiasmDirection(double crossingAngle, bool right);
/// In-plane normal pointing away from the midline: n_L = (−cos(ω/2), sin(ω/2), 0), mirrored for
/// the right nerve.
Vec3 chiasmLateralNormal(double crossingAngle, bool right);
/// The uncrossed (side) path of the left nerve, docs/tissue-models.md §6.5 [ours, replaces
/// fastPLI's five-point curve, whose tip has a radius of curvature of only 0.144·H, so that the
/// inner fibers of any bundle wider than that folded over]: along the left nerve's axis from −H·d0,
/// a circular arc of radius turnRadius tangent to both nerve axes (centre (−turnRadius/cos(ω/2), 0,
/// 0), turning by ω), then along the right nerve's axis to +H·d1 = (−S, C). The arc is left where
/// the nerve axes are turnRadius·tan(ω/2) from the crossing; turnRadius is reduced to H/tan(ω/2) if
/// that point would lie beyond the nerve's end. Sampled densely (links <= step). Right nerve: x →
/// −x.
std::vector<Vec3> chiasmSidePath(
  double halfLength, double crossingAngle, double turnRadius, bool right, double step);

/// The arc radius chiasmSidePath actually uses: min(turnRadius, H/tan(ω/2)).
double chiasmTurnRadius(double halfLength, double crossingAngle, double turnRadius);

} // namespace fiberpli
