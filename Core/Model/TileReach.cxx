#include "Model/TileReach.h"

#include "Model/PeriodicTiling.h"

#include <algorithm>

namespace fiberpli
{

TileReach unite(const TileReach& a, const TileReach& b)
{
  if (b.empty())
  {
    return a;
  }
  TileReach u = a;
  u.radiusScale = std::max(a.radiusScale, b.radiusScale);
  for (int d = 0; d < 3; ++d)
  {
    u.box[2 * d] = a.empty() ? b.box[2 * d] : std::min(a.box[2 * d], b.box[2 * d]);
    u.box[2 * d + 1] = a.empty() ? b.box[2 * d + 1] : std::max(a.box[2 * d + 1], b.box[2 * d + 1]);
  }
  return u;
}

bool linkReaches(const Fiber& fiber, const TileReach& reach, const Vec3& shift)
{
  if (reach.empty())
  {
    return false;
  }
  for (std::size_t k = 0; k + 1 < fiber.size(); ++k)
  {
    const double grow = reach.radiusScale * fiber.linkRadius(k);
    bool overlaps = true;
    for (int d = 0; d < 3 && overlaps; ++d)
    {
      // The same sum as the translate tileModel makes (p + t), so both agree on every bit.
      const double a = fiber.points[k][d] + shift[d], b = fiber.points[k + 1][d] + shift[d];
      overlaps =
        std::min(a, b) - grow <= reach.box[2 * d + 1] && std::max(a, b) + grow >= reach.box[2 * d];
    }
    if (overlaps)
    {
      return true;
    }
  }
  return false;
}

bool fiberReaches(const Fiber& fiber, const TileReach& reach)
{
  return reach.periodic ? periodicTranslateReaches(fiber, reach) : linkReaches(fiber, reach);
}

} // namespace fiberpli
