// Beading (docs/tissue-models.md §10.3): exact CV and mean per fiber, positivity, periodicity,
// and the correlation length of the field measured from many fibers.
#include "Tissue/Beading.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace fiberpli;

namespace
{
std::vector<double> uniformArc(std::size_t n, double length)
{
  std::vector<double> arc(n);
  for (std::size_t i = 0; i < n; ++i)
    arc[i] = length * static_cast<double>(i) / static_cast<double>(n - 1);
  return arc;
}
} // namespace

TEST(Beading, EveryFiberHasTheRequestedCVAndMeanOne)
{
  for (bool closed : { false, true })
  {
    for (double cv : { 0.05, 0.15, 0.3, 0.6 })
    {
      for (std::uint64_t fiber = 0; fiber < 10; ++fiber)
      {
        RandomStream rng(4, 0, fiber);
        const BeadingProfile p = drawBeading(rng, uniformArc(31, 60.0), 5.0, cv, closed);
        const std::vector<double> f = beadingFactors(p);
        const std::size_t counted = closed ? f.size() - 1 : f.size();
        double mean = 0.0, sq = 0.0;
        for (std::size_t i = 0; i < counted; ++i)
        {
          EXPECT_GT(f[i], 0.0);
          mean += f[i];
        }
        mean /= static_cast<double>(counted);
        for (std::size_t i = 0; i < counted; ++i)
          sq += (f[i] - mean) * (f[i] - mean);
        EXPECT_NEAR(mean, 1.0, 1e-12);
        EXPECT_NEAR(std::sqrt(sq / static_cast<double>(counted)) / mean, cv, 1e-9 * (1.0 + cv));
        if (closed)
        {
          EXPECT_EQ(f.back(), f.front());
        }
      }
    }
  }
}

TEST(Beading, FieldHasTheRequestedCorrelationLength)
{
  // Squared-exponential correlation: at lag ℓ it is exp(−1/2) = 0.607, at 3ℓ exp(−4.5) = 0.011.
  // Estimated from many long fibers (200 ℓ each, so the per-fiber standardisation barely biases
  // it).
  const double ell = 2.0;
  const std::size_t n = 801; // spacing 0.5 µm = ℓ/4
  const std::vector<double> arc = uniformArc(n, 400.0);
  double c1 = 0.0, c3 = 0.0;
  int pairs1 = 0, pairs3 = 0;
  for (std::uint64_t fiber = 0; fiber < 40; ++fiber)
  {
    RandomStream rng(8, 1, fiber);
    const BeadingProfile p = drawBeading(rng, arc, ell, 0.2, true);
    for (std::size_t i = 0; i + 12 < n - 1; ++i)
    {
      c1 += p.field[i] * p.field[i + 4];
      ++pairs1;
      c3 += p.field[i] * p.field[i + 12];
      ++pairs3;
    }
  }
  EXPECT_NEAR(c1 / pairs1, std::exp(-0.5), 0.05);
  EXPECT_NEAR(c3 / pairs3, std::exp(-4.5), 0.05);
}

TEST(Beading, ScaledSigmaGoesFromUniformToTarget)
{
  RandomStream rng(2, 2, 2);
  const BeadingProfile p = drawBeading(rng, uniformArc(50, 100.0), 4.0, 0.25, false);
  EXPECT_NEAR(coefficientOfVariation(beadingFactors(p, 0.0), false), 0.0, 1e-15);
  const double half = coefficientOfVariation(beadingFactors(p, 0.5), false);
  EXPECT_GT(half, 0.05);
  EXPECT_LT(half, 0.25);
  EXPECT_NEAR(coefficientOfVariation(beadingFactors(p, 1.0), false), 0.25, 1e-9);
}
