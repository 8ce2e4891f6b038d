/// FiberShape: per-fiber and per-bundle shape statistics of a fiber model — orientation order (c2)
/// and mean direction, tortuosity, link length and radius ranges.
#pragma once

#include "Geometry/Vec3.h"
#include "Metrics/Capsules.h"
#include "Model/FiberModel.h"

#include <cstddef>
#include <vector>

namespace fiberpli
{

/// min / mean / max of a set of values (all NaN when the set is empty).
struct Range
{
  double min, mean, max;
  std::size_t count = 0;
};

/// Orientation of a set of links: the length-weighted orientation tensor T = Σ l·u·uᵀ / Σ l of the
/// unit link directions u. c2 = ⟨P2(cos θ)⟩ = (3·λ1 − 1)/2 with λ1 the largest eigenvalue of T
/// (in [0, 1] since λ1 >= 1/3: 1 all parallel, 0 isotropic); direction = its
/// eigenvector, sign chosen so that its largest component is positive. NaN without links.
struct Orientation
{
  double c2;
  Vec3 direction;
};

struct BundleShape
{
  int bundle = 0;
  std::size_t fibers = 0;
  Orientation orientation;
  Range tortuosity;
  Range fiberLength;
};

struct ShapeResult
{
  std::vector<double> fiberLength; ///< arc length of each fiber
  std::vector<double> tortuosity;  ///< arc length / end-to-end distance (NaN if the ends coincide)
  Orientation orientation;         ///< of all links
  Range tortuosityRange, linkLength, radius;
  std::vector<BundleShape> bundles; ///< in increasing bundle id
};

ShapeResult fiberShape(const FiberModel& model, const CapsuleSet& set);

} // namespace fiberpli
