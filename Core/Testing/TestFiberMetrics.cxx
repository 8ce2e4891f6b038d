// FiberMetrics against closed forms: volume fraction of straight fibers, capsule gaps, periodic
// images, tortuosity of a helix, orientation order of parallel and perpendicular populations.
#include "Metrics/FiberMetrics.h"

#include "Util/Random.h"

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cmath>
#include <cstdlib>
#include <limits>

using namespace fiberpli;

namespace
{

Fiber straight(const Vec3& a, const Vec3& b, int links, double r, std::int64_t id, int bundle = 0)
{
  Fiber f;
  for (int k = 0; k <= links; ++k)
  {
    f.points.push_back(a + (double(k) / links) * (b - a));
    f.radii.push_back(r);
  }
  f.id = id;
  f.bundle = bundle;
  return f;
}

MetricsOptions box(double half, double voxel)
{
  MetricsOptions o;
  o.boxLo = { -half, -half, -half };
  o.boxHi = { half, half, half };
  o.voxelSize = voxel;
  return o;
}

/// 3 × 3 fibers along x at y, z in {−2.5, 0, 2.5}, from x0 to x1.
FiberModel lattice(double x0, double x1, double r)
{
  FiberModel m;
  for (int j = -1; j <= 1; ++j)
  {
    for (int k = -1; k <= 1; ++k)
    {
      m.fibers.push_back(
        straight({ x0, 2.5 * j, 2.5 * k }, { x1, 2.5 * j, 2.5 * k }, 8, r, m.fibers.size()));
    }
  }
  return m;
}

PeriodicCell cube(double half)
{
  PeriodicCell c;
  c.lo = { -half, -half, -half };
  c.hi = { half, half, half };
  return c;
}

// Brute-force distance of two segments by dense sampling (shares no formula with segmentDistance).
double sampledDistance(const Vec3& a0, const Vec3& a1, const Vec3& b0, const Vec3& b1)
{
  double best = 1e300;
  const int n = 400;
  for (int i = 0; i <= n; ++i)
  {
    const Vec3 p = a0 + (double(i) / n) * (a1 - a0);
    for (int j = 0; j <= n; ++j)
    {
      best = std::min(best, distance(p, b0 + (double(j) / n) * (b1 - b0)));
    }
  }
  return best;
}

} // namespace

TEST(FiberMetrics, CylindersThroughTheBoxGiveTheirExactVolumeFraction)
{
  // Fibers cross the whole box: inside it each is a cylinder of length 10, φ = 9·π·r²·10 / 10³.
  const double r = 1.0;
  const MetricsResult m = computeFiberMetrics(lattice(-8, 8, r), box(5, 0.05), nullptr);
  ASSERT_TRUE(m.error.empty()) << m.error;
  const double exact = 9 * M_PI * r * r * 10 / 1000;
  EXPECT_LE(std::abs(m.volume.fraction - exact), m.volume.errorBound);
  EXPECT_LT(m.volume.errorBound, 0.03);
  EXPECT_NEAR(
    m.volume.fraction, exact, 0.002); // voxel centres are far more accurate than the bound
  EXPECT_EQ(m.pairs.collisions, 0);
  EXPECT_NEAR(m.pairs.minGap, 2.5 - 2 * r, 1e-12); // neighbouring lattice fibers
}

TEST(FiberMetrics, FibersInsideTheBoxCountTheirEndCaps)
{
  // Fully inside: each fiber is one capsule of length 6, volume π·r²·6 + 4/3·π·r³.
  const double r = 0.8;
  const MetricsResult m = computeFiberMetrics(lattice(-3, 3, r), box(5, 0.05), nullptr);
  const double exact = 9 * (M_PI * r * r * 6 + 4.0 / 3.0 * M_PI * r * r * r) / 1000;
  EXPECT_LE(std::abs(m.volume.fraction - exact), m.volume.errorBound);
  EXPECT_NEAR(m.volume.fraction, exact, 0.002);
  EXPECT_DOUBLE_EQ(m.shape.linkLength.min, 0.75);
  EXPECT_DOUBLE_EQ(m.shape.linkLength.max, 0.75);
  EXPECT_NEAR(m.shape.radius.mean, r, 1e-12);
  EXPECT_EQ(m.links, 9u * 8u);
}

