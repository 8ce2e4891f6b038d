// Independent reference for the collision tests: segment distance as the minimum of the four
// end point–segment distances and the interior critical point (a different construction from
// Geometry/SegmentDistance), and an O(N²) pair list with the docs/solver.md §3.1 rules written out
// again.
#pragma once

#include "Model/FiberModel.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace fiberpli_test
{
using fiberpli::Vec3;

inline double refPointSegment(const Vec3& x, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double l2 = fiberpli::dot(ab, ab);
  double t = l2 > 0.0 ? fiberpli::dot(x - a, ab) / l2 : 0.0;
  t = std::min(1.0, std::max(0.0, t));
  return fiberpli::norm(x - (a + t * ab));
}

inline double refSegmentDistance(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1)
{
  double best = std::min(std::min(refPointSegment(a0, b0, b1), refPointSegment(a1, b0, b1)),
    std::min(refPointSegment(b0, a0, a1), refPointSegment(b1, a0, a1)));
  const Vec3 u = a1 - a0;
  const Vec3 v = b1 - b0;
  const Vec3 w = a0 - b0;
  const double A = fiberpli::dot(u, u), B = fiberpli::dot(u, v), C = fiberpli::dot(v, v);
  const double D = fiberpli::dot(u, w), E = fiberpli::dot(v, w);
  const double den = A * C - B * B;
  if (den > 0.0)
  {
    const double s = (B * E - C * D) / den;
    const double t = (A * E - B * D) / den;
    if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0)
    {
      best = std::min(best, fiberpli::norm((a0 + s * u) - (b0 + t * v)));
    }
  }
  return best;
}

struct RefLink
{
  Vec3 p0, p1;
  double rho;
  std::size_t fiber, k;
  double arc0, arc1;
};

inline std::vector<RefLink> refLinks(const fiberpli::FiberModel& m)
{
  std::vector<RefLink> links;
  for (std::size_t f = 0; f < m.fibers.size(); ++f)
  {
    const auto& fib = m.fibers[f];
    double arc = 0.0;
    for (std::size_t k = 0; k + 1 < fib.points.size(); ++k)
    {
      const double len = fiberpli::norm(fib.points[k + 1] - fib.points[k]);
      links.push_back({ fib.points[k], fib.points[k + 1], std::max(fib.radii[k], fib.radii[k + 1]),
        f, k, arc, arc + len });
      arc += len;
    }
  }
  return links;
}

/// All (a, b), a < b global link ids, with δ < ρa + ρb + gap; same fiber: not adjacent and the
/// arc length strictly between them >= 2·(ρa + ρb).
inline std::vector<std::pair<std::size_t, std::size_t>> refPairs(
  const std::vector<RefLink>& l, double gap = 0.0)
{
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (std::size_t a = 0; a < l.size(); ++a)
  {
    for (std::size_t b = a + 1; b < l.size(); ++b)
    {
      if (l[a].fiber == l[b].fiber)
      {
        if (l[b].k - l[a].k <= 1 || l[b].arc0 - l[a].arc1 < 2.0 * (l[a].rho + l[b].rho))
        {
          continue;
        }
      }
      if (refSegmentDistance(l[a].p0, l[a].p1, l[b].p0, l[b].p1) < l[a].rho + l[b].rho + gap)
      {
        out.emplace_back(a, b);
      }
    }
  }
  return out;
}

inline std::size_t refCollisionCount(const fiberpli::FiberModel& m, double gap = 0.0)
{
  return refPairs(refLinks(m), gap).size();
}
} // namespace fiberpli_test
