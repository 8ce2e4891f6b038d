// Dispersion (docs/tissue-models.md §10.2): the Watson ⟨cos²⟩ against an independent rejection
// sampler and its limits, sampling by inversion, lattice directions, and the measured c2 of the
// fibers the generators make.
#include "Tissue/BundleGenerator.h"
#include "Tissue/CubeGenerator.h"
#include "Tissue/Dispersion.h"
#include "Tissue/PopulationAxes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace fiberpli;

namespace
{
// Mean and standard error of cos² of the end-to-end directions about coordinate axis k.
void measuredC2(const FiberModel& m, int k, double& mean, double& stderror)
{
  double s = 0.0, s2 = 0.0;
  for (const Fiber& f : m.fibers)
  {
    const Vec3 d = normalized(f.points.back() - f.points.front());
    const double c2 = d[k] * d[k];
    s += c2;
    s2 += c2 * c2;
  }
  const double n = static_cast<double>(m.fibers.size());
  mean = s / n;
  stderror = std::sqrt(std::max(0.0, s2 / n - mean * mean) / n);
}
} // namespace

TEST(Dispersion, WatsonC2MatchesLimitsAndAnIndependentSampler)
{
  EXPECT_NEAR(watsonC2(0.0), 1.0 / 3.0, 1e-12);
  // Large κ: 1 − 1/κ to first order.
  EXPECT_NEAR(watsonC2(1e4), 1.0 - 1e-4, 2e-8);
  // Best & Fisher's rejection sampler for t = |cos θ| (proposal ∝ e^{κt}, acceptance e^{κ(t²−t)}).
  for (double kappa : { 0.5, 3.0, 12.0 })
  {
    RandomStream rng(99, 0, static_cast<std::uint64_t>(kappa * 10));
    double sum = 0.0;
    int n = 0;
    while (n < 200000)
    {
      const double u = rng.uniform(), v = rng.uniform();
      const double t = 1.0 + std::log(u + (1.0 - u) * std::exp(-kappa)) / kappa;
      if (v <= std::exp(kappa * (t * t - t)))
      {
        sum += t * t;
        ++n;
      }
    }
    EXPECT_NEAR(watsonC2(kappa), sum / n, 0.003) << "kappa " << kappa;
  }
  for (double c2 : { 0.4, 0.7, 0.93, 0.999 })
    EXPECT_NEAR(watsonC2(watsonConcentration(c2)), c2, 1e-9);
}

TEST(Dispersion, InversionSamplesTheTargetC2)
{
  for (double c2 : { 0.5, 0.8, 0.93 })
  {
    const WatsonTable table(watsonConcentration(c2));
    RandomStream rng(5, 5, 5);
    double s = 0.0, s2 = 0.0;
    const int n = 50000;
    for (int i = 0; i < n; ++i)
    {
      const double t = table.cosine(rng.uniform());
      s += t * t;
      s2 += t * t * t * t;
    }
    const double mean = s / n;
    const double se = std::sqrt((s2 / n - mean * mean) / n);
    EXPECT_NEAR(mean, c2, 3.5 * se) << "c2 " << c2;
  }
}

TEST(Dispersion, QuantilesAreEvenlySpreadForEveryCount)
{
  // The fraction of the first N quantiles below x differs from x by O(log N / N), far less than
  // the 1/(2√N) of independent draws.
  for (int n : { 10, 100, 1000 })
    for (double x : { 0.1, 0.37, 0.5, 0.9 })
    {
      int below = 0;
      for (int j = 0; j < n; ++j)
        below += dispersionQuantile(0.3, static_cast<std::uint64_t>(j)) < x ? 1 : 0;
      EXPECT_NEAR(static_cast<double>(below) / n, x, 3.0 * std::log(n + 1.0) / n) << n << " " << x;
    }
}

