/// Angles: cos and sin that are exact at multiples of a quarter turn. π/2 has no exact double, so
/// std::cos(π/2) = 6e-17 and std::sin(π) = 1.2e-16: in the 90°/180°/270° views that puts the rays
/// one rounding step off the voxel-centre planes, where an interpolated axis switches neighbours.
#pragma once

#include <cmath>

namespace fiberpli
{

/// c = cos a, s = sin a (a in radians); exactly 0 or ±1 when a is within 1e-12 of a multiple of
/// π/2.
inline void cosSinQuarterExact(double a, double& c, double& s)
{
  const double q = a / (M_PI / 2.0);
  const double r = std::round(q);
  if (std::fabs(q - r) < 1e-12 && std::fabs(r) < 1e15)
  {
    const long long k = ((static_cast<long long>(r) % 4) + 4) % 4;
    const double cs[4][2] = { { 1, 0 }, { 0, 1 }, { -1, 0 }, { 0, -1 } };
    c = cs[k][0];
    s = cs[k][1];
    return;
  }
  c = std::cos(a);
  s = std::sin(a);
}

} // namespace fiberpli
