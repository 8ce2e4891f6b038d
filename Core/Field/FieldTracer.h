/// FieldTracer: one smooth polyline through an orientation field (docs/field-source.md §3). From a
/// seed the line is integrated both ways with steps of the segment length (RK2 or RK4 on the
/// interpolated axis, each stage sign-aligned to the heading, so the line never turns back on a
/// sign-free field). A side ends on the region's boundary (the last point is on the face) or on the
/// mask's edge (located by bisection), or when the length cap is reached; a line that comes back to
/// its seed ends there (a closed field line), so a closed field never loops forever.
#pragma once

#include "Field/OrientationField.h"
#include "Geometry/Vec3.h"

#include <string>
#include <vector>

namespace fiberpli
{

/// `IntegrationScheme` property: api strings "RK2" and "RK4".
enum class TraceScheme
{
  RK2 = 0, ///< midpoint rule: error per unit length O(h²)
  RK4 = 1  ///< classical Runge–Kutta: O(h⁴)
};

/// The api string of a scheme ("RK2", "RK4").
const char* traceSchemeName(TraceScheme scheme);

/// Why one side of a traced line stopped.
enum class TraceEnd
{
  Boundary = 0,  ///< on a face of the region
  Empty = 1,     ///< at the edge of the empty (masked) part of the field
  LengthCap = 2, ///< the whole line reached maxLength
  Closed = 3     ///< the line came back to its seed
};

struct TraceOptions
{
  double segmentLength = 2.0; ///< µm, the step; > 0
  TraceScheme scheme = TraceScheme::RK4;
  double maxLength = 0.0; ///< µm, cap on the whole line; <= 0: 4 × the region's diagonal
};

struct TracedLine
{
  std::vector<Vec3> points; ///< backward end first, the seed inside, forward end last
  TraceEnd backwardEnd = TraceEnd::Empty;
  TraceEnd forwardEnd = TraceEnd::Empty;
  double length() const;
};

/// Empty when the options are usable, else the message naming SegmentLength or MaxFiberLength.
std::string validateTraceOptions(const TraceOptions& options);

/// The length cap used for `field` (options.maxLength, or 4 × the region's diagonal).
double traceLengthCap(const OrientationField& field, const TraceOptions& options);

/// Traces the field line through `seed`. An empty field at the seed gives a line of one point.
/// Consecutive points are segmentLength apart (a RK step is a chord of that length) except the
/// last on each side, which lands on the boundary or the mask's edge: it is appended when it is at
/// least a third of a segment beyond the previous point and otherwise replaces it, so every
/// segment is between 1/3 and 4/3 of segmentLength long.
TracedLine traceFieldLine(
  const OrientationField& field, const Vec3& seed, const TraceOptions& options);

} // namespace fiberpli
