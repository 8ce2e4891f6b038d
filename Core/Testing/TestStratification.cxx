// Stratified transverse positions (Tissue/Stratification.h) and their use by the cube's Interwoven
// Random seeding: counts per stratum and per L/3 block, and fibers only moved, never reshaped.
#include "Tissue/CubeGenerator.h"
#include "Tissue/Stratification.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

using namespace fiberpli;

TEST(Stratification, StrataPerSideIsAMultipleOfThreeWithNoMoreStrataThanFibers)
{
  EXPECT_EQ(strataPerSide(0), 3);
  EXPECT_EQ(strataPerSide(17), 3);
  EXPECT_EQ(strataPerSide(36), 6);
  EXPECT_EQ(strataPerSide(60), 6);
  EXPECT_EQ(strataPerSide(81), 9);
  for (std::size_t n = 9; n < 2000; n += 37)
  {
    const int m = strataPerSide(n);
    EXPECT_EQ(m % 3, 0);
    EXPECT_LE(static_cast<std::size_t>(m * m), n) << n;
  }
}

TEST(Stratification, BlocksGetEqualCountsAndWeightsAndStrataEqualCounts)
{
  const int m = 6; // 3 × 3 blocks of 2 × 2 strata
  std::vector<double> weights;
  for (int i = 0; i < 100; ++i)
    weights.push_back(
      0.3 + std::fmod(i * 0.618034, 1.0) * std::fmod(i * 0.414214, 2.0)); // uneven, in [0.3, 2.3)
  const std::vector<int> strata = assignStrata(weights, m, 42, 7);
  ASSERT_EQ(strata.size(), weights.size());
  std::vector<int> perStratum(36, 0);
  std::vector<int> count(9, 0);
  std::vector<double> weight(9, 0.0);
  for (std::size_t i = 0; i < strata.size(); ++i)
  {
    ASSERT_GE(strata[i], 0);
    ASSERT_LT(strata[i], 36);
    ++perStratum[static_cast<std::size_t>(strata[i])];
    const int block = (strata[i] % m) / 2 + 3 * ((strata[i] / m) / 2);
    ++count[static_cast<std::size_t>(block)];
    weight[static_cast<std::size_t>(block)] += weights[i];
  }
  // 100 fibers: every block 11 or 12; a block's 11–12 fibers over its 4 strata: 2 to 3 each.
  const auto [cLo, cHi] = std::minmax_element(count.begin(), count.end());
  EXPECT_LE(*cHi - *cLo, 1);
  for (int c : perStratum)
  {
    EXPECT_GE(c, 2);
    EXPECT_LE(c, 3);
  }
  // One fiber of each weight class of nine per block: the blocks' weights differ by at most the
  // spread of the weights plus the one fiber a block may have more.
  const double wMax = *std::max_element(weights.begin(), weights.end());
  const double wMin = *std::min_element(weights.begin(), weights.end());
  const auto [wLo, wHi] = std::minmax_element(weight.begin(), weight.end());
  EXPECT_LE(*wHi - *wLo, (wMax - wMin) + wMax);
  EXPECT_EQ(assignStrata(weights, m, 42, 7), strata);
  EXPECT_NE(assignStrata(weights, m, 43, 7), strata);
  EXPECT_TRUE(assignStrata(weights, 4, 42, 7).empty());
}

TEST(Stratification, IntoStratumKeepsTheDrawnFractionInsideTheCell)
{
  const double L = 30.0;
  EXPECT_DOUBLE_EQ(intoStratum(-15.0, 0, 3, L), -15.0);
  EXPECT_DOUBLE_EQ(intoStratum(0.0, 1, 3, L), 0.0);    // the middle of the middle cell
  EXPECT_DOUBLE_EQ(intoStratum(0.0, 2, 3, L), 10.0);   // the middle of the last cell
  EXPECT_DOUBLE_EQ(intoStratum(-15.0, 2, 6, L), -5.0); // the start of cell 2 of 6
  for (double t = -15.0; t < 15.0; t += 0.7)
  {
    const double s = intoStratum(t, 4, 6, L);
    EXPECT_GE(s, -15.0 + 4 * 5.0);
    EXPECT_LE(s, -15.0 + 5 * 5.0);
  }
}

namespace
{
CubeOptions threePopulationCell(CubeArrangement arrangement, bool undulating = true)
{
  CubeOptions o;
  o.populations = 3;
  o.numberOfFibers = 270;
  o.edgeLength = 30.0;
  o.segmentLength = 2.0;
  o.fiberRadius = 0.5;
  o.periodic = true;
  o.seed = 11;
  o.arrangement = arrangement;
  o.displacement = undulating ? 0.5 : 0.0;
  if (undulating)
  {
    o.realism.tortuosity = 1.05;
    o.realism.undulationWavelength = 10.0;
  }
  return o;
}
} // namespace

TEST(Stratification, InterwovenCellGivesEveryBlockOfEveryPopulationItsShare)
{
  // Straight fibers: a fiber's place is exact (the rigid moves of undulating ones are checked
  // below).
  const CubeOptions o = threePopulationCell(CubeArrangement::Interwoven, false);
  const FiberModel m = generateCube(o);
  ASSERT_EQ(m.fibers.size(), 270u);
  // 90 fibers a population: each of the 3 × 3 blocks of edge L/3 holds 10.
  int blocks[3][3][3] = {};
  for (const Fiber& f : m.fibers)
  {
    const int k = f.bundle;
    const double half = 0.5 * o.edgeLength;
    const auto block = [&](double t)
    {
      const double u = (t + half) / o.edgeLength;
      return std::min(2, std::max(0, static_cast<int>(std::floor(3.0 * (u - std::floor(u))))));
    };
    Vec3 mean;
    for (const Vec3& p : f.points)
      mean = mean + p;
    mean = (1.0 / static_cast<double>(f.points.size())) * mean;
    ++blocks[k][block(mean[(k + 1) % 3])][block(mean[(k + 2) % 3])];
  }
  for (int k = 0; k < 3; ++k)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
      {
        EXPECT_EQ(blocks[k][a][b], 10) << k << " " << a << " " << b;
      }
}

TEST(Stratification, InterwovenOnlyMovesTheFibersOfAutoRigidly)
{
  const FiberModel moved = generateCube(threePopulationCell(CubeArrangement::Interwoven));
  const FiberModel drawn = generateCube(threePopulationCell(CubeArrangement::Auto));
  ASSERT_EQ(moved.fibers.size(), drawn.fibers.size());
  std::size_t shifted = 0;
  for (std::size_t i = 0; i < moved.fibers.size(); ++i)
  {
    const Fiber& a = moved.fibers[i];
    const Fiber& b = drawn.fibers[i];
    ASSERT_EQ(a.points.size(), b.points.size());
    EXPECT_EQ(a.radii, b.radii);
    const Vec3 shift = a.points.front() - b.points.front();
    EXPECT_DOUBLE_EQ(shift[a.bundle], 0.0); // never along the fiber's own axis
    for (std::size_t p = 0; p < a.points.size(); ++p)
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(a.points[p][c] - b.points[p][c], shift[c], 1e-9);
    shifted += norm(shift) > 1e-12 ? 1 : 0;
  }
  EXPECT_GT(shifted, moved.fibers.size() / 2);
}
