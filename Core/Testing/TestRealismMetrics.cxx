// FiberMetrics' realism measures against models whose answers are known in closed form: helices of
// known tortuosity in a periodic cell, a fan of known end-to-end c2, a zigzag of known segment c2,
// a sinusoidal radius of known CV, a myelinated straight fiber of known myelin and axon volume,
// and two populations in halves or interleaved for the mixing figure.
#include "Metrics/FiberMetrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

using namespace fiberpli;

namespace
{

PeriodicCell cellOf(double edge)
{
  PeriodicCell c;
  c.lo = { 0.0, 0.0, 0.0 };
  c.hi = { edge, edge, edge };
  return c;
}

/// A closed helix along z through a cell of height p: `turns` turns of radius R per period p,
/// n points per turn; last point = first + (0, 0, p).
Fiber helix(const Vec3& centre, double R, double p, int turns, int n, int bundle, std::int64_t id)
{
  Fiber f;
  const int points = turns * n;
  for (int k = 0; k <= points; ++k)
  {
    const double t = 2.0 * M_PI * k / n;
    f.points.push_back({ centre.x + R * std::cos(t), centre.y + R * std::sin(t),
      centre.z + p * k / double(points) });
  }
  f.radii.assign(f.points.size(), 0.2);
  f.bundle = bundle;
  f.id = id;
  return f;
}

Fiber segment(const Vec3& a, const Vec3& b, int links, double r, int bundle, std::int64_t id)
{
  Fiber f;
  for (int k = 0; k <= links; ++k)
  {
    f.points.push_back(a + (double(k) / links) * (b - a));
    f.radii.push_back(r);
  }
  f.bundle = bundle;
  f.id = id;
  return f;
}

MetricsOptions shapeOnly()
{
  MetricsOptions o;
  o.volumeFraction = false;
  o.pairs = false;
  o.mixing = false;
  return o;
}

} // namespace

TEST(RealismMetrics, ClosedHelicesHaveTheTortuosityOfTheirPitch)
{
  // A helix of radius R and pitch q has τ = √(1 + (2πR/q)²); sampled with n chords per turn each
  // chord is √((2R sin(π/n))² + (q/n)²), so the polyline's τ is n·chord/q (→ the former as n
  // grows).
  const double L = 20.0, n = 720;
  FiberModel m;
  m.fibers.push_back(helix({ 5, 5, 0 }, 0.5, L, 4, 720, 0, 0));  // pitch 5
  m.fibers.push_back(helix({ 15, 5, 0 }, 1.0, L, 4, 720, 0, 1)); // pitch 5, wider
  m.fibers.push_back(helix({ 5, 15, 0 }, 0.8, L, 2, 720, 1, 2)); // pitch 10
  MetricsOptions o = shapeOnly();
  o.cell = cellOf(L);
  const MetricsResult res = computeFiberMetrics(m, o, nullptr);
  ASSERT_TRUE(res.error.empty()) << res.error;
  const auto polyline = [n](double R, double q)
  { return n * std::sqrt(std::pow(2 * R * std::sin(M_PI / n), 2) + std::pow(q / n, 2)) / q; };
  const auto continuous = [](double R, double q)
  { return std::sqrt(1 + std::pow(2 * M_PI * R / q, 2)); };
  ASSERT_EQ(res.realism.populations.size(), 2u);
  const PopulationRealism& p0 = res.realism.populations[0];
  EXPECT_EQ(p0.fibers, 2u);
  EXPECT_NEAR(p0.tortuosity.min, polyline(0.5, 5), 1e-12);
  EXPECT_NEAR(p0.tortuosity.max, polyline(1.0, 5), 1e-12);
  EXPECT_NEAR(p0.tortuosity.mean, 0.5 * (polyline(0.5, 5) + polyline(1.0, 5)), 1e-12);
  EXPECT_NEAR(p0.tortuosity.max, continuous(1.0, 5), 1e-4 * continuous(1.0, 5));
  const PopulationRealism& p1 = res.realism.populations[1];
  EXPECT_NEAR(p1.tortuosity.mean, polyline(0.8, 10), 1e-12);
  EXPECT_NEAR(p1.tortuosity.mean, continuous(0.8, 10), 1e-4 * continuous(0.8, 10));
  // Closed fibers: the end-to-end vector is the lattice vector, so the axis is z and c2 = 1.
  EXPECT_NEAR(std::abs(p1.axis.z), 1.0, 1e-12);
  EXPECT_NEAR(p1.c2EndToEnd, 1.0, 1e-12);
  // Every chord makes the same angle with z: cos² = (q/n)² / chord².
  const double chord = std::sqrt(std::pow(2 * 0.8 * std::sin(M_PI / n), 2) + std::pow(10.0 / n, 2));
  EXPECT_NEAR(p1.c2Segments, std::pow(10.0 / n / chord, 2), 1e-12);
}

