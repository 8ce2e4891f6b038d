// Helpers of the PLI tests: the Fourier (EPA) analysis of one pixel, written from its definition
// (docs/pli-analysis.md §6) and independent of the simulation code, plus small fiber builders.
#pragma once

#include "Model/FiberModel.h"

#include <cmath>
#include <vector>

namespace plitest
{

struct Epa
{
  double T, dirDeg, ret;
};

/// I(ρ_k), ρ_k = k·180°/N: a0 = mean, a2/b2 = cos 2ρ / sin 2ρ coefficients;
/// I = (T/2)(1 + ret·sin 2(ρ − dir)).
inline Epa epa(const double* I, int N)
{
  double a0 = 0, a2 = 0, b2 = 0;
  for (int k = 0; k < N; ++k)
  {
    const double r = k * M_PI / N;
    a0 += I[k] / N;
    a2 += 2.0 / N * I[k] * std::cos(2 * r);
    b2 += 2.0 / N * I[k] * std::sin(2 * r);
  }
  double d = 0.5 * std::atan2(-a2, b2) * 180.0 / M_PI;
  if (d < 0)
    d += 180.0;
  return { 2 * a0, d, std::hypot(a2, b2) / a0 };
}

/// Circular difference of two directions modulo 180°.
inline double dirDiff(double a, double b)
{
  double d = std::fmod(std::fabs(a - b), 180.0);
  return std::min(d, 180.0 - d);
}

/// Straight fiber through c along unit u, ±half µm long, constant radius.
inline fiberpli::Fiber line(
  const fiberpli::Vec3& c, const fiberpli::Vec3& u, double half, double r, int bundle = 0)
{
  fiberpli::Fiber f;
  f.points = { c - half * u, c + half * u };
  f.radii = { r, r };
  f.bundle = bundle;
  return f;
}

inline fiberpli::Vec3 dirVec(double phiDeg, double alphaDeg)
{
  const double p = phiDeg * M_PI / 180, a = alphaDeg * M_PI / 180;
  return { std::cos(a) * std::cos(p), std::cos(a) * std::sin(p), std::sin(a) };
}

} // namespace plitest
