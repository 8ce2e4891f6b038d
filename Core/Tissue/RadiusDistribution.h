/// RadiusDistribution: per-fiber radii of a bundle or cube (docs/tissue-models.md §5.3 [ours]).
#pragma once

#include "Util/EnumCode.h"
#include "Util/Random.h"

#include <string>

namespace fiberpli
{

/// `RadiusDistribution` property: api strings "LogNormal" (default), "Uniform", "Gamma" and
/// "Constant".
/// A spread s = 0 gives the constant radius r with every distribution.
enum class RadiusDistribution
{
  LogNormal = 0, ///< r·exp(s·z), z ~ N(0, 1) truncated to |z| <= 3 (r is the median)
  Uniform = 1,   ///< U[r(1 − s), r(1 + s)], needs s < 1 (r is the mean)
  /// Gamma with mean r and coefficient of variation s: shape α = 1/s², scale β = r·s² (MEDUSA's
  /// and CATERPillar's α = 4, β = 0.25 µm is r = 1, s = 0.5), truncated to [r/4, 4r] by rejection
  /// so that a rare tiny radius does not slow the whole solve (its step is relative to the
  /// smallest radius).
  Gamma = 2,
  Constant = 3 ///< always r, the spread is ignored, no draws
};

/// The api string of a radius distribution ("LogNormal", "Uniform", "Gamma", "Constant").
const char* radiusDistributionName(RadiusDistribution kind);

/// The `RadiusDistribution` code as the enum (Util/EnumCode.h): "" or the message naming the code.
inline std::string radiusDistributionFromCode(int code, RadiusDistribution& kind)
{
  return enumFromCode(code, static_cast<int>(RadiusDistribution::Constant), "RadiusDistribution",
    "0 (LogNormal) to 3 (Constant)", kind);
}

/// Largest RadiusSpread of LogNormal: its radii r·exp(s·z), |z| <= 3, then span e^±6.
constexpr double kMaxLogNormalSpread = 2.0;

/// Empty when spread s and distribution are usable, else a message naming RadiusSpread (or
/// RadiusDistribution, for a value outside the enum).
std::string validateRadiusDistribution(RadiusDistribution kind, double spread);

/// The smallest radius the distribution can return, as a fraction of r.
double minimumRadiusFactor(RadiusDistribution kind, double spread);

/// Draws one fiber radius, docs/tissue-models.md §5.3: nominal radius r, spread s >= 0, clamped to
/// <= maxRadius (the bundle radius). Always consumes the same kind of draws for a given
/// distribution, also for s = 0 (which returns r exactly; Gamma with s = 0 draws nothing), so that
/// the draws after the radius (Ranvier phase, displacements; §7) do not depend on the spread.
/// Truncations are done by rejection inside the fiber's own stream.
double drawFiberRadius(
  RandomStream& rng, double radius, double spread, RadiusDistribution kind, double maxRadius);

} // namespace fiberpli
