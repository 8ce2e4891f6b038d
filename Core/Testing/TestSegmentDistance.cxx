// Closest points of two segments (docs/solver.md §2, tests 1–8 of §10).
#include "Geometry/SegmentDistance.h"

#include "BruteForceOverlap.h"
#include "Util/Random.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace fiberpli;

namespace
{
// Dense sampling of s plus a golden-section refinement around the best sample: a brute-force
// distance that shares no formula with the code under test.
double sampledDistance(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1)
{
  auto f = [&](double s) { return fiberpli_test::refPointSegment(a0 + s * (a1 - a0), b0, b1); };
  const int n = 2000;
  int best = 0;
  for (int i = 1; i <= n; ++i)
  {
    if (f(double(i) / n) < f(double(best) / n))
    {
      best = i;
    }
  }
  double lo = std::max(0.0, double(best - 1) / n), hi = std::min(1.0, double(best + 1) / n);
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 200; ++it)
  {
    const double m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    if (f(m1) < f(m2))
      hi = m2;
    else
      lo = m1;
  }
  return f(0.5 * (lo + hi));
}
} // namespace

TEST(SegmentDistance, Skew90Degrees)
{
  for (double d : { 0.0, 1e-9, 0.3 })
  {
    const SegmentClosest c = closestPoints({ -1, 0, 0 }, { 1, 0, 0 }, { 0, -1, d }, { 0, 1, d });
    EXPECT_NEAR(c.distance, d, 1e-12 * 2.0);
    EXPECT_NEAR(c.s, 0.5, 1e-12);
    EXPECT_NEAR(c.t, 0.5, 1e-12);
  }
}

TEST(SegmentDistance, ParallelOverlapTakesOverlapMidpoint)
{
  const double h = 0.25;
  const SegmentClosest c = closestPoints({ 0, 0, 0 }, { 2, 0, 0 }, { 1, h, 0 }, { 3, h, 0 });
  EXPECT_NEAR(c.distance, h, 1e-12);
  EXPECT_NEAR(c.s, 0.75, 1e-12);
  EXPECT_NEAR(c.t, 0.25, 1e-12);
  EXPECT_TRUE(c.parallel);
  const SegmentClosest swapped = closestPoints({ 1, h, 0 }, { 3, h, 0 }, { 0, 0, 0 }, { 2, 0, 0 });
  EXPECT_NEAR(swapped.s, 0.25, 1e-12);
  EXPECT_NEAR(swapped.t, 0.75, 1e-12);
  const SegmentClosest reversed = closestPoints({ 0, 0, 0 }, { 2, 0, 0 }, { 3, h, 0 }, { 1, h, 0 });
  EXPECT_NEAR(distance(reversed.p, c.p), 0.0, 1e-12);
  EXPECT_NEAR(distance(reversed.q, c.q), 0.0, 1e-12);
}

TEST(SegmentDistance, CollinearDisjoint)
{
  const SegmentClosest c = closestPoints({ 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 }, { 3, 0, 0 });
  EXPECT_DOUBLE_EQ(c.distance, 1.0);
  EXPECT_DOUBLE_EQ(c.s, 1.0);
  EXPECT_DOUBLE_EQ(c.t, 0.0);
}

TEST(SegmentDistance, ZeroLengthSegments)
{
  const SegmentClosest ps = closestPoints({ 0.5, 2, 0 }, { 0.5, 2, 0 }, { 0, 0, 0 }, { 1, 0, 0 });
  EXPECT_DOUBLE_EQ(ps.distance, 2.0);
  EXPECT_DOUBLE_EQ(ps.s, 0.5);
  EXPECT_DOUBLE_EQ(ps.t, 0.5);
  const SegmentClosest sp = closestPoints({ 0, 0, 0 }, { 1, 0, 0 }, { 3, 4, 0 }, { 3, 4, 0 });
  EXPECT_DOUBLE_EQ(sp.distance, std::sqrt(4.0 + 16.0));
  EXPECT_DOUBLE_EQ(sp.s, 1.0);
  const SegmentClosest pp = closestPoints({ 1, 1, 1 }, { 1, 1, 1 }, { 1, 4, 5 }, { 1, 4, 5 });
  EXPECT_DOUBLE_EQ(pp.distance, 5.0);
  EXPECT_TRUE(std::isfinite(pp.s) && std::isfinite(pp.t));
  const SegmentClosest same = closestPoints({ 1, 1, 1 }, { 1, 1, 1 }, { 1, 1, 1 }, { 1, 1, 1 });
  EXPECT_EQ(same.distance, 0.0);
  EXPECT_TRUE(isFinite(separationDirection(same, {}, {})));
  EXPECT_DOUBLE_EQ(norm(separationDirection(same, {}, {})), 1.0);
}

