#include "Tissue/BundleShapes.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

std::vector<Vec3> straightPath(double halfLength, double angle)
{
  const Vec3 d{ std::cos(angle), std::sin(angle), 0.0 };
  return { -halfLength * d, halfLength * d };
}

std::vector<Vec3> yBranchPath(
  double halfLength, double openingAngle, double turnRadius, bool left, double step)
{
  const double side = left ? -1.0 : 1.0;
  std::vector<Vec3> path;
  const int trunkSteps = std::max(1, static_cast<int>(std::ceil(halfLength / step)));
  for (int i = 0; i < trunkSteps; ++i)
  {
    path.push_back({ 0.0, -halfLength + halfLength * i / trunkSteps, 0.0 });
  }
  const double arcAngle = std::min(0.5 * openingAngle, halfLength / turnRadius);
  const int arcSteps = std::max(1, static_cast<int>(std::ceil(turnRadius * arcAngle / step)));
  for (int i = 0; i <= arcSteps; ++i)
  {
    const double phi = arcAngle * i / arcSteps;
    // Centre of the turn at (side·R_turn, 0): the arc leaves the fork along +y.
    path.push_back({ side * turnRadius * (1.0 - std::cos(phi)), turnRadius * std::sin(phi), 0.0 });
  }
  const double straight = halfLength - turnRadius * arcAngle;
  if (straight > 1e-9 * halfLength)
  {
    const Vec3 b{ side * std::sin(arcAngle), std::cos(arcAngle), 0.0 };
    const Vec3 start = path.back();
    const int straightSteps = std::max(1, static_cast<int>(std::ceil(straight / step)));
    for (int i = 1; i <= straightSteps; ++i)
    {
      path.push_back(start + (straight * i / straightSteps) * b);
    }
  }
  return path;
}

Vec3 chiasmDirection(double crossingAngle, bool right)
{
  const double h = 0.5 * crossingAngle;
  return { (right ? -1.0 : 1.0) * std::sin(h), std::cos(h), 0.0 };
}

Vec3 chiasmLateralNormal(double crossingAngle, bool right)
{
  const double h = 0.5 * crossingAngle;
  return { (right ? 1.0 : -1.0) * std::cos(h), std::sin(h), 0.0 };
}

double chiasmTurnRadius(double halfLength, double crossingAngle, double turnRadius)
{
  const double t = std::tan(0.5 * crossingAngle);
  return t > 0.0 ? std::min(turnRadius, halfLength / t) : turnRadius;
}

std::vector<Vec3> chiasmSidePath(
  double halfLength, double crossingAngle, double turnRadius, bool right, double step)
{
  const double mirror = right ? -1.0 : 1.0;
  const double h = 0.5 * crossingAngle;
  const double s = std::sin(h);
  const double c = std::cos(h);
  const double rt = chiasmTurnRadius(halfLength, crossingAngle, turnRadius);
  const double a = rt / c; // distance of the arc centre from the crossing point
  const Vec3 d0{ s, c, 0.0 };
  const Vec3 d1{ -s, c, 0.0 };
  const double tangent = a * s; // distance of both tangent points from the crossing point
  std::vector<Vec3> path;
  const double straight = halfLength - tangent;
  const int straightSteps = std::max(1, static_cast<int>(std::ceil(straight / step)));
  if (straight > 1e-9 * halfLength)
  {
    for (int i = 0; i < straightSteps; ++i)
    {
      path.push_back(-(halfLength - straight * i / straightSteps) * d0);
    }
  }
  const int arcSteps = std::max(2, static_cast<int>(std::ceil(rt * crossingAngle / step)));
  for (int i = 0; i <= arcSteps; ++i)
  {
    const double phi = -h + crossingAngle * i / arcSteps;
    path.push_back({ -a + rt * std::cos(phi), rt * std::sin(phi), 0.0 });
  }
  if (straight > 1e-9 * halfLength)
  {
    for (int i = 1; i <= straightSteps; ++i)
    {
      path.push_back((tangent + straight * i / straightSteps) * d1);
    }
  }
  for (Vec3& p : path)
  {
    p.x *= mirror;
  }
  return path;
}

} // namespace fiberpli
