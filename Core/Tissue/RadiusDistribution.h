/// RadiusDistribution: per-fiber radii of a bundle (tissue-models.md §5.3 [ours]).
#pragma once

#include "Util/Random.h"

namespace fiberpli
{

/// `RadiusDistribution` property: api strings "LogNormal" (default) and "Uniform".
enum class RadiusDistribution
{
  LogNormal = 0, ///< r·exp(s·z), z ~ N(0, 1) truncated to |z| <= 3 (r is the median)
  Uniform = 1    ///< U[r(1 − s), r(1 + s)], needs s < 1 (r is the mean)
};

/// Draws one fiber radius, tissue-models.md §5.3: nominal radius r, spread s >= 0, clamped to
/// <= maxRadius (the bundle radius). Always consumes the same kind of draws for a given
/// distribution, also for s = 0 (which returns r exactly), so that the draws after the radius
/// (Ranvier phase, displacements; §7) do not depend on the spread. The truncation of z is done by
/// rejection inside the fiber's own stream.
double drawFiberRadius(RandomStream& rng, double radius, double spread, RadiusDistribution kind,
  double maxRadius);

} // namespace fiberpli