TEST(RealismMetrics, FanOfStraightFibersHasItsClosedFormC2)
{
  // N straight fibers at θ_i = −Θ + 2Θ·i/(N − 1) from z in the xz-plane: ⟨cos²θ⟩ = 1/2 + Σcos
  // 2θ_i/(2N), and Σ cos 2θ_i = sin(N·d/2)/sin(d/2) with d = 4Θ/(N − 1) (a Dirichlet sum centred on
  // 0).
  const int N = 15;
  const double Theta = 30.0 * M_PI / 180.0;
  FiberModel m;
  for (int i = 0; i < N; ++i)
  {
    const double t = -Theta + 2 * Theta * i / (N - 1);
    // Lengths differ (weights would show) but the segment c2 of straight fibers is length-weighted.
    const double len = 10.0;
    m.fibers.push_back(segment(
      { 3.0 * i, 0, 0 }, { 3.0 * i + len * std::sin(t), 0, len * std::cos(t) }, 5, 0.3, 7, i));
  }
  const MetricsResult res = computeFiberMetrics(m, shapeOnly(), nullptr);
  ASSERT_TRUE(res.error.empty()) << res.error;
  const double d = 4 * Theta / (N - 1);
  const double expected = 0.5 + std::sin(N * d / 2) / std::sin(d / 2) / (2.0 * N);
  ASSERT_EQ(res.realism.populations.size(), 1u);
  const PopulationRealism& p = res.realism.populations[0];
  EXPECT_EQ(p.bundle, 7);
  EXPECT_NEAR(p.c2EndToEnd, expected, 1e-12);
  EXPECT_NEAR(p.c2Segments, expected, 1e-12);
  EXPECT_NEAR(p.axis.z, 1.0, 1e-12);
  EXPECT_NEAR(p.tortuosity.mean, 1.0, 1e-12);
  // The angle histogram holds every link once, each in the bin of its fiber's |θ|.
  const Histogram& h = res.realism.segmentAngleHistogram;
  EXPECT_EQ(std::accumulate(h.count.begin(), h.count.end(), std::size_t(0)), std::size_t(N * 5));
  EXPECT_EQ(h.count[0], 15u); // bins of 4.5°: θ = 0 and ±4.29° (three fibers of five links)
}