TEST(Dispersion, NearestLatticeDirections)
{
  const std::vector<PopulationAxis> axes = populationAxes(3, 90.0, true);
  EXPECT_EQ(nearestLatticeDirection(axes[0], { 1, 0, 0 }), (Vec3{ 1, 0, 0 }));
  EXPECT_EQ(nearestLatticeDirection(axes[0], { 1, 1, 0 }), (Vec3{ 1, 1, 0 }));
  EXPECT_EQ(nearestLatticeDirection(axes[1], { 0.02, 1, -0.26 }), (Vec3{ 0, 4, -1 }));
  EXPECT_EQ(nearestLatticeDirection(axes[2], { 0.5, 0, 1 }), (Vec3{ 1, 0, 2 }));
  // About a diagonal axis (1, 1, 0): across it (0, 0, 1) and (−1, 1, 0).
  const PopulationAxis diagonal = populationAxes(2, 45.0, true)[1];
  EXPECT_EQ(nearestLatticeDirection(diagonal, { 1, 1, 0.1 }), (Vec3{ 1, 1, 0 }));
  EXPECT_EQ(nearestLatticeDirection(diagonal, { 1, 1, 0.25 }), (Vec3{ 4, 4, 1 }));
  // About (6, 5, 0), 0.8° nearer is not worth a fiber four times as long: within 1° the shortest.
  const PopulationAxis forty = populationAxes(2, 40.0, true)[1];
  ASSERT_EQ(forty.lattice, (Vec3{ 6, 5, 0 }));
  const Vec3 slightlyOff = normalized(forty.lattice) + 0.0175 * Vec3{ 0, 0, 1 }; // 1.0° up
  EXPECT_EQ(nearestLatticeDirection(forty, slightlyOff), (Vec3{ 6, 5, 0 }));
}

TEST(Dispersion, OpenCubeAndBundleFibersHaveTheTargetC2)
{
  CubeOptions o;
  o.numberOfFibers = 3000;
  o.edgeLength = 20.0;
  o.displacement = 0.0;
  o.realism.dispersionC2 = 0.85;
  const FiberModel m = generateCube(o);
  double mean, se;
  measuredC2(m, 0, mean, se);
  EXPECT_NEAR(mean, 0.85, se);
  EXPECT_NEAR(cubeDispersionC2(o)[0], mean, 1e-12);

  BundleOptions b;
  b.numberOfFibers = 3000;
  b.displacement = 0.0;
  b.length = 20.0;
  b.realism.dispersionC2 = 0.9;
  const FiberModel bundle = generateBundle(b, nullptr);
  measuredC2(bundle, 0, mean, se);
  EXPECT_NEAR(mean, 0.9, se);
}

TEST(Dispersion, PeriodicFibersCloseOnLatticeVectorsNearTheTarget)
{
  CubeOptions o;
  o.numberOfFibers = 600;
  o.populations = 2;
  o.edgeLength = 20.0;
  o.periodic = true;
  o.displacement = 0.1;
  o.realism.dispersionC2 = 0.9;
  o.realism.tortuosity = 1.04;
  const FiberModel m = generateCube(o);
  const PeriodicCell cell = cubeCell(o);
  int tilted = 0;
  for (const Fiber& f : m.fibers)
  {
    Vec3 closure;
    ASSERT_TRUE(isClosedFiber(f, cell, closure));
    EXPECT_EQ(f.points.back(), f.points.front() + closure);
    double len = 0.0;
    for (std::size_t i = 1; i < f.points.size(); ++i)
      len += distance(f.points[i - 1], f.points[i]);
    EXPECT_NEAR(len / norm(closure), 1.04, 1e-3);
    tilted += closure[f.bundle] != norm(closure) ? 1 : 0;
  }
  EXPECT_GT(tilted, 100);
  const std::vector<double> achieved = cubeDispersionC2(o);
  for (int k = 0; k < 2; ++k)
  {
    FiberModel population;
    for (const Fiber& f : m.fibers)
      if (f.bundle == k)
        population.fibers.push_back(f);
    double mean, se;
    measuredC2(population, k, mean, se);
    EXPECT_NEAR(achieved[k], mean, 1e-12);
    // κ is calibrated on the snapped directions and the quantiles are evenly spread: the
    // population reaches the request to within about its standard error.
    EXPECT_NEAR(mean, 0.9, std::max(0.01, 2.0 * se));
  }
}
