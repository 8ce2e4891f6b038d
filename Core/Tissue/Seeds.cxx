#include "Tissue/Seeds.h"

#include <cmath>

namespace fiberpli
{

std::vector<Seed2D> triangularGrid(double halfWidth, double halfHeight, double spacing)
{
  std::vector<Seed2D> seeds;
  if (!(spacing > 0.0) || !std::isfinite(spacing) || !(halfWidth >= 0.0) || !(halfHeight >= 0.0) ||
    !std::isfinite(halfWidth) || !std::isfinite(halfHeight))
  {
    return seeds;
  }
  const double h = spacing * std::sqrt(3.0) / 2.0;
  const long jMax = static_cast<long>(std::floor(halfHeight / h));
  const long iMax = static_cast<long>(std::floor(halfWidth / spacing)) + 1;
  for (long j = -jMax; j <= jMax; ++j)
  {
    // Odd rows (also negative ones) are shifted by d/2, which keeps the set symmetric in x.
    const double shift = (j % 2 != 0) ? 0.5 : 0.0;
    const double y = static_cast<double>(j) * h;
    for (long i = -iMax; i <= iMax; ++i)
    {
      const double x = (static_cast<double>(i) + shift) * spacing;
      if (std::fabs(x) <= halfWidth)
      {
        seeds.push_back({ x, y });
      }
    }
  }
  return seeds;
}

bool seedInsideCircle(const Seed2D& s, double seedRadius, double circleRadius)
{
  const double room = circleRadius - seedRadius;
  return room >= 0.0 && s.x * s.x + s.y * s.y <= room * room;
}

std::vector<Seed2D> triangularCircle(double radius, double spacing, double fiberRadius)
{
  std::vector<Seed2D> kept;
  for (const Seed2D& s : triangularGrid(radius + spacing, radius + spacing, spacing))
  {
    if (seedInsideCircle(s, fiberRadius, radius))
    {
      kept.push_back(s);
    }
  }
  return kept;
}

Seed2D randomSeedInDisc(double u1, double u2, double effectiveRadius)
{
  const double rho = (effectiveRadius > 0.0 ? effectiveRadius : 0.0) * std::sqrt(u1);
  const double angle = 2.0 * M_PI * u2;
  return { rho * std::cos(angle), rho * std::sin(angle) };
}

} // namespace fiberpli
