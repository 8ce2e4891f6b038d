// Undulation (docs/tissue-models.md §10.1): calibrated tortuosity, closure, zero-mean periodic
// deviation, ends on the base path, equal spacing along the path, scaling for a continuation.
#include "Tissue/Undulation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace fiberpli;

namespace
{
double lengthOf(const std::vector<Vec3>& p)
{
  double len = 0.0;
  for (std::size_t i = 1; i < p.size(); ++i)
    len += std::sqrt(norm2(p[i] - p[i - 1]));
  return len;
}
} // namespace

TEST(Undulation, ClosedFiberReachesItsTortuosityAndClosesExactly)
{
  const Vec3 start{ -15.0, 3.0, -7.0 };
  const Vec3 span{ 30.0, 0.0, 0.0 };
  for (double tau : { 1.01, 1.03, 1.06, 1.15, 1.4 })
  {
    for (std::uint64_t fiber = 0; fiber < 20; ++fiber)
    {
      RandomStream rng(5, 0, fiber);
      const BasePath base = straightBasePath(start, span, true);
      Undulation und = drawUndulation(rng, 30.0, 10.0, true);
      const std::size_t n = undulatedPointCount(30.0, tau, 2.0, 3);
      ASSERT_TRUE(calibrateUndulation(base, und, tau, n));
      const std::vector<Vec3> p = undulatedPath(base, und, und.amplitude, n);
      ASSERT_EQ(p.size(), n);
      // The measured tortuosity of this fiber, from its own points.
      EXPECT_NEAR(lengthOf(p) / 30.0, tau, 1e-5 * tau) << "tau " << tau << " fiber " << fiber;
      // Closed: the last point is the first shifted by the lattice vector, bit for bit.
      EXPECT_EQ(p.back(), p.front() + span);
      // Whole waves over the period.
      for (const UndulationMode& m : und.modes)
        EXPECT_EQ(m.cycles, std::round(m.cycles));
    }
  }
}

TEST(Undulation, ClosedDeviationHasZeroMeanAndIsPeriodic)
{
  RandomStream rng(11, 2, 3);
  const Undulation und = drawUndulation(rng, 40.0, 13.0, true);
  double su = 0.0, sv = 0.0;
  const int samples = 4096;
  for (int i = 0; i < samples; ++i)
  {
    double du, dv;
    undulationDeviation(und, static_cast<double>(i) / samples, true, du, dv);
    su += du;
    sv += dv;
  }
  // A rectangle rule over a whole period integrates sines with fewer than samples/2 waves exactly.
  EXPECT_NEAR(su / samples, 0.0, 1e-12);
  EXPECT_NEAR(sv / samples, 0.0, 1e-12);
  double u0, v0, u1, v1;
  undulationDeviation(und, 0.0, true, u0, v0);
  undulationDeviation(und, 1.0, true, u1, v1);
  EXPECT_NEAR(u0, u1, 1e-12);
  EXPECT_NEAR(v0, v1, 1e-12);
}

TEST(Undulation, OpenFiberKeepsItsEndsAndEvenSpacing)
{
  const Vec3 start{ 0.0, 0.0, 0.0 };
  const Vec3 span{ 10.0, 20.0, -5.0 };
  const double L = norm(span);
  RandomStream rng(1, 1, 1);
  const BasePath base = straightBasePath(start, span, false);
  Undulation und = drawUndulation(rng, L, 8.0, false);
  const std::size_t n = undulatedPointCount(L, 1.1, 1.0, 2);
  ASSERT_TRUE(calibrateUndulation(base, und, 1.1, n));
  const std::vector<Vec3> p = undulatedPath(base, und, und.amplitude, n);
  EXPECT_NEAR(distance(p.front(), start), 0.0, 1e-12);
  EXPECT_NEAR(distance(p.back(), start + span), 0.0, 1e-9);
  EXPECT_NEAR(lengthOf(p) / L, 1.1, 1e-5);
  // Points about SegmentLength apart along the path (equal arc length on the smooth curve).
  double lo = 1e9, hi = 0.0;
  for (std::size_t i = 1; i < p.size(); ++i)
  {
    lo = std::min(lo, distance(p[i - 1], p[i]));
    hi = std::max(hi, distance(p[i - 1], p[i]));
  }
  EXPECT_GT(lo, 0.97);
  EXPECT_LT(hi, 1.03);
  // The deviation is transverse on average: the mean offset along the span stays at the centre.
  Vec3 mean;
  for (const Vec3& q : p)
    mean += q / static_cast<double>(p.size());
  EXPECT_NEAR(dot(mean - 0.5 * span, normalized(span)), 0.0, 0.05 * L);
}

TEST(Undulation, ScaledAmplitudeGoesFromStraightToTarget)
{
  const BasePath base = straightBasePath({ 0, 0, 0 }, { 0, 0, 50.0 }, true);
  RandomStream rng(9, 0, 0);
  Undulation und = drawUndulation(rng, 50.0, 12.0, true);
  const std::size_t n = undulatedPointCount(50.0, 1.2, 2.0, 3);
  ASSERT_TRUE(calibrateUndulation(base, und, 1.2, n));
  double previous = 0.0;
  for (double f : { 0.0, 0.25, 0.5, 0.75, 1.0 })
  {
    const double tau = lengthOf(undulatedPath(base, und, f * und.amplitude, n)) / 50.0;
    EXPECT_GT(tau, previous);
    previous = tau;
  }
  EXPECT_NEAR(lengthOf(undulatedPath(base, und, 0.0, n)) / 50.0, 1.0, 1e-12);
  EXPECT_NEAR(previous, 1.2, 1e-5);
}

TEST(Undulation, JitterCountsAndTooMuchJitterIsReported)
{
  const BasePath base = straightBasePath({ 0, 0, 0 }, { 30.0, 0, 0 }, true);
  RandomStream rng(3, 0, 0);
  Undulation und = drawUndulation(rng, 30.0, 10.0, true);
  const std::size_t n = undulatedPointCount(30.0, 1.05, 2.0, 3);
  std::vector<Vec3> jitter(n);
  RandomStream j(3, 1, 0);
  for (Vec3& d : jitter)
    d = { j.uniform(-0.2, 0.2), j.uniform(-0.2, 0.2), j.uniform(-0.2, 0.2) };
  jitter.back() = jitter.front();
  ASSERT_TRUE(calibrateUndulation(base, und, 1.05, n, &jitter));
  std::vector<Vec3> p = undulatedPath(base, und, und.amplitude, n);
  for (std::size_t i = 0; i < n; ++i)
    p[i] += jitter[i];
  EXPECT_NEAR(lengthOf(p) / 30.0, 1.05, 1e-5);
  // 1 µm jitter on 2 µm links is already far above 1.01: no undulation, and the caller is told.
  for (Vec3& d : jitter)
    d = { j.uniform(-1.0, 1.0), j.uniform(-1.0, 1.0), j.uniform(-1.0, 1.0) };
  EXPECT_FALSE(calibrateUndulation(base, und, 1.01, n, &jitter));
  EXPECT_EQ(und.amplitude, 0.0);
}