TEST(FiberMetrics, DefaultBoxIsThePointBounds)
{
  // Fibers along x from −3 to 3 at y, z = ±2.5, 0: bounds 6 × 5 × 5 (radii not included).
  const double r = 0.5;
  MetricsOptions o;
  o.voxelSize = 0.05;
  const MetricsResult m = computeFiberMetrics(lattice(-3, 3, r), o, nullptr);
  ASSERT_TRUE(m.error.empty()) << m.error;
  EXPECT_DOUBLE_EQ(m.regionLo.y, -2.5);
  EXPECT_DOUBLE_EQ(m.regionHi.x, 3.0);
  // Inside the bounds: the centre fiber whole, edge fibers half, corner fibers a quarter.
  const double exact = (1 + 4 * 0.5 + 4 * 0.25) * M_PI * r * r * 6 / (6 * 5 * 5);
  EXPECT_LE(std::abs(m.volume.fraction - exact), m.volume.errorBound);
  EXPECT_NEAR(m.volume.fraction, exact, 0.002);
}

TEST(FiberMetrics, PeriodicCellCountsEveryImageOnce)
{
  // One fiber along x through a (10 µm)³ cell near its +y face: the part beyond y = 5 wraps to
  // y = −5, so φ = π·r²·10 / 10³ wherever the fiber lies, also when stored one period away.
  const double r = 1.0, exact = M_PI * r * r * 10 / 1000;
  for (double shift : { 0.0, 10.0 })
  {
    FiberModel m;
    m.fibers.push_back(straight({ -5 + shift, 4.5, 0 }, { 5 + shift, 4.5, 0 }, 10, r, 0));
    MetricsOptions o = box(5, 0.05);
    o.cell = cube(5);
    const MetricsResult res = computeFiberMetrics(m, o, nullptr);
    ASSERT_TRUE(res.error.empty()) << res.error;
    EXPECT_LE(std::abs(res.volume.fraction - exact), res.volume.errorBound) << shift;
    EXPECT_NEAR(res.volume.fraction, exact, 0.001) << shift;
    // A fiber closed through the cell never collides with itself across the seam.
    EXPECT_EQ(res.pairs.collisions, 0) << shift;
  }
}

TEST(FiberMetrics, TwoCapsulesAtAKnownGap)
{
  // A along x, B along z at y = 1 + g: axis distance 1 + g, radii 0.5 each → surface gap g.
  for (double g : { 0.3, 1e-9, -1e-9, -0.01, -0.7 })
  {
    FiberModel m;
    m.fibers.push_back(straight({ 0, 0, 0 }, { 1, 0, 0 }, 1, 0.5, 0));
    m.fibers.push_back(straight({ 0.5, 1 + g, -1 }, { 0.5, 1 + g, 1 }, 1, 0.5, 1));
    MetricsOptions o;
    o.volumeFraction = false;
    const MetricsResult res = computeFiberMetrics(m, o, nullptr);
    EXPECT_NEAR(res.pairs.minGap, g, 1e-12);
    EXPECT_EQ(res.pairs.collisions, g < 0 ? 1 : 0) << g;
  }
}

TEST(FiberMetrics, SmallestGapOfFarApartFibersIsExact)
{
  // Gap much larger than any capsule: the search widens until it is certain.
  FiberModel m;
  m.fibers.push_back(straight({ 0, 0, 0 }, { 1, 0, 0 }, 1, 0.5, 0));
  m.fibers.push_back(straight({ 0, 100, 0 }, { 1, 100, 0 }, 1, 0.5, 1));
  m.fibers.push_back(straight({ 0, 300, 0 }, { 1, 300, 0 }, 1, 0.5, 2));
  MetricsOptions o;
  o.volumeFraction = false;
  EXPECT_NEAR(computeFiberMetrics(m, o, nullptr).pairs.minGap, 99.0, 1e-12);
}

