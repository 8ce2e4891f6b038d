// The one shape of a refused value (Util/ValueCheck.h): the message names the option, the value in
// its short form and the rule; a chain keeps the first refusal.
#include "Util/ValueCheck.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace fiberpli;

TEST(ValueCheck, MessageShape)
{
  EXPECT_EQ(mustBe("VoxelSize", 0.0, "> 0"), "VoxelSize is 0, must be > 0");
  EXPECT_EQ(mustBe("NumberOfSides", 2, "in [3, 256]"), "NumberOfSides is 2, must be in [3, 256]");
  // The value as it reads back, not rounded to six digits.
  EXPECT_EQ(mustBe("StepSize", 0.1234567, "> 0"), "StepSize is 0.1234567, must be > 0");
  EXPECT_EQ(mustBe("Wavelength", std::nan(""), "> 0"), "Wavelength is nan, must be > 0");
}

TEST(ValueCheck, Rules)
{
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ValueChecks().positive("a", 1e-300).error(), "");
  EXPECT_EQ(ValueChecks().positive("a", 0.0).error(), "a is 0, must be > 0");
  EXPECT_EQ(ValueChecks().positive("a", inf).error(), "a is inf, must be > 0");
  EXPECT_EQ(ValueChecks().atLeast("b", 1.0, 1.0).error(), "");
  EXPECT_EQ(ValueChecks().atLeast("b", 0.5, 1.0).error(), "b is 0.5, must be >= 1");
  EXPECT_EQ(ValueChecks().atLeast("b", std::nan(""), 0.0).error(), "b is nan, must be >= 0");
  EXPECT_EQ(ValueChecks().atLeast("n", -1, 0).error(), "n is -1, must be >= 0");
  EXPECT_EQ(ValueChecks().within("c", 1.0, 0.0, 1.0).error(), "");
  EXPECT_EQ(
    ValueChecks().within("c", std::nan(""), 0.0, 1.0).error(), "c is nan, must be in [0, 1]");
  EXPECT_EQ(ValueChecks().within("c", 2.0, 0.0, 1e15, " (x)").error(), "");
  EXPECT_EQ(ValueChecks().within("c", 2e15, 0.0, 1e15, " (x)").error(),
    "c is 2e+15, must be in [0, 1e+15] (x)");
}

TEST(ValueCheck, FirstRefusalWins)
{
  ValueChecks c;
  c.positive("first", 1.0)
    .then("")
    .atLeast("second", -2.0, 0.0)
    .positive("third", 0.0)
    .then("fourth");
  EXPECT_EQ(c.error(), "second is -2, must be >= 0");
  EXPECT_EQ(
    ValueChecks().then("written elsewhere").positive("x", 0.0).error(), "written elsewhere");
}
