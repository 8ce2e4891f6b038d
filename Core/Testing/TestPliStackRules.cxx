// How the analysis reads a PLISimulation image (Analysis/PliStackRules.h): polarizer angles, tilted
// views and their set-up from the field data, the tilted-sensor rule, and the errors naming the
// array or field data at fault.
#include "Analysis/PliStackRules.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace fiberpli;

namespace
{
constexpr double kDeg = M_PI / 180.0;

/// An image with an intensity array of n components and `tilts` tilted stacks of n components.
PliStackFields stackOf(int n, std::size_t tilts)
{
  PliStackFields f;
  f.hasIntensity = true;
  f.components = n;
  f.tiltComponents.assign(tilts, n);
  return f;
}

bool mentions(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}
} // namespace

TEST(PliStackRules, EquidistantAnglesWithoutField)
{
  const std::vector<double> rho = polarizerAnglesOf(stackOf(4, 0));
  ASSERT_EQ(rho.size(), 4u);
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_NEAR(rho[k], k * M_PI / 4, 1e-15);
  }
}

TEST(PliStackRules, FieldAnglesWin)
{
  PliStackFields f = stackOf(3, 0);
  f.hasPolarizerAngles = true;
  f.polarizerAngles = { 10, 70, 130 };
  PliStackLayout layout;
  ASSERT_EQ(decodePliStack(f, InclinationMethod::Auto, layout), "");
  ASSERT_EQ(layout.rho.size(), 3u);
  EXPECT_NEAR(layout.rho[1], 70 * kDeg, 1e-15);
  EXPECT_EQ(layout.tiltStacks, 0u);
  EXPECT_TRUE(layout.tiltViews.empty());
}

TEST(PliStackRules, TooFewOrMismatchedAngles)
{
  PliStackLayout layout;
  const std::string few = decodePliStack(stackOf(2, 0), InclinationMethod::Auto, layout);
  EXPECT_TRUE(mentions(few, "2 polarizer angles")) << few;
  PliStackFields f = stackOf(5, 0);
  f.hasPolarizerAngles = true;
  f.polarizerAngles = { 0, 60, 120 };
  const std::string mismatch = decodePliStack(f, InclinationMethod::Auto, layout);
  EXPECT_TRUE(mentions(mismatch, "'intensity' has 5 components")) << mismatch;
  EXPECT_TRUE(mentions(mismatch, "has 3 angles")) << mismatch;
}

TEST(PliStackRules, ImageShapeErrors)
{
  PliStackLayout layout;
  PliStackFields f = stackOf(4, 0);
  f.slices = 3;
  EXPECT_TRUE(mentions(decodePliStack(f, InclinationMethod::Auto, layout), "3 slices along z"));
  f = stackOf(4, 0);
  f.hasIntensity = false;
  EXPECT_TRUE(
    mentions(decodePliStack(f, InclinationMethod::Auto, layout), "no point array 'intensity'"));
  f = stackOf(4, 3);
  f.tiltComponents[1] = 6;
  const std::string e = decodePliStack(f, InclinationMethod::Auto, layout);
  EXPECT_TRUE(mentions(e, "'intensity_tilt_1' has 6 components")) << e;
}

TEST(PliStackRules, OlderOneAngleFormGivesFourAzimuths)
{
  PliStackFields f = stackOf(9, 4);
  f.tiltAngle = 5.5;
  PliStackLayout layout;
  ASSERT_EQ(decodePliStack(f, InclinationMethod::Auto, layout), "");
  ASSERT_EQ(layout.tiltStacks, 4u);
  ASSERT_EQ(layout.tiltViews.size(), 4u);
  for (int v = 0; v < 4; ++v)
  {
    EXPECT_NEAR(layout.tiltViews[v].theta, 5.5 * kDeg, 1e-15);
    EXPECT_NEAR(layout.tiltViews[v].azimuth, v * M_PI / 2, 1e-15);
  }
}

TEST(PliStackRules, TiltViewsPerView)
{
  PliStackFields f = stackOf(9, 2);
  f.hasTiltAngles = true;
  f.tiltAngles = { 4, 8 };
  f.tiltDirections = { 30, 210 };
  std::vector<TiltView> views;
  ASSERT_EQ(tiltViewsOf(f, 2, views), "");
  ASSERT_EQ(views.size(), 2u);
  EXPECT_NEAR(views[1].theta, 8 * kDeg, 1e-15);
  EXPECT_NEAR(views[1].azimuth, 210 * kDeg, 1e-15);
}

TEST(PliStackRules, CountsThatDoNotMatchTheStacks)
{
  PliStackFields f = stackOf(9, 2);
  f.hasTiltAngles = true;
  f.tiltAngles = { 4, 8, 12 };
  f.tiltDirections = { 0, 180 };
  std::vector<TiltView> views;
  const std::string angles = tiltViewsOf(f, 2, views);
  EXPECT_TRUE(mentions(angles, "'tilt_angles' has 3 values for 2 tilted views")) << angles;
  // Two views in the older form: no default azimuths exist for them.
  PliStackFields older = stackOf(9, 2);
  older.tiltAngle = 5;
  const std::string azimuths = tiltViewsOf(older, 2, views);
  EXPECT_TRUE(mentions(azimuths, "'tilt_directions' has 0 values for 2 tilted views")) << azimuths;
  EXPECT_TRUE(views.empty());
}

TEST(PliStackRules, TiltedSensorRefusesTheTiltFitAndAutoDropsTheViews)
{
  PliStackFields f = stackOf(9, 4);
  f.tiltAngle = 5.5;
  f.tiltedSensor = 1;
  PliStackLayout layout;
  const std::string e = decodePliStack(f, InclinationMethod::Tilt, layout);
  EXPECT_TRUE(mentions(e, "tilted_sensor = 1")) << e;
  for (InclinationMethod m : { InclinationMethod::Auto, InclinationMethod::Retardation })
  {
    ASSERT_EQ(decodePliStack(f, m, layout), "");
    EXPECT_EQ(layout.tiltStacks, 0u);
    EXPECT_TRUE(layout.tiltViews.empty());
  }
  f.tiltedSensor = 0; // registered views: the tilt fit may read them
  ASSERT_EQ(decodePliStack(f, InclinationMethod::Tilt, layout), "");
  EXPECT_EQ(layout.tiltStacks, 4u);
}

TEST(PliStackRules, ConventionAndNoiseGain)
{
  PliStackFields f = stackOf(3, 0);
  f.tiltConvention = 1;
  f.noiseGain = 2.5;
  PliStackLayout layout;
  ASSERT_EQ(decodePliStack(f, InclinationMethod::Auto, layout), "");
  EXPECT_EQ(layout.convention, TiltConvention::FastPLI);
  EXPECT_EQ(layout.noiseGain, 2.5);
  f.tiltConvention = 0;
  f.noiseGain = -1;
  ASSERT_EQ(decodePliStack(f, InclinationMethod::Auto, layout), "");
  EXPECT_EQ(layout.convention, TiltConvention::Physical);
  EXPECT_LT(layout.noiseGain, 0.0);
}
