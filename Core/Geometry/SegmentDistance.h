/// SegmentDistance: closest points of two line segments (docs/solver.md §2) and the
/// deterministic separation direction of a pair whose axes touch (§2.4). Scale free: every
/// threshold is relative to the segment lengths, so µm and mm models take the same branches.
#pragma once

#include "Geometry/Vec3.h"

namespace fiberpli
{

/// Result of closestPoints. A(s) = a0 + s·(a1 − a0), B(t) = b0 + t·(b1 − b0), s, t ∈ [0, 1].
struct SegmentClosest
{
  double s = 0.0;
  double t = 0.0;
  Vec3 p;                ///< A(s)
  Vec3 q;                ///< B(t)
  double distance = 0.0; ///< |p − q|
  bool parallel = false; ///< the parallel branch (§2.2) or a zero-length segment was used
};

/// Closest points of segments [a0, a1] and [b0, b1] (docs/solver.md §2.1, §2.2): clamped
/// parametric minimum with relative tolerances; parallel segments take the middle of their
/// overlap; a zero-length segment uses parameter 0.5 on its side. Never divides by zero, never
/// returns NaN for finite input.
SegmentClosest closestPoints(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1);

/// Unit direction along which link a moves (link b moves opposite) when the axes meet
/// (docs/solver.md §2.4): u × v when the links are not parallel, else u × e_m with e_m the
/// coordinate axis least aligned with u (ties → lower axis), e_x when u = 0.
/// u = a1 − a0 and v = b1 − b0 where a is the link with the smaller global id.
Vec3 degenerateDirection(const Vec3& u, const Vec3& v);

/// Unit direction of the push on link a (b gets the opposite): (p − q)/|p − q|, or
/// degenerateDirection(u, v) when |p − q| <= 1e-12 · (longest segment length) (§2.4).
Vec3 separationDirection(const SegmentClosest& c, const Vec3& u, const Vec3& v);

} // namespace fiberpli
