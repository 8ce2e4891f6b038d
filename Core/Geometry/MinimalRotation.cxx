#include "Geometry/MinimalRotation.h"

#include <cmath>

namespace fiberpli
{

Vec3 rotateMinimal(const Vec3& a, const Vec3& b, const Vec3& w)
{
  const Vec3 axis = cross(a, b);
  const double s = norm(axis);
  const double c = dot(a, b);
  if (s > 1e-12)
  {
    const Vec3 k = axis / s;
    // Rodrigues with sin and cos taken from the vectors: no acos, well conditioned at any angle.
    return c * w + s * cross(k, w) + (1.0 - c) * dot(k, w) * k;
  }
  if (c > 0.0)
  {
    return w;
  }
  // 180° reversal: any axis perpendicular to a gives a minimal rotation; take a fixed one.
  Vec3 em{ 1.0, 0.0, 0.0 };
  if (std::fabs(a.y) <= std::fabs(a.x) && std::fabs(a.y) <= std::fabs(a.z))
  {
    em = { 0.0, 1.0, 0.0 };
  }
  else if (std::fabs(a.z) <= std::fabs(a.x) && std::fabs(a.z) <= std::fabs(a.y))
  {
    em = { 0.0, 0.0, 1.0 };
  }
  const Vec3 k = normalized(cross(a, em));
  return 2.0 * dot(k, w) * k - w;
}

} // namespace fiberpli
