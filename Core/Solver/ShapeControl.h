/// ShapeControl: the solver's shape rules per fiber (docs/solver.md §5): segment length
/// (split / merge, §5.1) and curvature (minimum circumradius and 60° vertex angle, §5.2).
/// Both are sequential inside one fiber and independent between fibers (parallel over fibers).
#pragma once

#include "Geometry/Vec3.h"
#include "Model/FiberModel.h"

#include <string>
#include <vector>

namespace fiberpli
{

/// What end points may do when they move (docs/solver.md §4.2).
enum class EndPointRule
{
  Perpendicular = 0, ///< move only perpendicular to the end link (paper; fibers keep their length)
  Free = 1,          ///< move like any other point (fastPLI)
  Fixed = 2          ///< never move (anchored ends, stitched tiles)
};

/// Per-point data that travels with the points through split and merge: the velocity (drag
/// memory) and the fractional input point index (3.5 = midpoint of input points 3 and 4); and
/// the fiber's radii as it entered the run (by input point index), from which a split takes the
/// new point's radius, so that a radius profile (beading, nodes) survives any number of merges and
/// splits instead of being averaged away.
struct FiberPointState
{
  std::vector<Vec3> velocity;
  std::vector<double> source;
  std::vector<double> inputRadii; ///< empty: a split takes the mean of its two points' radii
};

/// The radius of a fiber's input profile at fractional input point index s (linear between input
/// points, clamped to the ends); profile must not be empty.
double profileRadius(const std::vector<double>& profile, double s);

/// Applies the end-point rule to a displacement d of point i (0 or n−1) of fiber f; interior
/// points are returned unchanged (docs/solver.md §4.2).
Vec3 constrainEndMove(const Fiber& f, std::size_t i, const Vec3& d, EndPointRule rule);

/// Split / merge of docs/solver.md §5.1 with l_min = 2/3·L̄, l_max = 4/3·L̄ (segmentLength =
/// L̄ > 0). A split inserts the mean position, velocity and source index, and the input radius
/// profile's value at that index (or the mean radius without a profile); a merge deletes
/// one point (never an end point, the one with the weaker radius feature). A fiber of minPoints
/// points is never shortened (2; a fiber closed through a periodic cell needs 3). state arrays must
/// have f.size() entries. Returns true when a point was inserted or removed. Bounded: a link whose
/// midpoint rounds to one of its ends is left as it is, and one pass takes at most four times the
/// steps its links can need.
bool controlSegmentLength(
  Fiber& f, FiberPointState& state, double segmentLength, std::size_t minPoints = 2);

/// Largest |coordinate| of a point relative to the segment length L̄ (µm/µm): there neighbouring
/// doubles are 2.2e-4 L̄ apart, still fine enough for split and merge; much farther out a
/// link's midpoint rounds to one of its ends (docs/solver.md §5.1).
constexpr double kMaxCoordinateOverSegment = 1e12;

/// "" when every coordinate of the model is within kMaxCoordinateOverSegment × segmentLength of
/// the origin (or split/merge is off, segmentLength <= 0), else a message naming the fiber, the
/// point and the value. The solver refuses such input (fresh or resumed) before it starts.
std::string checkCoordinateResolution(const FiberModel& model, double segmentLength);

/// Curvature rule of docs/solver.md §5.2 (division-free): a vertex whose circumradius is
/// below minRadius or whose angle is below 60° moves by +0.2·step towards the inside of the bend,
/// its neighbours by −0.05·step; all moves of the fiber are summed in vertex order, then applied
/// (end points obey rule). minRadius <= 0 disables it. Returns true when a vertex violated.
/// closure (non-null): the fiber is closed through a periodic cell, its last point is the first
/// shifted by *closure; the first/last point is then a vertex like any other (its neighbours are
/// p_{n−2} − closure and p_1), has no end-point rule, and both copies move alike.
bool controlCurvature(
  Fiber& f, double minRadius, double step, EndPointRule rule, const Vec3* closure = nullptr);

/// True when every interior vertex (and with closure the first/last one) has circumradius >=
/// minRadius and angle >= 60° (same tests as controlCurvature; degenerate vertices with a
/// zero-length link are skipped).
bool curvatureOk(const Fiber& f, double minRadius, const Vec3* closure = nullptr);

} // namespace fiberpli
