#include "Tissue/FiberShape.h"

namespace fiberpli
{

std::vector<Vec3> FiberShape::points(double fraction) const
{
  std::vector<Vec3> p =
    undulatedPath(base, undulation, fraction * undulation.amplitude, pointCount);
  for (std::size_t i = 0; i < p.size() && i < jitter.size(); ++i)
    p[i] += jitter[i];
  if (base.closed)
    p.back() = p.front() + base.closure;
  return p;
}

std::vector<Vec3> drawJitter(RandomStream& rng, std::size_t count, double displacement, bool closed)
{
  std::vector<Vec3> jitter(count);
  const std::size_t drawn = closed && count > 0 ? count - 1 : count;
  for (std::size_t i = 0; i < drawn; ++i)
    for (int a = 0; a < 3; ++a)
      jitter[i][a] = rng.uniform(-displacement, displacement);
  if (closed && count > 0)
    jitter.back() = jitter.front();
  return jitter;
}

} // namespace fiberpli
