#include "Solver/BeadProfile.h"

#include <cmath>

namespace fiberpli
{

namespace
{
constexpr double kTwoPi = 6.283185307179586476925;

// x modulo period, in [0, period).
double wrapIndex(double x, double period)
{
  double w = std::fmod(x, period);
  if (w < 0.0)
    w += period;
  return w < period ? w : 0.0; // -tiny + period may round to period
}
} // namespace

double periodicProfileRadius(const std::vector<double>& profile, double s)
{
  const double period = static_cast<double>(profile.size() - 1);
  return profileRadius(profile, wrapIndex(s, period));
}

bool followBeadProfile(Fiber& f, FiberPointState& state)
{
  const std::size_t n = f.size();
  const std::vector<double>& profile = state.inputRadii;
  if (n < 3 || profile.size() < 3 || state.source.size() != n)
    return false;
  bool constant = true;
  for (double r : profile)
    constant = constant && r == profile.front();
  if (constant)
    return false;
  const double period = static_cast<double>(profile.size() - 1);
  std::vector<double> arc(n, 0.0);
  for (std::size_t i = 1; i < n; ++i)
    arc[i] = arc[i - 1] + distance(f.points[i - 1], f.points[i]);
  const double length = arc.back();
  if (!(length > 0.0))
    return false;
  for (double& a : arc)
    a *= period / length;
  // The phase: how far the points slid along the profile, on average (circular over the period).
  double sx = 0.0, sy = 0.0;
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    const double angle = kTwoPi * (state.source[i] - arc[i]) / period;
    sx += std::cos(angle);
    sy += std::sin(angle);
  }
  const double phase = (sx != 0.0 || sy != 0.0) ? period * std::atan2(sy, sx) / kTwoPi : 0.0;
  bool changed = false;
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    state.source[i] = wrapIndex(arc[i] + phase, period);
    const double r = profileRadius(profile, state.source[i]);
    if (std::fabs(r - f.radii[i]) > 1e-9 * f.radii[i])
    {
      f.radii[i] = r;
      changed = true;
    }
  }
  // The last point is the first one again.
  state.source[n - 1] = state.source[0];
  f.radii[n - 1] = f.radii[0];
  return changed;
}

} // namespace fiberpli
