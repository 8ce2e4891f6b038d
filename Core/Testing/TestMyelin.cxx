// Myelin (docs/tissue-models.md §10.4): the inner radius of the Constant and Lee2019 g-ratio
// models.
#include "Tissue/Myelin.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace fiberpli;

TEST(Myelin, ConstantGRatioScalesTheOuterRadius)
{
  EXPECT_DOUBLE_EQ(innerRadius(1.5, 0.7, GRatioModel::Constant), 1.05);
  EXPECT_DOUBLE_EQ(innerRadius(0.2, 0.6, GRatioModel::Constant), 0.12);
}

TEST(Myelin, Lee2019SatisfiesItsClosedForm)
{
  // d = 1 µm: thickness 0.35 + 0.006 + 0.024·ln 1 = 0.356 µm, so R = 0.856 µm has inner radius 0.5.
  EXPECT_NEAR(innerRadius(0.856, 0.0, GRatioModel::Lee2019), 0.5, 1e-11);
  double previous = 0.0;
  for (double R : { 0.2, 0.4, 0.8, 1.0, 1.5, 2.5, 4.0 })
  {
    const double r = innerRadius(R, 0.0, GRatioModel::Lee2019);
    const double d = 2.0 * r;
    EXPECT_GT(r, previous);
    EXPECT_LT(r, R);
    EXPECT_NEAR(R - r, 0.35 + 0.006 * d + 0.024 * std::log(d), 1e-11 * R);
    previous = r;
  }
  // A typical corpus callosum axon: outer radius 1 µm gives a g-ratio near 0.65.
  EXPECT_NEAR(innerRadius(1.0, 0.0, GRatioModel::Lee2019) / 1.0, 0.65, 0.03);
}
