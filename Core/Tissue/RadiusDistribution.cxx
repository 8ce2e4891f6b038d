#include "Tissue/RadiusDistribution.h"

#include <cmath>

namespace fiberpli
{

double drawFiberRadius(RandomStream& rng, double radius, double spread, RadiusDistribution kind,
  double maxRadius)
{
  double r = radius;
  if (kind == RadiusDistribution::Uniform)
  {
    r = rng.uniform(radius * (1.0 - spread), radius * (1.0 + spread));
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