TEST(RealismMetrics, ZigzagSegmentsMakeTheirAngleWithTheAxis)
{
  // Links alternating ±α from z: end-to-end along z (c2 = 1), every link at α (c2 = cos²α).
  const double alpha = 35.0 * M_PI / 180.0;
  FiberModel m;
  for (int f = 0; f < 3; ++f)
  {
    Fiber z;
    for (int k = 0; k <= 20; ++k)
    {
      z.points.push_back({ 10.0 * f + (k % 2) * std::sin(alpha), 0, k * std::cos(alpha) });
      z.radii.push_back(0.1);
    }
    z.id = f;
    m.fibers.push_back(z);
  }
  const MetricsResult res = computeFiberMetrics(m, shapeOnly(), nullptr);
  const PopulationRealism& p = res.realism.populations[0];
  EXPECT_NEAR(p.c2EndToEnd, 1.0, 1e-12);
  EXPECT_NEAR(p.c2Segments, std::pow(std::cos(alpha), 2), 1e-12);
  EXPECT_NEAR(p.tortuosity.mean, 1.0 / std::cos(alpha), 1e-12);
  const Histogram& h = res.realism.segmentAngleHistogram;
  const std::size_t bin = static_cast<std::size_t>(35.0 / 4.5);
  EXPECT_EQ(h.count[bin], 60u);
  EXPECT_NEAR(h.weight[bin], 60.0, 1e-12); // unit links
}

TEST(RealismMetrics, SinusoidalRadiusHasCVOfAmplitudeOverRootTwo)
{
  // r(s) = r0·(1 + a·sin(2πs/λ)) over whole periods: mean r0, standard deviation r0·a/√2.
  const double r0 = 1.2, a = 0.3, lambda = 5.0;
  const int periods = 8, perPeriod = 64;
  FiberModel m;
  for (int f = 0; f < 2; ++f)
  {
    Fiber fiber;
    const int points = periods * perPeriod;
    for (int k = 0; k <= points; ++k)
    {
      const double s = lambda * k / perPeriod;
      fiber.points.push_back({ 5.0 * f, 0, s });
      fiber.radii.push_back((f == 0 ? r0 : 2 * r0) * (1 + a * std::sin(2 * M_PI * s / lambda)));
    }
    fiber.id = f;
    m.fibers.push_back(fiber);
  }
  m.fibers.push_back(segment({ 20, 0, 0 }, { 20, 0, 40 }, 8, 0.7, 0, 2)); // constant: CV 0
  const MetricsResult res = computeFiberMetrics(m, shapeOnly(), nullptr);
  ASSERT_TRUE(res.error.empty()) << res.error;
  // The linear interpolant between samples adds O((2π/64)²) to the variance.
  const double cv = a / std::sqrt(2.0);
  EXPECT_NEAR(res.realism.fiberRadiusCV[0], cv, 1e-3 * cv);
  EXPECT_NEAR(res.realism.fiberRadiusCV[1], cv, 1e-3 * cv); // scale-free
  EXPECT_NEAR(res.realism.fiberRadiusCV[2], 0.0, 1e-7);
  // Length-weighted over fibers: two of length 40 at cv, one of 40 at 0.
  EXPECT_NEAR(res.realism.populations[0].radiusCV, 2.0 * cv / 3.0, 1e-3 * cv);
  EXPECT_NEAR(res.realism.radiusCV, 2.0 * cv / 3.0, 1e-3 * cv);
  // The radius histogram counts every point once.
  const Histogram& h = res.realism.radiusHistogram;
  EXPECT_EQ(std::accumulate(h.count.begin(), h.count.end(), std::size_t(0)), res.points);
  EXPECT_NEAR(h.lo, 0.7, 1e-12);
  EXPECT_NEAR(h.hi, 2 * r0 * (1 + a), 1e-12);
}