TEST(SegmentDistance, NearParallel)
{
  const double L = 2.0;
  for (double theta : { 1e-3, 1e-6, 1e-9 })
  {
    // Shared end point at the origin, opening angle theta, plus an offset copy.
    for (double off : { 0.0, 0.3 })
    {
      const Vec3 a0{ 0, 0, off }, a1{ L, 0, off };
      const Vec3 b0{ 0, 0, 0 }, b1{ L * std::cos(theta), L * std::sin(theta), 0 };
      const SegmentClosest c = closestPoints(a0, a1, b0, b1);
      const double ref = sampledDistance(a0, a1, b0, b1);
      if (theta >= 1e-3)
      {
        EXPECT_NEAR(c.distance, ref, 1e-9 * L) << theta;
      }
      else
      {
        EXPECT_TRUE(c.parallel);
        EXPECT_GE(c.distance, ref - 1e-12 * L);
        EXPECT_LE(c.distance, ref + 0.5 * L * std::sin(theta) + 1e-12 * L) << theta;
      }
    }
  }
}

TEST(SegmentDistance, RandomPairsAgreeWithIndependentReference)
{
  RandomStream rng(2024, 5, 0);
  for (int i = 0; i < 100000; ++i)
  {
    Vec3 p[4];
    for (Vec3& x : p)
      x = { rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2) };
    const double L = std::max(distance(p[0], p[1]), distance(p[2], p[3]));
    const SegmentClosest c = closestPoints(p[0], p[1], p[2], p[3]);
    ASSERT_NEAR(c.distance, fiberpli_test::refSegmentDistance(p[0], p[1], p[2], p[3]), 1e-9 * L);
    ASSERT_NEAR(c.distance, distance(c.p, c.q), 1e-15 * L);
  }
}

TEST(SegmentDistance, ScaleInvariance)
{
  RandomStream rng(7, 1, 0);
  for (int i = 0; i < 1000; ++i)
  {
    Vec3 p[4];
    for (Vec3& x : p)
      x = { rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2) };
    if (i % 3 == 0) // make every third pair exactly parallel
      p[3] = p[2] + 0.7 * (p[1] - p[0]);
    const SegmentClosest c = closestPoints(p[0], p[1], p[2], p[3]);
    const double L = std::max(distance(p[0], p[1]), distance(p[2], p[3]));
    for (double k : { 1e-3, 1e3 })
    {
      const SegmentClosest ck = closestPoints(k * p[0], k * p[1], k * p[2], k * p[3]);
      EXPECT_NEAR(ck.distance, k * c.distance, 1e-12 * k * L);
      EXPECT_NEAR(ck.s, c.s, 1e-12);
      EXPECT_NEAR(ck.t, c.t, 1e-12);
      EXPECT_EQ(ck.parallel, c.parallel);
    }
  }
}

TEST(SegmentDistance, Symmetry)
{
  RandomStream rng(9, 2, 0);
  for (int i = 0; i < 10000; ++i)
  {
    Vec3 p[4];
    for (Vec3& x : p)
      x = { rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2) };
    const double L = std::max(distance(p[0], p[1]), distance(p[2], p[3]));
    const SegmentClosest ab = closestPoints(p[0], p[1], p[2], p[3]);
    const SegmentClosest ba = closestPoints(p[2], p[3], p[0], p[1]);
    ASSERT_NEAR(ab.distance, ba.distance, 1e-12 * L);
    ASSERT_NEAR(ab.s, ba.t, 1e-9);
    ASSERT_NEAR(ab.t, ba.s, 1e-9);
  }
}

TEST(SegmentDistance, DegenerateDirection)
{
  // Intersecting 90° links: a along x, b along y → a moves +z, deterministic.
  const Vec3 a0{ -1, 0, 0 }, a1{ 1, 0, 0 }, b0{ 0, -1, 0 }, b1{ 0, 1, 0 };
  const SegmentClosest c = closestPoints(a0, a1, b0, b1);
  EXPECT_EQ(c.distance, 0.0);
  const Vec3 n = separationDirection(c, a1 - a0, b1 - b0);
  EXPECT_EQ(n, (Vec3{ 0, 0, 1 }));
  // Swapping the roles (b has the smaller id) flips the direction: u × v changes sign.
  EXPECT_EQ(separationDirection(c, b1 - b0, a1 - a0), (Vec3{ 0, 0, -1 }));
  // Coincident parallel links along z: least aligned axis x → u × e_x = +e_y.
  const Vec3 z0{ 0, 0, 0 }, z1{ 0, 0, 1 };
  const SegmentClosest cz = closestPoints(z0, z1, z0, z1);
  const Vec3 nz = separationDirection(cz, z1 - z0, z1 - z0);
  EXPECT_EQ(nz, (Vec3{ 0, 1, 0 }));
  // Coincident along a general direction: unit and perpendicular to the axis.
  const Vec3 u{ 0.3, -1.2, 0.7 };
  const Vec3 ng = separationDirection(closestPoints(z0, u, z0, u), u, u);
  EXPECT_NEAR(norm(ng), 1.0, 1e-15);
  EXPECT_NEAR(dot(ng, u), 0.0, 1e-15);
  // Regular case: unit vector from q to p.
  const SegmentClosest r = closestPoints({ -1, 0, 0.5 }, { 1, 0, 0.5 }, b0, b1);
  EXPECT_EQ(separationDirection(r, { 2, 0, 0 }, { 0, 2, 0 }), (Vec3{ 0, 0, 1 }));
}
