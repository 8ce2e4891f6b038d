// Analytic orientation fields for the field-source tests: uniform, a circular bend about the z
// axis (e_φ, optionally masked to an annulus) and a uniform field inside a ball.
#pragma once

#include "Field/OrientationField.h"

#include <cmath>
#include <functional>

namespace fiberpli
{
namespace testing
{

/// A grid of n[a] points from `origin` with `spacing`, filled by value(point).
inline OrientationField makeField(
  Vec3 origin, double spacing, std::array<int, 3> n, const std::function<Vec3(const Vec3&)>& value)
{
  OrientationField f;
  f.origin = origin;
  f.spacing = { spacing, spacing, spacing };
  f.dimensions = n;
  f.vectors.resize(f.size());
  for (int k = 0; k < n[2]; ++k)
  {
    for (int j = 0; j < n[1]; ++j)
    {
      for (int i = 0; i < n[0]; ++i)
      {
        const Vec3 p{ origin.x + i * spacing, origin.y + j * spacing, origin.z + k * spacing };
        f.vectors[f.index(i, j, k)] = value(p);
      }
    }
  }
  normalizeOrientationField(f);
  return f;
}

/// e_φ = (−y, x, 0)/ρ about the z axis for inner <= ρ <= outer, empty elsewhere.
inline std::function<Vec3(const Vec3&)> bendAbout(double inner, double outer)
{
  return [inner, outer](const Vec3& p)
  {
    const double rho = std::hypot(p.x, p.y);
    return rho >= inner && rho <= outer ? Vec3{ -p.y / rho, p.x / rho, 0.0 } : Vec3{};
  };
}

} // namespace testing
} // namespace fiberpli