TEST(FiberMetrics, PairsAcrossThePeriodicBoundaryUseTheNearestImage)
{
  // Fibers at y = −4.8 and y = 4.8 in a (10 µm)³ cell are 0.4 apart through the boundary (3 links
  // each: too short to be compared with themselves).
  FiberModel m;
  m.fibers.push_back(straight({ -1.5, -4.8, 0 }, { 1.5, -4.8, 0 }, 3, 0.5, 0));
  m.fibers.push_back(straight({ -1.5, 4.8, 0 }, { 1.5, 4.8, 0 }, 3, 0.5, 1));
  MetricsOptions o;
  o.volumeFraction = false;
  EXPECT_NEAR(computeFiberMetrics(m, o, nullptr).pairs.minGap, 9.6 - 1.0, 1e-12);
  o.cell = cube(5);
  const MetricsResult res = computeFiberMetrics(m, o, nullptr);
  EXPECT_NEAR(res.pairs.minGap, 0.4 - 1.0, 1e-12);
  // Link i of one fiber reaches link j of the other at 0.4 µm when |i − j| <= 1 (3 + 2 + 2 pairs);
  // at |i − j| = 2 the axes are √(1 + 0.4²) > 1 apart.
  EXPECT_EQ(res.pairs.collisions, 7);
}

TEST(FiberMetrics, StraightFiberNeverCollidesWithItself)
{
  // 10 links of 1 µm, r = 0.5: links with ≥ 2 µm of arc between them are compared; the
  // closest such pair (k, k+3) has axis distance 2 → gap 1.
  FiberModel m;
  m.fibers.push_back(straight({ 0, 0, 0 }, { 10, 0, 0 }, 10, 0.5, 0));
  MetricsOptions o;
  o.volumeFraction = false;
  const MetricsResult res = computeFiberMetrics(m, o, nullptr);
  EXPECT_EQ(res.pairs.collisions, 0);
  EXPECT_NEAR(res.pairs.minGap, 1.0, 1e-12);
}

TEST(FiberMetrics, HairpinCollidesWithItself)
{
  // Two 10-link legs 0.8 µm apart (r = 0.5) joined at one end: leg–leg pairs far along the arc
  // overlap.
  Fiber f;
  for (int k = 0; k <= 10; ++k)
  {
    f.points.push_back({ double(k), 0, 0 });
  }
  for (int k = 10; k >= 0; --k)
  {
    f.points.push_back({ double(k), 0.8, 0 });
  }
  f.radii.assign(f.points.size(), 0.5);
  FiberModel m;
  m.fibers.push_back(f);
  MetricsOptions o;
  o.volumeFraction = false;
  const MetricsResult res = computeFiberMetrics(m, o, nullptr);
  EXPECT_GT(res.pairs.collisions, 0);
  EXPECT_NEAR(res.pairs.minGap, 0.8 - 1.0, 1e-12);
}

TEST(FiberMetrics, HashFindsWhatBruteForceFinds)
{
  // 300 random short capsules: collisions and smallest gap equal an all-pairs comparison, for
  // 1 and 2 threads, with and without a periodic cell.
  RandomStream rng(7);
  FiberModel m;
  for (int i = 0; i < 300; ++i)
  {
    const Vec3 a{ rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5) };
    const Vec3 d{ rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1) };
    m.fibers.push_back(straight(a, a + d, 1, rng.uniform(0.1, 0.3), i));
  }
  // Then with three long links (reach 2.65 > twice any short one: oversize, outside the hash).
  for (bool longLinks : { false, true })
    for (bool periodic : { false, true })
    {
      if (longLinks && m.fibers.size() == 300)
      {
        for (int i = 0; i < 3; ++i)
        {
          const Vec3 a{ rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5) };
          m.fibers.push_back(straight(a, a + Vec3{ 4.8, 0.3 * i, 0 }, 1, 0.25, 300 + i));
        }
      }
      PeriodicCell cell = periodic ? cube(5) : PeriodicCell{};
      const CapsuleSet set = makeCapsules(m, cell);
      std::int64_t collisions = 0;
      double minGap = 1e300;
      for (std::size_t i = 0; i < set.capsules.size(); ++i)
      {
        for (std::size_t j = i + 1; j < set.capsules.size(); ++j)
        {
          const Capsule &p = set.capsules[i], &q = set.capsules[j];
          // every image within one period, not only the nearest midpoint image
          double d = 1e300;
          for (int sx = -1; sx <= 1; ++sx)
            for (int sy = -1; sy <= 1; ++sy)
              for (int sz = -1; sz <= 1; ++sz)
              {
                if (!periodic && (sx || sy || sz))
                  continue;
                const Vec3 s{ 10.0 * sx, 10.0 * sy, 10.0 * sz };
                d = std::min(d, segmentDistance(p.a, p.b, q.a + s, q.b + s));
              }
          const double gap = d - p.r - q.r;
          collisions += gap < 0 ? 1 : 0;
          minGap = std::min(minGap, gap);
        }
      }
      ASSERT_GT(collisions, 5);
      for (int threads : { 1, 2 })
      {
        const PairResult res = compareCapsulePairs(set, cell, threads, nullptr);
        EXPECT_EQ(res.collisions, collisions) << periodic << threads << longLinks;
        EXPECT_EQ(res.minGap, minGap) << periodic << threads << longLinks;
      }
    }
}

