/// Vec3: a point or direction in 3D (µm). Plain value type with the arithmetic the Core needs.
#pragma once

#include <cmath>

namespace fiberpli
{

struct Vec3
{
  double x = 0.0;
  double y = 0.0;
  double z = 0.0;

  double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

inline Vec3 operator+(const Vec3& a, const Vec3& b)
{
  return { a.x + b.x, a.y + b.y, a.z + b.z };
}
inline Vec3 operator-(const Vec3& a, const Vec3& b)
{
  return { a.x - b.x, a.y - b.y, a.z - b.z };
}
inline Vec3 operator-(const Vec3& a)
{
  return { -a.x, -a.y, -a.z };
}
inline Vec3 operator*(double s, const Vec3& a)
{
  return { s * a.x, s * a.y, s * a.z };
}
inline Vec3 operator*(const Vec3& a, double s)
{
  return { s * a.x, s * a.y, s * a.z };
}
inline Vec3 operator/(const Vec3& a, double s)
{
  return { a.x / s, a.y / s, a.z / s };
}
inline Vec3& operator+=(Vec3& a, const Vec3& b)
{
  a.x += b.x;
  a.y += b.y;
  a.z += b.z;
  return a;
}
inline Vec3& operator-=(Vec3& a, const Vec3& b)
{
  a.x -= b.x;
  a.y -= b.y;
  a.z -= b.z;
  return a;
}
inline Vec3& operator*=(Vec3& a, double s)
{
  a.x *= s;
  a.y *= s;
  a.z *= s;
  return a;
}
inline bool operator==(const Vec3& a, const Vec3& b)
{
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
inline bool operator!=(const Vec3& a, const Vec3& b)
{
  return !(a == b);
}

inline double dot(const Vec3& a, const Vec3& b)
{
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline Vec3 cross(const Vec3& a, const Vec3& b)
{
  return { a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x };
}
inline double norm2(const Vec3& a)
{
  return dot(a, a);
}
inline double norm(const Vec3& a)
{
  return std::sqrt(dot(a, a));
}
inline double distance(const Vec3& a, const Vec3& b)
{
  return norm(a - b);
}
inline bool isFinite(const Vec3& a)
{
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
/// Per-axis minimum and maximum (the corners of a bounding box).
inline Vec3 componentMin(const Vec3& a, const Vec3& b)
{
  return { a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z };
}
inline Vec3 componentMax(const Vec3& a, const Vec3& b)
{
  return { a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z };
}

/// Unit vector along a; a zero vector stays zero (callers decide what a degenerate direction
/// means).
inline Vec3 normalized(const Vec3& a)
{
  const double n = norm(a);
  return n > 0.0 ? a / n : Vec3{};
}

} // namespace fiberpli
