/// FiberModel: the data contract (docs/data-contract.md §1) in Core form. A fiber is an ordered
/// polyline of points with one radius per point (µm); a link (p_i, p_i+1) is a capsule of radius
/// max(r_i, r_i+1). Every fiber carries its fiber id and the bundle (population) it belongs to.
#pragma once

#include "Geometry/PeriodicCell.h"
#include "Geometry/Vec3.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

struct Fiber
{
  std::vector<Vec3> points;
  std::vector<double> radii; ///< one per point, > 0
  std::int64_t id = 0;       ///< unique within a model (cell array fiber_id)
  int bundle = 0;            ///< bundle / population (cell array bundle_id)
  /// Optional point array inner_radius (Model/InnerRadii.h): empty, or one axon radius per point
  /// inside the myelin sheath, 0 < inner <= radius. Filled only where an algorithm uses it
  /// (metrics, PLI); algorithms that reshape fibers (the solver) leave it out.
  std::vector<double> innerRadii;

  std::size_t size() const { return points.size(); }
  /// Capsule radius of link k (paper eq. 1).
  double linkRadius(std::size_t k) const
  {
    return radii[k] > radii[k + 1] ? radii[k] : radii[k + 1];
  }
};

struct FiberModel
{
  std::vector<Fiber> fibers;

  std::size_t numberOfPoints() const;
  std::size_t numberOfLinks() const;
  bool empty() const { return fibers.empty(); }
};

/// Axis-aligned bounds of all points, enlarged by each point's radius when withRadii is true.
/// Returns false for a model without points.
bool modelBounds(const FiberModel& model, bool withRadii, Vec3& lo, Vec3& hi);

/// Largest radius of the fibers that have links (>= 2 points); 0 for a model without links.
double largestRadius(const FiberModel& model);

/// True when the fiber is a closed loop through the cell: it has >= 3 points (a loop needs two
/// distinct links) and last point − first point is a non-zero lattice vector (closesThroughCell);
/// closure receives that vector exactly. The one closure rule of the solver and the metrics.
bool isClosedFiber(const Fiber& fiber, const PeriodicCell& cell, Vec3& closure);

/// Whether validateModel accepts fibers of fewer than 2 points. The data contract refuses them;
/// the collision solver takes them and copies them through unchanged (they have no link).
enum class ShortFibers
{
  Refused,
  Allowed
};

/// Checks the data contract: every fiber has >= 2 points (unless shortFibers is Allowed),
/// radii.size() == points.size(), finite coordinates, finite radii > 0. Returns an empty string
/// when valid, else a message that names the fiber (by index and id) and the point; badFiber
/// (optional) receives the fiber's index.
std::string validateModel(const FiberModel& model, std::size_t* badFiber = nullptr,
  ShortFibers shortFibers = ShortFibers::Refused);

/// Bytes a generated model of `fibers` fibers with `points` points in all takes, together with one
/// converted copy of the same size (the polydata a source hands on): for the sources' memory guard.
inline double fiberModelBytes(double fibers, double points)
{
  constexpr double kPerPoint = sizeof(Vec3) + sizeof(double);
  constexpr double kPerFiber = sizeof(Fiber) + 64.0; // + two allocations' bookkeeping
  return 2.0 * (fibers * kPerFiber + points * kPerPoint);
}

} // namespace fiberpli
