/// Trajectory: the centre line of a bundle and its cross-section frames (docs/tissue-models.md §2).
/// Validation of user polylines, arc-length resampling through a centripetal Catmull–Rom curve, and
/// the rotation-minimising (parallel-transport) frame that keeps the cross-section perpendicular to
/// the tangent without twisting.
#pragma once

#include "Geometry/MinimalRotation.h" // rotateMinimal, the transport step of transportFrames
#include "Geometry/Vec3.h"

#include <cstddef>
#include <string>
#include <vector>

namespace fiberpli
{

/// Upper limit on the points of an input polyline (guards absurd inputs before allocating).
constexpr std::size_t kMaxTrajectoryPoints = 100000;

/// docs/tissue-models.md §2 and §8 (Trajectory): empty when usable, else a message naming the
/// point: fewer than 2 points, more than kMaxTrajectoryPoints, a NaN/Inf coordinate, a point that
/// repeats the previous one; with a scale array: wrong size, or a scale that is not finite and > 0.
std::string validateTrajectory(
  const std::vector<Vec3>& points, const std::vector<double>* scale = nullptr);

/// Polyline length (sum of link lengths).
double polylineLength(const std::vector<Vec3>& points);

/// A trajectory resampled by arc length; scale has one σ_k per point (1 when none was given).
struct ResampledTrajectory
{
  std::vector<Vec3> points;
  std::vector<double> scale;
};

/// docs/tissue-models.md §2 [ours] and §5.1: centripetal Catmull–Rom curve through the points
/// (phantom end points 2P0 − P1 and 2P(m−1) − P(m−2), so a 2-point input stays a straight line),
/// resampled to n = max(2, round(L/l) + 1) points equidistant in arc length (L measured on a dense
/// sampling of the curve). End points are kept exactly; scale interpolates linearly along the
/// curve. Precondition: validateTrajectory(points, scale) is empty and segmentLength > 0.
ResampledTrajectory resampleTrajectory(
  const std::vector<Vec3>& points, const std::vector<double>* scale, double segmentLength);

/// Per trajectory point: unit tangent t_k and the transported images u_k, v_k of the seed-plane
/// axes e_x, e_y (docs/tissue-models.md §2). t_k by central differences (one-sided at the ends);
/// the frame starts from t_(−1) = e_z and is carried by the minimal rotation taking t_(k−1) to t_k
/// at every k. Transporting (u, v) is the same as transporting every seed offset, since the
/// rotations are linear: offset of seed (x, y) at k = x·u_k + y·v_k.
struct TrajectoryFrames
{
  std::vector<Vec3> tangent;
  std::vector<Vec3> u;
  std::vector<Vec3> v;
};

/// Frames of a polyline without repeated consecutive points (see TrajectoryFrames).
TrajectoryFrames transportFrames(const std::vector<Vec3>& points);

/// Smallest circumradius of three consecutive points (docs/solver.md §5.2 formula, written
/// with |cross| instead of Heron), and the index of its middle point; +inf for straight lines or
/// fewer than 3 points. Used to warn when the bundle would fold at a bend (docs/tissue-models.md
/// §2).
double minimumCircumradius(const std::vector<Vec3>& points, std::size_t* where = nullptr);

} // namespace fiberpli
