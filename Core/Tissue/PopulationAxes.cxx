#include "Tissue/PopulationAxes.h"

#include "Tissue/Dispersion.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numeric>

namespace fiberpli
{

namespace
{
constexpr double kDegree = M_PI / 180.0;

PopulationAxis coordinateAxis(int k)
{
  PopulationAxis a;
  a.direction[k] = 1.0;
  a.lattice[k] = 1.0;
  a.across1[(k + 1) % 3] = 1.0;
  a.across2[(k + 2) % 3] = 1.0;
  return a;
}

// The lattice direction (p, q, 0), p >= 0, q >= 0, gcd 1, for angle ω ∈ [0°, 90°] from x.
Vec3 planeLatticeDirection(double omega)
{
  Vec3 nearest, shortest;
  double nearestError = 1e9, shortestLength = 1e9;
  for (int p = 0; p <= kMaxAxisPeriods; ++p)
    for (int q = 0; q <= kMaxAxisPeriods; ++q)
    {
      if (std::gcd(p, q) != 1)
        continue;
      const double error = std::fabs(std::atan2(double(q), double(p)) - omega);
      const double length = std::sqrt(double(p * p + q * q));
      if (error < nearestError - 1e-12)
      {
        nearestError = error;
        nearest = { double(p), double(q), 0.0 };
      }
      if (error <= 1.0 * kDegree + 1e-12 && length < shortestLength)
      {
        shortestLength = length;
        shortest = { double(p), double(q), 0.0 };
      }
    }
  return shortestLength < 1e9 ? shortest : nearest;
}
} // namespace

std::vector<PopulationAxis> populationAxes(int populations, double crossingAngle, bool periodic)
{
  std::vector<PopulationAxis> axes;
  for (int k = 0; k < populations; ++k)
    axes.push_back(coordinateAxis(k));
  if (populations < 2 || crossingAngle == 90.0)
    return axes;
  PopulationAxis& a = axes[1];
  a.standard = false;
  const double omega = crossingAngle * kDegree;
  if (periodic)
  {
    a.lattice = planeLatticeDirection(omega);
    a.direction = normalized(a.lattice);
    a.across1 = { 0.0, 0.0, 1.0 };
    a.across2 = { -a.lattice.y, a.lattice.x, 0.0 };
  }
  else
  {
    a.direction = { std::cos(omega), std::sin(omega), 0.0 };
    a.lattice = a.direction;
    a.across1 = { 0.0, 0.0, 1.0 };
    a.across2 = { -a.direction.y, a.direction.x, 0.0 };
  }
  return axes;
}

double axesAngle(const std::vector<PopulationAxis>& axes)
{
  if (axes.size() < 2)
    return 0.0;
  const double c = std::fabs(dot(axes[0].direction, axes[1].direction));
  return std::acos(std::min(1.0, c)) / kDegree;
}

Vec3 nearestLatticeDirection(const PopulationAxis& axis, const Vec3& direction)
{
  const Vec3 d = normalized(direction);
  // Two passes: the smallest angle to d, then the shortest vector within 1° of it. Long vectors
  // (several periods) win only where they are clearly nearer: a fiber along one of them is that
  // many periods long, which costs points and leaves fewer fibers for the same volume.
  const auto visit = [&](auto&& use)
  {
    for (int m = 1; m <= kMaxDispersionPeriods; ++m)
      for (int a = -kMaxDispersionPeriods; a <= kMaxDispersionPeriods; ++a)
        for (int b = -kMaxDispersionPeriods; b <= kMaxDispersionPeriods; ++b)
        {
          const Vec3 v =
            double(m) * axis.lattice + double(a) * axis.across1 + double(b) * axis.across2;
          const double length = norm(v);
          use(v, length, std::acos(std::clamp(dot(v, d) / length, -1.0, 1.0)));
        }
  };
  double bestAngle = 10.0;
  visit([&](const Vec3&, double, double angle) { bestAngle = std::min(bestAngle, angle); });
  Vec3 best;
  double bestLength = 1e300;
  visit(
    [&](const Vec3& v, double length, double angle)
    {
      if (angle <= bestAngle + 1.0 * kDegree && length < bestLength - 1e-12)
      {
        best = v;
        bestLength = length;
      }
    });
  return best;
}

} // namespace fiberpli
