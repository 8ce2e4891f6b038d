// Seeds and radius distributions (docs/tissue-models.md §1, §5.3): grid geometry, cropping, random
// seeds uniform in area, radius statistics.
#include "Tissue/RadiusDistribution.h"
#include "Tissue/Seeds.h"
#include "Util/Random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace fiberpli;

namespace
{
double dist(const Seed2D& a, const Seed2D& b)
{
  return std::hypot(a.x - b.x, a.y - b.y);
}
} // namespace

TEST(Seeds, TriangularGridNeighboursAreExactlyOneSpacingApart)
{
  const double d = 1.7;
  const double half = 12.0;
  const std::vector<Seed2D> grid = triangularGrid(half, half, d);
  ASSERT_GT(grid.size(), 50u);
  for (std::size_t i = 0; i < grid.size(); ++i)
  {
    double nearest = 1e300;
    int atSpacing = 0;
    for (std::size_t j = 0; j < grid.size(); ++j)
    {
      if (i == j)
      {
        continue;
      }
      const double r = dist(grid[i], grid[j]);
      nearest = std::min(nearest, r);
      atSpacing += std::fabs(r - d) < 1e-9 ? 1 : 0;
    }
    EXPECT_NEAR(nearest, d, 1e-9) << "seed " << i;
    // A seed away from the border has the 6 neighbours of a hexagonal lattice.
    if (std::fabs(grid[i].x) < half - d && std::fabs(grid[i].y) < half - d)
    {
      EXPECT_EQ(atSpacing, 6) << "seed " << i;
    }
  }
}

TEST(Seeds, TriangularGridIsCentredSymmetricAndSorted)
{
  const std::vector<Seed2D> grid = triangularGrid(5.0, 4.0, 1.0);
  bool origin = false;
  for (std::size_t i = 0; i < grid.size(); ++i)
  {
    const Seed2D& s = grid[i];
    EXPECT_LE(std::fabs(s.x), 5.0);
    EXPECT_LE(std::fabs(s.y), 4.0);
    origin = origin || (s.x == 0.0 && s.y == 0.0);
    const bool mirrored = std::any_of(grid.begin(), grid.end(),
      [&](const Seed2D& t)
      { return std::fabs(t.x + s.x) < 1e-12 && std::fabs(t.y + s.y) < 1e-12; });
    EXPECT_TRUE(mirrored) << "seed " << i;
    if (i > 0)
    {
      const Seed2D& p = grid[i - 1];
      EXPECT_TRUE(p.y < s.y || (p.y == s.y && p.x < s.x)) << "order at " << i;
    }
  }
  EXPECT_TRUE(origin);
  EXPECT_TRUE(triangularGrid(5.0, 5.0, 0.0).empty());
  EXPECT_TRUE(triangularGrid(5.0, 5.0, std::nan("")).empty());
}

TEST(Seeds, CircleCropKeepsWholeFiberDiscsInside)
{
  const double R = 10.0, d = 2.0, r = 0.8;
  const std::vector<Seed2D> kept = triangularCircle(R, d, r);
  for (const Seed2D& s : kept)
  {
    EXPECT_LE(std::hypot(s.x, s.y), R - r + 1e-12);
  }
  // Exactly the grid points within R − r are kept (none missing).
  std::size_t expected = 0;
  for (const Seed2D& s : triangularGrid(R + d, R + d, d))
  {
    expected += std::hypot(s.x, s.y) <= R - r ? 1 : 0;
  }
  EXPECT_EQ(kept.size(), expected);
  // Lattice points of the hexagonal lattice (d = 2) within 9.2, counted independently in numpy: 85.
  // The area estimate 2/(√3 d²)·π(R − r)² ≈ 77 of docs/tissue-models.md §8 misses the boundary
  // term.
  EXPECT_EQ(kept.size(), 85u);
  const double nominal = M_PI * (R - r) * (R - r) * 2.0 / (std::sqrt(3.0) * d * d);
  EXPECT_NEAR(static_cast<double>(kept.size()), nominal, 0.15 * nominal);
  EXPECT_FALSE(seedInsideCircle({ 0.0, 0.0 }, 2.0, 1.0));
  EXPECT_TRUE(seedInsideCircle({ 0.0, 1.0 }, 1.0, 2.0));
}

TEST(Seeds, RandomSeedsAreUniformInAreaInsideTheDisc)
{
  const double Reff = 9.2;
  const int n = 20000;
  double meanR2 = 0.0, meanX = 0.0, meanY = 0.0;
  int inner = 0;
  for (int j = 0; j < n; ++j)
  {
    RandomStream rng(3, 0, static_cast<std::uint64_t>(j));
    const double u1 = rng.uniform();
    const double u2 = rng.uniform();
    const Seed2D s = randomSeedInDisc(u1, u2, Reff);
    const double r2 = s.x * s.x + s.y * s.y;
    ASSERT_LE(r2, Reff * Reff);
    meanR2 += r2 / n;
    meanX += s.x / n;
    meanY += s.y / n;
    inner += r2 <= 0.25 * Reff * Reff ? 1 : 0;
  }
  // Uniform in area: E|s|² = R²/2, a quarter of the points within R/2, centred.
  EXPECT_NEAR(meanR2, 0.5 * Reff * Reff, 0.02 * Reff * Reff);
  EXPECT_NEAR(static_cast<double>(inner) / n, 0.25, 0.01);
  EXPECT_NEAR(meanX, 0.0, 0.1);
  EXPECT_NEAR(meanY, 0.0, 0.1);
}