TEST(RealismMetrics, MyelinatedFiberGivesMyelinAndAxonFractionsInClosedForm)
{
  // A straight fiber of outer radius R along z through a periodic cell (a closed cylinder, no
  // caps): fiber volume πR²L, axon πg²R²L, myelin πR²(1 − g²)L over the cell volume L³.
  const double L = 12.0, R = 2.0, g = 0.65;
  FiberModel m;
  m.fibers.push_back(segment({ 6, 6, 0 }, { 6, 6, L }, 12, R, 0, 0));
  m.fibers[0].innerRadii.assign(13, g * R);
  MetricsOptions o;
  o.cell = cellOf(L);
  o.voxelSize = 0.05;
  o.pairs = false;
  const MetricsResult res = computeFiberMetrics(m, o, nullptr);
  ASSERT_TRUE(res.error.empty()) << res.error;
  const double fiber = M_PI * R * R / (L * L), axon = M_PI * g * g * R * R / (L * L);
  EXPECT_NEAR(res.volume.fraction, fiber, res.volume.errorBound);
  EXPECT_NEAR(res.axonVolume.fraction, axon, res.axonVolume.errorBound);
  EXPECT_NEAR(res.myelinFraction, fiber - axon, res.volume.errorBound + res.axonVolume.errorBound);
  EXPECT_NEAR(res.extraAxonalFraction, 1.0 - fiber, res.volume.errorBound);
  EXPECT_LT(res.volume.errorBound, 0.01);
  EXPECT_NEAR(res.realism.gRatio, g, 1e-12);
  EXPECT_NEAR(res.realism.populations[0].gRatio, g, 1e-12);
  EXPECT_EQ(res.realism.gRatioHistogram.count[0] + res.realism.gRatioHistogram.count[1] +
      std::accumulate(res.realism.gRatioHistogram.count.begin() + 2,
        res.realism.gRatioHistogram.count.end(), std::size_t(0)),
    13u);
  // Monte Carlo: the same closed forms within 4 standard errors.
  o.monteCarlo = true;
  o.samples = 400000;
  const MetricsResult mc = computeFiberMetrics(m, o, nullptr);
  EXPECT_NEAR(mc.axonVolume.fraction, axon, 4 * mc.axonVolume.errorBound);
  EXPECT_NEAR(
    mc.myelinFraction, fiber - axon, 4 * (mc.volume.errorBound + mc.axonVolume.errorBound));
  // Without inner radii nothing about myelin is claimed.
  m.fibers[0].innerRadii.clear();
  const MetricsResult none = computeFiberMetrics(m, o, nullptr);
  EXPECT_TRUE(std::isnan(none.axonVolume.fraction));
  EXPECT_TRUE(std::isnan(none.myelinFraction));
  EXPECT_TRUE(std::isnan(none.realism.gRatio));
  EXPECT_TRUE(std::isnan(none.realism.fiberGRatio[0]));
}

TEST(RealismMetrics, BadInnerRadiiAndBinsAreErrorsNamingTheValue)
{
  FiberModel m;
  m.fibers.push_back(segment({ 0, 0, 0 }, { 0, 0, 4 }, 2, 1.0, 0, 5));
  MetricsOptions o = shapeOnly();
  const auto errorWith = [&](std::vector<double> inner)
  {
    FiberModel bad = m;
    bad.fibers[0].innerRadii = std::move(inner);
    return computeFiberMetrics(bad, o, nullptr).error;
  };
  EXPECT_NE(errorWith({ 0.5, 1.5, 0.5 }).find("1.5"), std::string::npos);
  EXPECT_NE(errorWith({ 0.5, NAN, 0.5 }).find("inner_radius of fiber 0 (fiber_id 5) point 1"),
    std::string::npos);
  EXPECT_NE(errorWith({ 0.5, 0.5 }).find("2 values for 3 points"), std::string::npos);
  EXPECT_NE(errorWith({ 0.5, 0.0, 0.5 }).find("> 0"), std::string::npos);
  EXPECT_TRUE(errorWith({ 0.5, 1.0, 0.5 }).empty()); // inner = radius: no sheath there, allowed
  o.histogramBins = 0;
  EXPECT_NE(computeFiberMetrics(m, o, nullptr).error.find("HistogramBins 0"), std::string::npos);
}

