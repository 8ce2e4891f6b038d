#include "Tissue/RadiusDistribution.h"

#include "Util/NumberFormat.h"
#include "Util/ValueCheck.h"

#include <cmath>

namespace fiberpli
{

namespace
{
// Marsaglia & Tsang (2000) for shape a >= 1, scale 1; for a < 1 the boost Gamma(a + 1)·U^(1/a).
double drawGamma(RandomStream& rng, double a)
{
  const double boost = a < 1.0 ? std::pow(rng.uniform(), 1.0 / a) : 1.0;
  const double d = (a < 1.0 ? a + 1.0 : a) - 1.0 / 3.0;
  const double c = 1.0 / std::sqrt(9.0 * d);
  while (true)
  {
    const double z = rng.normal();
    const double v = 1.0 + c * z;
    if (v <= 0.0)
    {
      continue;
    }
    const double v3 = v * v * v;
    const double u = 1.0 - rng.uniform(); // (0, 1]
    if (std::log(u) < 0.5 * z * z + d - d * v3 + d * std::log(v3))
    {
      return d * v3 * boost;
    }
  }
}
} // namespace

const char* radiusDistributionName(RadiusDistribution kind)
{
  switch (kind)
  {
    case RadiusDistribution::Uniform:
      return "Uniform";
    case RadiusDistribution::Gamma:
      return "Gamma";
    case RadiusDistribution::Constant:
      return "Constant";
    default:
      return "LogNormal";
  }
}

std::string validateRadiusDistribution(RadiusDistribution kind, double spread)
{
  RadiusDistribution known;
  // r·exp(±3s) must stay a usable radius: beyond kMaxLogNormalSpread the radii span more than
  // e^±6 (a factor 160 000 between the thinnest and the thickest fiber) and, for large s,
  // underflow to 0.
  return ValueChecks()
    .then(radiusDistributionFromCode(static_cast<int>(kind), known))
    .require(std::isfinite(spread) && spread >= 0.0, "RadiusSpread", spread, ">= 0")
    .require(kind != RadiusDistribution::Uniform || spread < 1.0, "RadiusSpread", spread,
      "< 1 for RadiusDistribution Uniform")
    .require(kind != RadiusDistribution::LogNormal || spread <= kMaxLogNormalSpread, "RadiusSpread",
      spread,
      "<= " + formatNumber(kMaxLogNormalSpread) +
        " for RadiusDistribution LogNormal (radii r*exp(s*z), |z| <= 3)")
    .require(kind != RadiusDistribution::Gamma || spread <= 2.0, "RadiusSpread", spread,
      "<= 2 for RadiusDistribution Gamma (shape 1/s^2 >= 0.25)")
    .error();
}

double minimumRadiusFactor(RadiusDistribution kind, double spread)
{
  if (!(spread > 0.0) || kind == RadiusDistribution::Constant)
  {
    return 1.0;
  }
  switch (kind)
  {
    case RadiusDistribution::Uniform:
      return 1.0 - spread;
    case RadiusDistribution::Gamma:
      return 0.25;
    default:
      return std::exp(-3.0 * spread);
  }
}

double drawFiberRadius(
  RandomStream& rng, double radius, double spread, RadiusDistribution kind, double maxRadius)
{
  double r = radius;
  if (kind == RadiusDistribution::Constant)
  {
    // no draws
  }
  else if (kind == RadiusDistribution::Uniform)
  {
    r = rng.uniform(radius * (1.0 - spread), radius * (1.0 + spread));
  }
  else if (kind == RadiusDistribution::Gamma)
  {
    if (spread > 0.0)
    {
      const double shape = 1.0 / (spread * spread);
      const double scale = radius * spread * spread;
      do
      {
        r = scale * drawGamma(rng, shape);
      } while (r < 0.25 * radius || r > 4.0 * radius);
    }
  }
  else
  {
    double z = rng.normal();
    // P(|z| > 3) = 0.27 %: the loop ends almost always at once.
    while (std::fabs(z) > 3.0)
    {
      z = rng.normal();
    }
    r = spread > 0.0 ? radius * std::exp(spread * z) : radius;
  }
  return r < maxRadius ? r : maxRadius;
}

} // namespace fiberpli