TEST(RadiusDistribution, LogNormalHasMedianRAndTruncatedSpread)
{
  const double r = 0.8, s = 0.2;
  const int n = 20000;
  std::vector<double> radii;
  double meanLog = 0.0, meanLog2 = 0.0;
  for (int j = 0; j < n; ++j)
  {
    RandomStream rng(11, 0, static_cast<std::uint64_t>(j));
    const double x = drawFiberRadius(rng, r, s, RadiusDistribution::LogNormal, 100.0);
    radii.push_back(x);
    const double z = std::log(x / r) / s;
    ASSERT_LE(std::fabs(z), 3.0 + 1e-12); // truncated at |z| <= 3
    meanLog += z / n;
    meanLog2 += z * z / n;
  }
  std::nth_element(radii.begin(), radii.begin() + n / 2, radii.end());
  EXPECT_NEAR(radii[n / 2], r, 0.01 * r);
  EXPECT_NEAR(meanLog, 0.0, 0.03);
  // Variance of N(0,1) truncated to |z| <= 3: 1 − 6φ(3)/(2Φ(3) − 1) = 0.9733.
  EXPECT_NEAR(meanLog2, 0.9733, 0.03);
}

TEST(RadiusDistribution, UniformHasMeanRAndStaysInRange)
{
  const double r = 1.0, s = 0.5;
  const int n = 20000;
  double mean = 0.0, lo = 1e300, hi = -1e300;
  for (int j = 0; j < n; ++j)
  {
    RandomStream rng(5, 1, static_cast<std::uint64_t>(j));
    const double x = drawFiberRadius(rng, r, s, RadiusDistribution::Uniform, 100.0);
    mean += x / n;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  EXPECT_NEAR(mean, r, 0.01);
  EXPECT_GE(lo, 0.5);
  EXPECT_LT(hi, 1.5);
  EXPECT_LT(lo, 0.51); // the whole range is used
  EXPECT_GT(hi, 1.49);
}

TEST(RadiusDistribution, ZeroSpreadIsConstantAndRadiiAreClampedToTheBundle)
{
  for (int j = 0; j < 100; ++j)
  {
    RandomStream a(1, 0, static_cast<std::uint64_t>(j));
    EXPECT_EQ(drawFiberRadius(a, 0.8, 0.0, RadiusDistribution::LogNormal, 10.0), 0.8);
    RandomStream b(1, 0, static_cast<std::uint64_t>(j));
    EXPECT_EQ(drawFiberRadius(b, 0.8, 0.0, RadiusDistribution::Uniform, 10.0), 0.8);
    RandomStream c(1, 0, static_cast<std::uint64_t>(j));
    EXPECT_LE(drawFiberRadius(c, 1.0, 0.9, RadiusDistribution::Uniform, 1.2), 1.2);
  }
  RandomStream d(1, 0, 0);
  EXPECT_EQ(drawFiberRadius(d, 5.0, 0.0, RadiusDistribution::LogNormal, 2.0), 2.0);
}

TEST(RadiusDistribution, GammaHasTheShapeAndScaleOfMedusa)
{
  // α = 4, β = 0.25 µm is mean r = αβ = 1, spread s = 1/√α = 0.5. Truncated to [r/4, 4r]: the
  // closed forms of the incomplete gamma function give the truncated mean 1.0153 and standard
  // deviation 0.4909 (P(0.25 <= X <= 4) = 0.98092; P(X < 0.25) = 1 − e⁻¹·(1 + 1 + ½ + ⅙)).
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0, lo = 1e9, hi = 0.0;
  int below = 0;
  for (int j = 0; j < n; ++j)
  {
    RandomStream rng(5, 1, static_cast<std::uint64_t>(j));
    const double x = drawFiberRadius(rng, 1.0, 0.5, RadiusDistribution::Gamma, 100.0);
    sum += x;
    sum2 += x * x;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
    below += x < 0.5 ? 1 : 0;
  }
  const double mean = sum / n;
  const double sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 1.0153, 0.0045);
  EXPECT_NEAR(sd, 0.4909, 0.006);
  EXPECT_GE(lo, 0.25);
  EXPECT_LE(hi, 4.0);
  // P(0.25 <= X < 0.5) / 0.98092: Gamma(4, 1) between 1 and 2 = e⁻¹·8/3 − e⁻²·19/3 = 0.12389.
  EXPECT_NEAR(double(below) / n, 0.12389 / 0.98092, 0.003);
  RandomStream z(1, 0, 0);
  EXPECT_EQ(drawFiberRadius(z, 0.8, 0.0, RadiusDistribution::Gamma, 10.0), 0.8);
}
