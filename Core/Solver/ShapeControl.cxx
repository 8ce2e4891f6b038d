#include "Solver/ShapeControl.h"
#include "Util/NumberFormat.h"

#include <cmath>

namespace fiberpli
{

namespace
{
// Radius feature strength (a Ranvier node point has a large one): the dev rule of §5.1.
double radiusDeviation(const Fiber& f, std::size_t j)
{
  return std::fabs(f.radii[j] - 0.5 * (f.radii[j - 1] + f.radii[j + 1]));
}

void erasePoint(Fiber& f, FiberPointState& st, std::size_t j)
{
  const auto off = static_cast<std::ptrdiff_t>(j);
  f.points.erase(f.points.begin() + off);
  f.radii.erase(f.radii.begin() + off);
  st.velocity.erase(st.velocity.begin() + off);
  st.source.erase(st.source.begin() + off);
}

// Whether the midpoint of a link is a third point: far from the origin (|x| ~ 3e16 µm, where
// neighbouring doubles are 4 µm apart) it rounds to an end point, and splitting would never end.
bool splittable(const Vec3& a, const Vec3& b)
{
  const Vec3 m = 0.5 * (a + b);
  return !(m == a) && !(m == b);
}

void insertMidpoint(Fiber& f, FiberPointState& st, std::size_t i)
{
  const auto off = static_cast<std::ptrdiff_t>(i + 1);
  const Vec3 p = 0.5 * (f.points[i] + f.points[i + 1]);
  const Vec3 v = 0.5 * (st.velocity[i] + st.velocity[i + 1]);
  const double s = 0.5 * (st.source[i] + st.source[i + 1]);
  const double r =
    st.inputRadii.empty() ? 0.5 * (f.radii[i] + f.radii[i + 1]) : profileRadius(st.inputRadii, s);
  f.points.insert(f.points.begin() + off, p);
  f.radii.insert(f.radii.begin() + off, r);
  st.velocity.insert(st.velocity.begin() + off, v);
  st.source.insert(st.source.begin() + off, s);
}

} // namespace

double profileRadius(const std::vector<double>& profile, double s)
{
  const std::size_t n = profile.size();
  if (n == 1 || !(s > 0.0))
    return profile.front();
  if (s >= static_cast<double>(n - 1))
    return profile.back();
  const auto k = static_cast<std::size_t>(s);
  const double t = s - static_cast<double>(k);
  // r_k + t·(r_{k+1} − r_k): exactly r_k on a constant profile, as the mean of equal radii is.
  return profile[k] + t * (profile[k + 1] - profile[k]);
}

namespace
{
enum class Bend
{
  Ok,
  Violated,
  Degenerate
};

// §5.2 [ours]: R < R_min ⇔ 2·|e1 × e2|·R_min > a·b·c (R = abc / (2|e1 × e2|)); angle < 60° ⇔
// (p_{i−1} − p_i)·(p_{i+1} − p_i) > ½·a·b. No division, no acos, no NaN.
Bend classifyVertex(const Vec3& pm, const Vec3& pi, const Vec3& pp, double minRadius)
{
  const Vec3 e1 = pi - pm;
  const Vec3 e2 = pp - pi;
  const double a = norm(e1);
  const double b = norm(e2);
  if (!(a > 1e-12 * b) || !(b > 1e-12 * a))
  {
    return Bend::Degenerate;
  }
  const double c = distance(pp, pm);
  if (2.0 * norm(cross(e1, e2)) * minRadius > a * b * c)
  {
    return Bend::Violated;
  }
  if (dot(pm - pi, pp - pi) > 0.5 * a * b)
  {
    return Bend::Violated;
  }
  return Bend::Ok;
}
} // namespace

Vec3 constrainEndMove(const Fiber& f, std::size_t i, const Vec3& d, EndPointRule rule)
{
  const std::size_t n = f.points.size();
  if (rule == EndPointRule::Free || n < 2 || (i != 0 && i != n - 1))
  {
    return d;
  }
  if (rule == EndPointRule::Fixed)
  {
    return Vec3{};
  }
  const Vec3 t = normalized(i == 0 ? f.points[1] - f.points[0] : f.points[n - 1] - f.points[n - 2]);
  return d - dot(d, t) * t;
}

bool controlSegmentLength(
  Fiber& f, FiberPointState& st, double segmentLength, std::size_t minPoints)
{
  if (!(segmentLength > 0.0))
  {
    return false;
  }
  const double lMin = segmentLength * (2.0 / 3.0);
  const double lMax = segmentLength * (4.0 / 3.0);
  // A bound on the steps of this pass (splits, merges, advances). Exact arithmetic needs fewer
  // than 2·ceil(len / lMin) per link for its splits and advances (halving ends at pieces longer
  // than lMin) plus two per merge, at most one merge per point and one split after it: four
  // times that is never reached, and ends the pass should rounding ever make a split and a merge
  // undo each other forever.
  double budget = 64.0 + 16.0 * static_cast<double>(f.points.size());
  for (std::size_t k = 0; k + 1 < f.points.size(); ++k)
  {
    budget += 8.0 * std::ceil(distance(f.points[k], f.points[k + 1]) / lMin);
  }
  bool changed = false;
  std::size_t i = 0;
  while (i + 1 < f.points.size() && budget-- > 0.0)
  {
    const std::size_t n = f.points.size();
    const double len = distance(f.points[i], f.points[i + 1]);
    if (len > lMax && splittable(f.points[i], f.points[i + 1]))
    {
      insertMidpoint(f, st, i);
      changed = true;
      continue; // re-check link i, now half as long
    }
    if (len > lMax)
    {
      ++i; // the midpoint rounds to an end point: double precision cannot shorten this link
      continue;
    }
    if (len < lMin && n > minPoints)
    {
      if (i == 0)
      {
        erasePoint(f, st, 1); // end points are never removed
      }
      else if (i == n - 2)
      {
        erasePoint(f, st, n - 2);
        --i; // the merged link i−1 may now be too long: re-check it in this pass
      }
      else if (radiusDeviation(f, i + 1) > radiusDeviation(f, i))
      {
        erasePoint(f, st, i); // keep the stronger radius feature (Ranvier node)
        --i;
      }
      else
      {
        erasePoint(f, st, i + 1);
      }
      changed = true;
      continue;
    }
    ++i;
  }
  return changed;
}

bool controlCurvature(
  Fiber& f, double minRadius, double step, EndPointRule rule, const Vec3* closure)
{
  const std::size_t n = f.points.size();
  if (!(minRadius > 0.0) || n < 3)
  {
    return false;
  }
  std::vector<Vec3> delta(n);
  bool violated = false;
  // Vertex i with neighbours pm, pp; its neighbours' moves go to points im and ip.
  auto bend = [&](const Vec3& pm, std::size_t i, const Vec3& pp, std::size_t im, std::size_t ip)
  {
    const Vec3& pi = f.points[i];
    if (classifyVertex(pm, pi, pp, minRadius) != Bend::Violated)
    {
      return;
    }
    violated = true;
    const Vec3 d = normalized((pm - pi) + (pp - pi)); // towards the inside of the bend
    delta[i] += (0.2 * step) * d;
    delta[im] -= (0.05 * step) * d;
    delta[ip] -= (0.05 * step) * d;
  };
  if (closure)
  {
    bend(f.points[n - 2] - *closure, 0, f.points[1], n - 2, 1);
  }
  for (std::size_t i = 1; i + 1 < n; ++i)
  {
    bend(f.points[i - 1], i, f.points[i + 1], i - 1, i + 1);
  }
  if (!violated)
  {
    return false;
  }
  if (closure)
  {
    // First and last point are one point of the closed fiber.
    delta[0] += delta[n - 1];
    delta[n - 1] = delta[0];
  }
  else
  {
    // End-point rule on the geometry before the move (the end link of this moment).
    delta[0] = constrainEndMove(f, 0, delta[0], rule);
    delta[n - 1] = constrainEndMove(f, n - 1, delta[n - 1], rule);
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    f.points[i] += delta[i];
  }
  return true;
}

bool curvatureOk(const Fiber& f, double minRadius, const Vec3* closure)
{
  const std::size_t n = f.points.size();
  if (!(minRadius > 0.0) || n < 3)
  {
    return true;
  }
  if (closure &&
    classifyVertex(f.points[n - 2] - *closure, f.points[0], f.points[1], minRadius) ==
      Bend::Violated)
  {
    return false;
  }
  for (std::size_t i = 1; i + 1 < n; ++i)
  {
    if (classifyVertex(f.points[i - 1], f.points[i], f.points[i + 1], minRadius) == Bend::Violated)
    {
      return false;
    }
  }
  return true;
}

std::string checkCoordinateResolution(const FiberModel& model, double segmentLength)
{
  if (!(segmentLength > 0.0))
  {
    return {};
  }
  const double limit = kMaxCoordinateOverSegment * segmentLength;
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fib = model.fibers[f];
    for (std::size_t i = 0; i < fib.points.size(); ++i)
    {
      for (int d = 0; d < 3; ++d)
      {
        if (!(std::fabs(fib.points[i][d]) <= limit))
        {
          return "fiber " + formatNumber(f) + " (fiber_id " + formatNumber(fib.id) + ") point " +
            formatNumber(i) + " has coordinate " + formatNumber(fib.points[i][d]) +
            " um, more than " + formatNumber(kMaxCoordinateOverSegment) + " x the segment length " +
            formatNumber(segmentLength) +
            " um: double precision cannot resolve links of that length so far from the origin "
            "(move the model "
            "towards the origin or raise SegmentLength)";
        }
      }
    }
  }
  return {};
}

} // namespace fiberpli
