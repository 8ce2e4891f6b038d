// PushBoost's two rules (docs/solver.md §4.1) against their closed forms.
#include "Solver/PushBoost.h"

#include <algorithm>

#include <gtest/gtest.h>

using namespace fiberpli;

TEST(PushBoost, ScaleRampsFromSixToNinePairsPerLink)
{
  // 100 links: q = pairs / 100.
  EXPECT_EQ(pushScaleFor(600, 100, 3.0), 1.0); // q = 6: not crowded
  EXPECT_EQ(pushScaleFor(450, 100, 3.0), 1.0);
  EXPECT_DOUBLE_EQ(pushScaleFor(750, 100, 3.0), 2.0); // halfway: 1 + 2 · 0.5
  EXPECT_DOUBLE_EQ(pushScaleFor(900, 100, 3.0), 3.0);
  EXPECT_DOUBLE_EQ(pushScaleFor(5000, 100, 3.0), 3.0); // no more than PushBoost
  EXPECT_EQ(pushScaleFor(5000, 100, 1.0), 1.0);        // off
  EXPECT_EQ(pushScaleFor(10, 0, 3.0), 1.0);            // no links
}

TEST(PushBoost, PushIsTheUnboostedOneWithoutBoost)
{
  for (double overlap : { 0.0, 0.01, 0.3, 1.6 })
  {
    EXPECT_EQ(boostedPush(0.02, 1.0, overlap), 0.02) << overlap;
  }
}

TEST(PushBoost, PushGrowsByTheScaleButNeverBeyondHalfTheOverlap)
{
  const double sigma0 = 0.02, scale = 3.0;                  // boosted push 0.06
  EXPECT_DOUBLE_EQ(boostedPush(sigma0, scale, 1.0), 0.06);  // deep: the full boost
  EXPECT_DOUBLE_EQ(boostedPush(sigma0, scale, 0.12), 0.06); // exactly half the overlap
  EXPECT_DOUBLE_EQ(boostedPush(sigma0, scale, 0.08), 0.04); // half the overlap
  EXPECT_DOUBLE_EQ(boostedPush(sigma0, scale, 0.03), 0.02); // never below the unboosted push
  EXPECT_DOUBLE_EQ(boostedPush(sigma0, scale, 0.0), 0.02);
}

TEST(PushBoost, PushIsMonotoneInOverlapAndScale)
{
  double last = 0.0;
  for (int i = 0; i <= 200; ++i)
  {
    const double p = boostedPush(0.02, 2.5, 0.001 * i);
    EXPECT_GE(p, last);
    EXPECT_LE(p, std::max(0.02, 0.5 * 0.001 * i) + 1e-15);
    last = p;
  }
  EXPECT_LE(boostedPush(0.02, 2.0, 0.5), boostedPush(0.02, 3.0, 0.5));
}