TEST(FiberMetrics, SpreadOutModelKeepsTheHashSmall)
{
  // Four 1 µm links 1e7 µm apart on every axis: extent/reach ~1e7 per axis would be 1e21 cells.
  FiberModel m;
  const double far = 1e7;
  for (const Vec3& a : { Vec3{ 0, 0, 0 }, Vec3{ far, 0, 0 }, Vec3{ 0, far, 0 }, Vec3{ 0, 0, far } })
  {
    m.fibers.push_back(straight(a, a + Vec3{ 1, 0, 0 }, 1, 0.5, m.fibers.size()));
  }
  MetricsOptions o;
  o.volumeFraction = false;
  const MetricsResult res = computeFiberMetrics(m, o, nullptr);
  EXPECT_TRUE(res.error.empty()) << res.error;
  EXPECT_EQ(res.pairs.collisions, 0);
  EXPECT_DOUBLE_EQ(res.pairs.minGap, far - 2.0); // link 0 ends at x = 1, link 1 starts at 1e7
}

TEST(FiberMetrics, LongUnwrappedFiberIsCheckedAgainstTheMemoryBudget)
{
  // One fiber closed through a 10 µm cell after 1e5 periods: its 1e5 links of just under 10 µm (one
  // cell edge each: longer ones are refused outright) each reach ~100 voxel layers, 1e7 layer
  // entries
  // (~320 MB), refused before any is stored; the Monte Carlo cells are refused too.
  FiberModel m;
  m.fibers.push_back(straight({ 0, 0, 0 }, { 0, 0, 1e6 }, 100001, 0.5, 0));
  MetricsOptions o = box(5, 0.1);
  o.cell = cube(5);
  o.pairs = false;
  setenv("FIBERPLI_MEMORY_LIMIT", "50M", 1);
  const MetricsResult grid = computeFiberMetrics(m, o, nullptr);
  o.monteCarlo = true;
  o.samples = 1000;
  setenv("FIBERPLI_MEMORY_LIMIT", "1M", 1);
  const MetricsResult mc = computeFiberMetrics(m, o, nullptr);
  unsetenv("FIBERPLI_MEMORY_LIMIT");
  EXPECT_NE(grid.error.find("memory budget"), std::string::npos) << grid.error;
  EXPECT_NE(mc.error.find("MonteCarlo"), std::string::npos) << mc.error;
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  EXPECT_LT(1024.0 * static_cast<double>(u.ru_maxrss), 150e6);
}

TEST(FiberMetrics, SegmentDistanceMatchesSampling)
{
  RandomStream rng(3);
  for (int i = 0; i < 40; ++i)
  {
    Vec3 v[4];
    for (Vec3& p : v)
    {
      p = { rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1) };
    }
    if (i % 4 == 0) // parallel pairs take the edge branch only
    {
      v[3] = v[2] + (v[1] - v[0]) * 0.7;
    }
    EXPECT_NEAR(
      segmentDistance(v[0], v[1], v[2], v[3]), sampledDistance(v[0], v[1], v[2], v[3]), 2e-3);
    EXPECT_LE(
      segmentDistance(v[0], v[1], v[2], v[3]), sampledDistance(v[0], v[1], v[2], v[3]) + 1e-12);
  }
}

