/// PeriodicCell: an axis-aligned box that tiles space (a periodic substrate). Points are stored
/// unwrapped (a fiber stays one continuous polyline); distances use the minimum-image convention,
/// i.e. the shortest of all lattice translates of a separation.
#pragma once

#include "Geometry/Vec3.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace fiberpli
{

struct PeriodicCell
{
  Vec3 lo; ///< min corner (µm)
  Vec3 hi; ///< max corner; the cell is off while hi <= lo on any axis (the default)

  bool enabled() const { return hi.x > lo.x && hi.y > lo.y && hi.z > lo.z; }
  Vec3 edge() const { return hi - lo; }
  double volume() const
  {
    const Vec3 e = edge();
    return e.x * e.y * e.z;
  }

  /// The multiple t of the edge along `axis` that brings x + t into [lo, hi) along it: the one
  /// wrap rule (the distributed solver's boxes, Solver/Decomposition.h, wrap with it and must
  /// agree bit for bit with the pair finder's images).
  double wrapShift(double x, int axis) const
  {
    const double e = hi[axis] - lo[axis];
    return -e * std::floor((x - lo[axis]) / e);
  }
  /// The lattice vector t (integer multiples of the edges) that brings p + t into [lo, hi).
  Vec3 wrapShift(const Vec3& p) const
  {
    Vec3 t;
    for (int d = 0; d < 3; ++d)
    {
      t[d] = wrapShift(p[d], d);
    }
    return t;
  }

  /// The lattice vector t that makes d + t the shortest image of the separation d.
  Vec3 imageShift(const Vec3& d) const
  {
    const Vec3 e = edge();
    Vec3 t;
    for (int a = 0; a < 3; ++a)
    {
      t[a] = -e[a] * std::nearbyint(d[a] / e[a]);
    }
    return t;
  }

  /// True when v is a non-zero lattice vector within tol (µm) per axis; n receives it exactly
  /// (integer multiples of the edges).
  bool isLatticeVector(const Vec3& v, double tol, Vec3& n) const
  {
    const Vec3 e = edge();
    bool nonZero = false;
    for (int a = 0; a < 3; ++a)
    {
      const double k = std::nearbyint(v[a] / e[a]);
      if (!(std::fabs(v[a] - k * e[a]) <= tol))
      {
        return false;
      }
      n[a] = k * e[a];
      nonZero = nonZero || k != 0.0;
    }
    return nonZero;
  }
};

/// The one rule of how small a periodic cell may be for its links: every edge must exceed twice
/// the largest link reach w (a link's largest extent along an axis + 2 × its radius + MinimumGap),
/// so that a link meets at most one image of another per axis. "" when the cell holds `reach`,
/// else the message (naming SegmentLength and MinimumGap). The solver's pair search applies it to
/// its links (Index/PeriodicPairs.h); FiberCubeSource to the longest links the solver makes of its
/// fibers (Tissue/CubeGenerator.h), so that a periodic cube the source accepts the solver accepts.
inline std::string periodicReachProblem(const PeriodicCell& cell, double reach)
{
  const Vec3 e = cell.edge();
  const double eMin = std::min(e.x, std::min(e.y, e.z));
  if (2.0 * reach < eMin)
  {
    return {};
  }
  std::ostringstream msg;
  msg << "periodic cell edge " << eMin << " must exceed twice the largest link reach " << reach
      << " um (segment extent + 2 x radius + MinimumGap): use a larger cell, a shorter "
         "SegmentLength or a "
         "smaller MinimumGap";
  return msg.str();
}

/// True when a fiber from `first` to `last` is closed through the cell: last − first is a non-zero
/// lattice vector within 1e-5 × the cell's largest edge per axis (docs/data-contract.md); closure
/// receives it exactly. The one closure rule of the solver and the metrics.
inline bool closesThroughCell(
  const Vec3& first, const Vec3& last, const PeriodicCell& cell, Vec3& closure)
{
  if (!cell.enabled())
  {
    return false;
  }
  const Vec3 e = cell.edge();
  const double tol = 1e-5 * std::max(e.x, std::max(e.y, e.z));
  return cell.isLatticeVector(last - first, tol, closure);
}

} // namespace fiberpli
