#include "Analysis/Axis.h"

#include <cmath>
#include <limits>

namespace fiberpli
{

Vec3 axisFromAngles(double direction, double inclination)
{
  const double c = std::cos(inclination);
  return { c * std::cos(direction), c * std::sin(direction), std::sin(inclination) };
}

Vec3 canonicalAxis(const Vec3& v)
{
  Vec3 u = normalized(v);
  if (u.y < 0.0 || (u.y == 0.0 && u.x < 0.0) || (u.x == 0.0 && u.y == 0.0 && u.z < 0.0))
  {
    u = -u;
    u +=
      Vec3{ 0.0, 0.0, 0.0 }; // −0.0 + 0.0 = +0.0: atan2(−0, −0) would give −π for a vertical axis
  }
  return u;
}

void axisAngles(const Vec3& v, double& direction, double& inclination)
{
  const Vec3 u = canonicalAxis(v);
  if (u.x == 0.0 && u.y == 0.0 && u.z == 0.0)
  {
    direction = inclination = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  direction = std::atan2(u.y, u.x);
  inclination = std::asin(u.z > 1.0 ? 1.0 : (u.z < -1.0 ? -1.0 : u.z));
  if (direction >= M_PI)
  {
    // u.y is a rounding residue (u ≈ (−x, 0, z)): π − ε rounded to π. Keep [0, π) by taking the
    // other representative of the same axis, (0, −α), not just (0, α).
    direction = 0.0;
    inclination = -inclination;
  }
}

double directionDifference(double directionA, double directionB)
{
  const double d = std::fmod(std::abs(directionA - directionB), M_PI);
  return d < M_PI - d ? d : M_PI - d;
}

double axisAngle(double directionA, double inclinationA, double directionB, double inclinationB)
{
  const Vec3 a = axisFromAngles(directionA, inclinationA);
  const Vec3 b = axisFromAngles(directionB, inclinationB);
  return std::atan2(norm(cross(a, b)), std::abs(dot(a, b)));
}

double unsignedAxisAngle(
  double directionA, double inclinationA, double directionB, double inclinationB)
{
  // Flipping both signs is a mirror image of flipping none, so one flip covers every case.
  const double same = axisAngle(directionA, inclinationA, directionB, inclinationB);
  const double flipped = axisAngle(directionA, -inclinationA, directionB, inclinationB);
  return same < flipped ? same : flipped;
}

} // namespace fiberpli
