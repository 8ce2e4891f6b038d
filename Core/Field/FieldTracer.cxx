#include "Field/FieldTracer.h"

#include "Util/NumberFormat.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fiberpli
{

namespace
{
/// One integration step of length h from p along `heading`. False when a stage falls outside the
/// region or on the empty field; then nothing is changed.
bool step(const OrientationField& f, TraceScheme scheme, double h, Vec3& p, Vec3& heading)
{
  Vec3 k1, k2, k3, k4;
  if (!fieldDirection(f, p, heading, k1) || !fieldDirection(f, p + (0.5 * h) * k1, k1, k2))
  {
    return false;
  }
  Vec3 move;
  Vec3 next;
  if (scheme == TraceScheme::RK2)
  {
    move = k2;
    next = k2;
  }
  else
  {
    if (!fieldDirection(f, p + (0.5 * h) * k2, k2, k3) || !fieldDirection(f, p + h * k3, k3, k4))
    {
      return false;
    }
    move = (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
    next = k4;
  }
  // A chord of exactly h: the points stay segmentLength apart, as the solver expects.
  const Vec3 chord = normalized(move);
  const Vec3 target = p + h * chord;
  Vec3 probe;
  if (!fieldDirection(f, target, next, probe))
  {
    return false;
  }
  p = target;
  heading = probe;
  return true;
}

/// How far from p along unit d the ray stays inside the region's box (>= 0).
double distanceToBoundary(const OrientationField& f, const Vec3& p, const Vec3& d)
{
  const Vec3 lo = f.lower();
  const Vec3 hi = f.upper();
  double t = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    if (d[a] > 0.0)
    {
      t = std::min(t, (hi[a] - p[a]) / d[a]);
    }
    else if (d[a] < 0.0)
    {
      t = std::min(t, (lo[a] - p[a]) / d[a]);
    }
  }
  return std::max(t, 0.0);
}

/// Adds the side's last point: along the current heading to the boundary when that is within one
/// step, else to the mask's edge found by bisection within that step. Returns why it ended.
TraceEnd finish(
  const OrientationField& f, double h, std::vector<Vec3>& side, const Vec3& p, const Vec3& heading)
{
  const double toBoundary = distanceToBoundary(f, p, heading);
  double reach = 0.0;
  TraceEnd end = TraceEnd::Boundary;
  Vec3 probe;
  if (toBoundary <= h && fieldDirection(f, p + toBoundary * heading, heading, probe))
  {
    reach = toBoundary;
  }
  else
  {
    // The field is full at p and empty (or outside) at p + b·heading: bisect to the edge.
    end = TraceEnd::Empty;
    double a = 0.0;
    double b = std::min(h, toBoundary);
    for (int i = 0; i < 40 && b - a > 1e-9 * h; ++i)
    {
      const double m = 0.5 * (a + b);
      (fieldDirection(f, p + m * heading, heading, probe) ? a : b) = m;
    }
    reach = a;
  }
  const Vec3 last = p + reach * heading;
  if (reach >= h / 3.0 || side.size() < 2)
  {
    if (reach > 0.0)
    {
      side.push_back(last);
    }
  }
  else
  {
    side.back() = last; // a stub shorter than h/3 is folded into the previous segment
  }
  return end;
}

/// Traces one side from the seed along `heading`; `side` starts with the seed.
TraceEnd traceSide(const OrientationField& f, const TraceOptions& o, double cap, const Vec3& seed,
  Vec3 heading, std::vector<Vec3>& side, double& used, bool watchClosure)
{
  const double h = o.segmentLength;
  Vec3 p = seed;
  while (true)
  {
    if (used + h > cap)
    {
      return TraceEnd::LengthCap;
    }
    Vec3 q = p;
    Vec3 nextHeading = heading;
    if (!step(f, o.scheme, h, q, nextHeading))
    {
      return finish(f, h, side, p, heading);
    }
    p = q;
    heading = nextHeading;
    side.push_back(p);
    used += h;
    // Back within one step of the seed after going round: a closed field line.
    if (watchClosure && used > 3.0 * h && distance(p, seed) < h)
    {
      return TraceEnd::Closed;
    }
  }
}

} // namespace

const char* traceSchemeName(TraceScheme scheme)
{
  return scheme == TraceScheme::RK2 ? "RK2" : "RK4";
}

double TracedLine::length() const
{
  double l = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i)
  {
    l += distance(points[i - 1], points[i]);
  }
  return l;
}

std::string validateTraceOptions(const TraceOptions& o)
{
  if (!(std::isfinite(o.segmentLength) && o.segmentLength > 0.0))
  {
    return "SegmentLength is " + formatNumber(o.segmentLength) + ", must be > 0";
  }
  if (o.scheme != TraceScheme::RK2 && o.scheme != TraceScheme::RK4)
  {
    return "IntegrationScheme is " + std::to_string(static_cast<int>(o.scheme)) +
      ", must be 0 (RK2) or 1 (RK4)";
  }
  if (!(std::isfinite(o.maxLength) && o.maxLength >= 0.0))
  {
    return "MaxFiberLength is " + formatNumber(o.maxLength) + ", must be >= 0 (0 = automatic)";
  }
  return {};
}

double traceLengthCap(const OrientationField& f, const TraceOptions& o)
{
  return o.maxLength > 0.0 ? o.maxLength : 4.0 * distance(f.lower(), f.upper());
}

TracedLine traceFieldLine(const OrientationField& f, const Vec3& seed, const TraceOptions& o)
{
  TracedLine line;
  Vec3 heading;
  if (!fieldDirection(f, seed, Vec3{}, heading))
  {
    line.points.push_back(seed);
    return line;
  }
  const double cap = traceLengthCap(f, o);
  double used = 0.0;
  std::vector<Vec3> forward{ seed };
  line.forwardEnd = traceSide(f, o, cap, seed, heading, forward, used, true);
  std::vector<Vec3> backward{ seed };
  if (line.forwardEnd == TraceEnd::Closed)
  {
    line.backwardEnd = TraceEnd::Closed;
  }
  else
  {
    line.backwardEnd = traceSide(f, o, cap, seed, -heading, backward, used, false);
  }
  line.points.assign(backward.rbegin(), backward.rend());
  line.points.insert(line.points.end(), forward.begin() + 1, forward.end());
  return line;
}

} // namespace fiberpli