TEST(FiberMetrics, HelixTortuosity)
{
  // Helix x = R cos t, y = R sin t, z = c·t sampled every Δt over two turns: each chord has length
  // √((2R sin(Δt/2))² + (cΔt)²) and the ends are c·4π apart.
  const double R = 2.0, c = 0.5, dt = 2 * M_PI / 24;
  Fiber f;
  for (int k = 0; k <= 48; ++k)
  {
    const double t = k * dt;
    f.points.push_back({ R * std::cos(t), R * std::sin(t), c * t });
  }
  f.radii.assign(f.points.size(), 0.1);
  FiberModel m;
  m.fibers.push_back(f);
  MetricsOptions o;
  o.volumeFraction = false;
  const MetricsResult res = computeFiberMetrics(m, o, nullptr);
  const double chord = std::sqrt(std::pow(2 * R * std::sin(dt / 2), 2) + std::pow(c * dt, 2));
  EXPECT_NEAR(res.shape.tortuosity[0], 48 * chord / (c * 4 * M_PI), 1e-12);
  EXPECT_NEAR(res.shape.fiberLength[0], 48 * chord, 1e-12);
  // 24 chords per turn, all at angle β to the axis with cos β = c·Δt / chord, their in-plane parts
  // evenly spread: T = diag(sin²β/2, sin²β/2, cos²β); here sin²β/2 is the largest eigenvalue.
  const double cos2 = std::pow(c * dt / chord, 2);
  ASSERT_GT((1 - cos2) / 2, cos2);
  EXPECT_NEAR(res.shape.orientation.c2, 1.5 * (1 - cos2) / 2 - 0.5, 1e-12);
  EXPECT_NEAR(res.shape.orientation.direction.z, 0.0, 1e-9);
}

TEST(FiberMetrics, OrientationOrderOfPopulations)
{
  FiberModel m;
  for (int i = 0; i < 4; ++i)
  {
    m.fibers.push_back(straight({ -3, double(i), 0 }, { 3, double(i), 0 }, 6, 0.3, i, 0));
    m.fibers.push_back(straight({ double(i), -3, 5 }, { double(i), 3, 5 }, 6, 0.3, 10 + i, 1));
    m.fibers.push_back(straight({ double(i), 9, -3 }, { double(i), 9, 3 }, 6, 0.3, 20 + i, 2));
  }
  MetricsOptions o;
  o.volumeFraction = false;
  o.pairs = false;
  const MetricsResult res = computeFiberMetrics(m, o, nullptr);
  ASSERT_EQ(res.shape.bundles.size(), 3u);
  for (int b = 0; b < 3; ++b)
  {
    EXPECT_NEAR(res.shape.bundles[b].orientation.c2, 1.0, 1e-12); // parallel fibers
    EXPECT_NEAR(res.shape.bundles[b].orientation.direction[b], 1.0, 1e-12);
    EXPECT_NEAR(res.shape.bundles[b].tortuosity.mean, 1.0, 1e-12);
    EXPECT_EQ(res.shape.bundles[b].fibers, 4u);
  }
  EXPECT_NEAR(res.shape.orientation.c2, 0.0, 1e-12); // three equal perpendicular populations
  FiberModel two;
  two.fibers.assign(m.fibers.begin(), m.fibers.begin() + 2);
  EXPECT_NEAR(computeFiberMetrics(two, o, nullptr).shape.orientation.c2, 0.25, 1e-12); // λ1 = 1/2
}

TEST(FiberMetrics, BadOptionsAreErrorsNamingTheValue)
{
  const FiberModel m = lattice(-3, 3, 0.5);
  MetricsOptions flat = box(5, 0.1);
  flat.boxHi.z = flat.boxLo.z;
  EXPECT_NE(computeFiberMetrics(m, flat, nullptr).error.find("Box"), std::string::npos);
  MetricsOptions negative = box(5, -1);
  EXPECT_NE(
    computeFiberMetrics(m, negative, nullptr).error.find("VoxelSize -1"), std::string::npos);
  MetricsOptions tiny = box(5, 1e-4);
  EXPECT_NE(computeFiberMetrics(m, tiny, nullptr).error.find("voxels"), std::string::npos);
  MetricsOptions badCell = box(5, 0.1);
  badCell.cell = cube(5);
  badCell.cell.hi.x = badCell.cell.lo.x;
  EXPECT_NE(
    computeFiberMetrics(m, badCell, nullptr).error.find("periodic_cell"), std::string::npos);
  // The cell is checked whatever is measured: a zero-width or infinite cell would give a wrong
  // collision count and a NaN gap.
  badCell.volumeFraction = false;
  EXPECT_NE(
    computeFiberMetrics(m, badCell, nullptr).error.find("periodic_cell"), std::string::npos);
  badCell.cell = cube(5);
  badCell.cell.hi.y = std::numeric_limits<double>::infinity();
  EXPECT_NE(
    computeFiberMetrics(m, badCell, nullptr).error.find("periodic_cell"), std::string::npos);
  // A planar model has no volume in its point bounds: the message says to set Box.
  FiberModel planar;
  planar.fibers.push_back(straight({ 0, 0, 0 }, { 1, 0, 0 }, 2, 0.5, 0));
  EXPECT_NE(computeFiberMetrics(planar, MetricsOptions{}, nullptr).error.find("set Box"),
    std::string::npos);
}

