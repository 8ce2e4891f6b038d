/// Capsules: a fiber model flattened into its links (capsules) for the metrics, with the periodic
/// cell (Geometry/PeriodicCell.h) and this module's own segment distance. Deliberately independent
/// of Core/Geometry's closestPoints and of the solver's collision grid, so that the metrics check
/// the solver instead of repeating it.
#pragma once

#include "Geometry/PeriodicCell.h"
#include "Geometry/Vec3.h"
#include "Model/FiberModel.h"

#include <cstddef>
#include <vector>

namespace fiberpli
{

/// One link of one fiber: the segment [a, b] swept by a sphere of radius r.
struct Capsule
{
  Vec3 a, b;
  double r = 0.0;
  std::size_t fiber = 0; ///< index into FiberModel::fibers
  std::size_t link = 0;  ///< link index k within the fiber (points k, k+1)
  double arcStart = 0.0; ///< arc length from the fiber's first point to point k
  double arcEnd = 0.0;   ///< arc length from the fiber's first point to point k+1
};

struct CapsuleSet
{
  std::vector<Capsule> capsules;
  std::vector<double> fiberLength; ///< arc length of each fiber
  std::vector<std::size_t> links;  ///< number of links of each fiber
  std::vector<char> closed;        ///< 1: last point = first point + a non-zero lattice vector
};

/// Flattens the model; in a periodic cell a fiber whose end is its start shifted by a lattice
/// vector (isClosedFiber) is a closed loop, so its first and last links are neighbours.
CapsuleSet makeCapsules(const FiberModel& model, const PeriodicCell& cell);

/// Distance of point p to segment [a, b] (a zero-length segment is the point a).
double pointSegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b);

/// Smallest distance between segments [a0, a1] and [b0, b1]: the smaller of the interior critical
/// point (when both parameters lie in [0, 1]) and the four end point-to-segment distances — the
/// minimum of a convex function over a square lies inside it or on one of its edges.
double segmentDistance(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1);

/// True when two links are never compared (the solver's contract): adjacent links of one fiber,
/// or links of one fiber with less than 2·(r_a + r_b) of arc length strictly between them (going
/// either way round a closed loop).
bool chainNeighbours(const Capsule& p, const Capsule& q, const CapsuleSet& set);

} // namespace fiberpli
