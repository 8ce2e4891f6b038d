#include "Geometry/SegmentDistance.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace fiberpli
{

namespace
{
double clamp01(double x)
{
  return x < 0.0 ? 0.0 : (x > 1.0 ? 1.0 : x);
}

// §2.2: the minimum is attained on an interval; its midpoint makes pushes symmetric and
// independent of which end point comes first.
double parallelMidS(double A, double B, double D)
{
  const double sigma0 = -D / A;      // (b0 − a0)·u / A
  const double sigma1 = (B - D) / A; // (b1 − a0)·u / A
  const double lo = std::max(0.0, std::min(sigma0, sigma1));
  const double hi = std::min(1.0, std::max(sigma0, sigma1));
  if (lo <= hi)
  {
    return 0.5 * (lo + hi);
  }
  return std::max(sigma0, sigma1) < 0.0 ? 0.0 : 1.0;
}
} // namespace

SegmentClosest closestPoints(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1)
{
  const Vec3 u = a1 - a0;
  const Vec3 v = b1 - b0;
  const Vec3 w = a0 - b0;
  const double A = dot(u, u);
  const double B = dot(u, v);
  const double C = dot(v, v);
  const double D = dot(u, w);
  const double E = dot(v, w);
  const double L2 = std::max(A, C);
  const double epsL = 1e-24 * std::max(std::max(L2, dot(w, w)), DBL_MIN);

  SegmentClosest r;
  if (A <= epsL && C <= epsL)
  {
    r.s = 0.5;
    r.t = 0.5;
    r.parallel = true;
  }
  else if (A <= epsL)
  {
    r.s = 0.5;
    r.t = clamp01(E / C);
    r.parallel = true;
  }
  else if (C <= epsL)
  {
    r.t = 0.5;
    r.s = clamp01(-D / A);
    r.parallel = true;
  }
  else
  {
    const double den = A * C - B * B; // A·C·sin²θ: relative test below is scale free
    if (den > 1e-12 * A * C)
    {
      r.s = clamp01((B * E - C * D) / den);
    }
    else
    {
      r.s = parallelMidS(A, B, D);
      r.parallel = true;
    }
    r.t = (B * r.s + E) / C;
    if (r.t < 0.0)
    {
      r.t = 0.0;
      r.s = clamp01(-D / A);
    }
    else if (r.t > 1.0)
    {
      r.t = 1.0;
      r.s = clamp01((B - D) / A);
    }
  }
  r.p = a0 + r.s * u;
  r.q = b0 + r.t * v;
  r.distance = distance(r.p, r.q);
  return r;
}

Vec3 degenerateDirection(const Vec3& u, const Vec3& v)
{
  const Vec3 n = cross(u, v);
  const double nn = norm2(n);
  if (nn > 1e-12 * norm2(u) * norm2(v) && nn > 0.0)
  {
    return n / std::sqrt(nn);
  }
  if (norm2(u) == 0.0)
  {
    return { 1.0, 0.0, 0.0 };
  }
  int m = 0;
  for (int i = 1; i < 3; ++i)
  {
    if (std::fabs(u[i]) < std::fabs(u[m]))
    {
      m = i;
    }
  }
  Vec3 e;
  e[m] = 1.0;
  return normalized(cross(u, e));
}

Vec3 separationDirection(const SegmentClosest& c, const Vec3& u, const Vec3& v)
{
  const double scale = std::sqrt(std::max(norm2(u), norm2(v)));
  if (c.distance > 1e-12 * scale && c.distance > 0.0)
  {
    return (c.p - c.q) / c.distance;
  }
  // Two zero-length links at one point: u and v are both zero, rule 2 gives e_x.
  return degenerateDirection(norm2(u) > 0.0 ? u : v, norm2(u) > 0.0 ? v : u);
}

} // namespace fiberpli