TEST(FiberMetrics, EmptyModelAndAbort)
{
  const MetricsResult empty = computeFiberMetrics(FiberModel{}, box(5, 0.1), nullptr);
  EXPECT_TRUE(empty.error.empty());
  EXPECT_EQ(empty.fibers, 0u);
  EXPECT_TRUE(std::isnan(empty.volume.fraction));
  const MetricsResult aborted =
    computeFiberMetrics(lattice(-8, 8, 1), box(5, 0.05), [](double) { return false; });
  EXPECT_TRUE(aborted.aborted);
}

TEST(FiberMetrics, MonteCarloAgreesWithinItsStandardError)
{
  // The lattice through the box (exact φ known) and the wrapped periodic fiber; the same numbers
  // for 1 and 2 threads (chunked seeds).
  const double r = 1.0, exact = 9 * M_PI * r * r * 10 / 1000;
  MetricsOptions o = box(5, 0.0);
  o.monteCarlo = true;
  o.samples = 400000;
  o.seed = 11;
  o.pairs = false;
  o.numberOfThreads = 1;
  const MetricsResult one = computeFiberMetrics(lattice(-8, 8, r), o, nullptr);
  ASSERT_TRUE(one.error.empty()) << one.error;
  EXPECT_NEAR(one.volume.errorBound, std::sqrt(exact * (1 - exact) / 400000), 2e-5);
  EXPECT_LE(std::abs(one.volume.fraction - exact), 4 * one.volume.errorBound);
  o.numberOfThreads = 2;
  EXPECT_EQ(
    computeFiberMetrics(lattice(-8, 8, r), o, nullptr).volume.fraction, one.volume.fraction);
  o.seed = 12;
  EXPECT_NE(
    computeFiberMetrics(lattice(-8, 8, r), o, nullptr).volume.fraction, one.volume.fraction);

  FiberModel m;
  m.fibers.push_back(
    straight({ 5, 4.5, 0 }, { 15, 4.5, 0 }, 10, r, 0)); // one period away, wrapping in y
  o.cell = cube(5);
  const MetricsResult periodic = computeFiberMetrics(m, o, nullptr);
  EXPECT_LE(std::abs(periodic.volume.fraction - M_PI * 10 / 1000), 4 * periodic.volume.errorBound);

  o.samples = 0;
  EXPECT_NE(computeFiberMetrics(m, o, nullptr).error.find("Samples 0"), std::string::npos);
}

TEST(FiberMetrics, LinksLongerThanThePeriodicCellAreRefusedAtOnce)
{
  // 99 µm links in a 10 µm cell wrapped over it ten times: every voxel visited once per wrap (a
  // minute for a few thousand fibers) and no single nearest image for a pair. Refused before any
  // work, naming the fiber, the link, its span and the edge; links up to the edge are measured.
  FiberModel m;
  for (int f = 0; f < 3; ++f)
  {
    Fiber fiber;
    for (int k = 0; k < 5; ++k)
      fiber.points.push_back({ -5.0 + (f == 2 ? 99.0 : 2.0) * k, -3.0 + 3.0 * f, 0.0 });
    fiber.radii.assign(5, 0.5);
    fiber.id = 10 + f;
    m.fibers.push_back(fiber);
  }
  MetricsOptions o;
  o.cell.lo = { -5, -5, -5 };
  o.cell.hi = { 5, 5, 5 };
  o.numberOfThreads = 1;
  const MetricsResult r = computeFiberMetrics(m, o, {});
  EXPECT_NE(
    r.error.find(
      "fiber 2 (fiber_id 12) link 0 spans 99 um along x, more than the periodic cell's edge 10"),
    std::string::npos)
    << r.error;
  EXPECT_NE(r.error.find("UsePeriodicCell"), std::string::npos) << r.error;
  m.fibers.pop_back();
  const MetricsResult ok = computeFiberMetrics(m, o, {});
  EXPECT_EQ(ok.error, "");
  EXPECT_GT(ok.volume.fraction, 0.0);
}