TEST(RealismMetrics, OnlyMyelinatedFibersHaveAGRatio)
{
  // Two fibers of equal length, one with g = 0.5, one without a sheath: the g-ratio is 0.5 (the
  // unmyelinated fiber is no g-ratio of 1), and the axons are the first fiber's inner capsules
  // plus the whole second fiber.
  FiberModel m;
  m.fibers.push_back(segment({ 0, 0, 0 }, { 0, 0, 10 }, 5, 1.0, 0, 0));
  m.fibers.push_back(segment({ 5, 0, 0 }, { 5, 0, 10 }, 5, 1.0, 0, 1));
  m.fibers[0].innerRadii.assign(6, 0.5);
  const MetricsResult res = computeFiberMetrics(m, shapeOnly(), nullptr);
  EXPECT_NEAR(res.realism.gRatio, 0.5, 1e-12);
  EXPECT_TRUE(std::isnan(res.realism.fiberGRatio[1]));
  const FiberModel axons = axonModel(m);
  EXPECT_EQ(axons.fibers[0].radii, std::vector<double>(6, 0.5));
  EXPECT_EQ(axons.fibers[1].radii, std::vector<double>(6, 1.0));
}

namespace
{

/// 6 × 6 fibers along z through a (12 µm)³ cell at x, y = 1, 3, …, 11; population(i, j) decides the
/// bundle. Each sub-cube of edge 4 holds 2 × 2 of them.
FiberModel grid(int (*population)(int, int))
{
  FiberModel m;
  for (int i = 0; i < 6; ++i)
  {
    for (int j = 0; j < 6; ++j)
    {
      m.fibers.push_back(segment({ 1.0 + 2 * i, 1.0 + 2 * j, 0 }, { 1.0 + 2 * i, 1.0 + 2 * j, 12 },
        6, 0.8, population(i, j), m.fibers.size()));
    }
  }
  return m;
}

} // namespace

TEST(RealismMetrics, MixingSeparatesHalvesFromInterleavedPopulations)
{
  MetricsOptions o;
  o.cell = cellOf(12.0);
  o.volumeFraction = false;
  o.pairs = false;
  o.samples = 300000;
  o.seed = 3;
  // Halves (x < 6 is population 0): the outer thirds along x hold one population only.
  const MetricsResult halves =
    computeFiberMetrics(grid([](int i, int) { return i < 3 ? 0 : 1; }), o, nullptr);
  ASSERT_TRUE(halves.error.empty()) << halves.error;
  EXPECT_EQ(halves.mixing.minimum, 0.0);
  ASSERT_EQ(halves.mixing.bundles.size(), 2u);
  // The middle third along x holds one column of each (x = 5 and x = 7): shares 1/2 there.
  const std::size_t middle = (1 * 3 + 1) * 3 + 1;
  EXPECT_NEAR(halves.mixing.share[middle * 2 + 0], 0.5, 0.02);
  // Checkerboard: every sub-cube holds two fibers of each: shares 1/2 within sampling error
  // (about 2000 fiber samples per sub-cube: standard error 0.011).
  const MetricsResult mixed =
    computeFiberMetrics(grid([](int i, int j) { return (i + j) % 2; }), o, nullptr);
  ASSERT_TRUE(mixed.error.empty()) << mixed.error;
  EXPECT_GT(mixed.mixing.minimum, 0.45);
  EXPECT_LE(mixed.mixing.minimum, 0.5);
  EXPECT_NEAR(mixed.mixing.volumeShare[0], 0.5, 0.01);
  // The same for any thread count (integer counts from chunked streams).
  MetricsOptions one = o;
  one.numberOfThreads = 1;
  MetricsOptions two = o;
  two.numberOfThreads = 2;
  const MetricsResult a =
    computeFiberMetrics(grid([](int i, int j) { return (i + j) % 2; }), one, nullptr);
  const MetricsResult b =
    computeFiberMetrics(grid([](int i, int j) { return (i + j) % 2; }), two, nullptr);
  EXPECT_EQ(a.mixing.share, b.mixing.share);
  // One population: 1 without sampling.
  const MetricsResult single = computeFiberMetrics(grid([](int, int) { return 4; }), o, nullptr);
  EXPECT_EQ(single.mixing.minimum, 1.0);
}
