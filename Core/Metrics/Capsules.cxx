#include "Metrics/Capsules.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

CapsuleSet makeCapsules(const FiberModel& model, const PeriodicCell& cell)
{
  CapsuleSet set;
  set.capsules.reserve(model.numberOfLinks());
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fiber = model.fibers[f];
    double arc = 0.0;
    for (std::size_t k = 0; k + 1 < fiber.size(); ++k)
    {
      Capsule c;
      c.a = fiber.points[k];
      c.b = fiber.points[k + 1];
      c.r = fiber.linkRadius(k);
      c.fiber = f;
      c.link = k;
      c.arcStart = arc;
      arc += distance(c.a, c.b);
      c.arcEnd = arc;
      set.capsules.push_back(c);
    }
    set.fiberLength.push_back(arc);
    set.links.push_back(fiber.size() > 1 ? fiber.size() - 1 : 0);
    Vec3 closure;
    set.closed.push_back(isClosedFiber(fiber, cell, closure) ? 1 : 0);
  }
  return set;
}

double pointSegmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 u = b - a;
  const double uu = dot(u, u);
  const double t = uu > 0.0 ? std::clamp(dot(p - a, u) / uu, 0.0, 1.0) : 0.0;
  return distance(p, a + t * u);
}

double segmentDistance(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1)
{
  double best =
    std::min(std::min(pointSegmentDistance(a0, b0, b1), pointSegmentDistance(a1, b0, b1)),
      std::min(pointSegmentDistance(b0, a0, a1), pointSegmentDistance(b1, a0, a1)));
  const Vec3 u = a1 - a0, v = b1 - b0, w = a0 - b0;
  const double uu = dot(u, u), uv = dot(u, v), vv = dot(v, v), uw = dot(u, w), vw = dot(v, w);
  const double det = uu * vv - uv * uv;
  if (det > 1e-12 * uu * vv) // not parallel: the only critical point of |A(s) − B(t)|²
  {
    const double s = (uv * vw - vv * uw) / det;
    const double t = (uu * vw - uv * uw) / det;
    if (s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0)
    {
      best = std::min(best, norm(w + s * u - t * v));
    }
  }
  return best;
}

bool chainNeighbours(const Capsule& p, const Capsule& q, const CapsuleSet& set)
{
  if (p.fiber != q.fiber)
  {
    return false;
  }
  const Capsule& first = p.link < q.link ? p : q;
  const Capsule& second = p.link < q.link ? q : p;
  std::size_t steps = second.link - first.link;
  double between = second.arcStart - first.arcEnd;
  if (set.closed[p.fiber])
  {
    steps = std::min(steps, set.links[p.fiber] - steps);
    between = std::min(between, set.fiberLength[p.fiber] - second.arcEnd + first.arcStart);
  }
  return steps <= 1 || between < 2.0 * (p.r + q.r);
}

} // namespace fiberpli
