// Polarimeter set-ups beyond the default: any list of polarizer angles, any set of tilt angles
// and azimuths, simulated and analysed back to the fiber of a uniform slab; bad lists are errors
// naming the property and the value.
#include "Analysis/Axis.h"
#include "Analysis/PliAnalysis.h"
#include "PLI/PLIPipeline.h"
#include "PLITestUtil.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace fiberpli;
using namespace fiberpli::pli;
using namespace plitest;

namespace
{
constexpr double kDeg = M_PI / 180.0;

// A slab of 20 × 20 × 60 µm cut from one thick fiber (radius 1 mm) of axis (dir, incl).
FiberModel slab(double dirDeg, double inclDeg)
{
  FiberModel m;
  m.fibers.push_back(line({ 0, 0, 0 }, dirVec(dirDeg, inclDeg), 2000, 1000));
  return m;
}

// Clean voxel-resolution images: PixelSize = VoxelSize, no blur, no noise.
PLIOptions slabOptions()
{
  PLIOptions o;
  const double voi[6] = { -10, 10, -10, 10, -30, 30 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  o.voxelSize = 2;
  o.pixelSize = 2;
  o.opticalSigma = 0;
  o.noiseGain = 0;
  o.layers = "1 -0.001 0 p";
  o.numberOfThreads = 1;
  return o;
}

// Simulates and analyses like PLISimulation → PLIAnalysis: the analysis reads the set-up from the
// plan exactly as the VTK filter reads it from the field data.
PliAnalysisMaps simulateAndAnalyse(
  const FiberModel& m, const PLIOptions& o, InclinationMethod method)
{
  PLIImage img;
  const Status st = runPLI(m, o, fiberpli::GridRange{}, img);
  EXPECT_TRUE(st.ok()) << st.error;
  PliStack s;
  s.nx = img.plan.pixels[0];
  s.ny = img.plan.pixels[1];
  s.rho = img.plan.rho;
  s.intensity = img.views[0].data.data();
  for (std::size_t v = 1; v < img.views.size(); ++v)
  {
    s.tilts.push_back(img.views[v].data.data());
    s.tiltViews.push_back(
      TiltView{ img.plan.tiltDeg[v - 1] * kDeg, img.plan.azimuthDeg[v - 1] * kDeg });
  }
  s.convention = o.tiltConvention == fiberpli::TiltConvention::FastPLI
    ? fiberpli::TiltConvention::FastPLI
    : fiberpli::TiltConvention::Physical;
  s.noiseGain = 0.0;
  PliAnalysisOptions a;
  a.method = method;
  a.threads = 1;
  PliAnalysisMaps maps;
  EXPECT_EQ(analysePli(s, a, wholeImage(s.nx, s.ny), maps).error, "");
  return maps;
}

double angleBetweenAxesDeg(double dirA, double inclA, double dirB, double inclB)
{
  const Vec3 a = axisFromAngles(dirA, inclA), b = axisFromAngles(dirB, inclB);
  return std::acos(std::min(1.0, std::fabs(dot(a, b)))) / kDeg;
}
} // namespace

TEST(PLISetUp, ArbitraryPolarizerAnglesGiveTheFiberDirection)
{
  for (double dir : { 0.0, 37.0, 101.0, 163.0 })
  {
    PLIOptions o = slabOptions();
    o.rotationAngles = { 0, 15, 50, 100, 170 };
    PLIPlan plan;
    ASSERT_TRUE(planPLI(slab(dir, 20), o, plan).ok());
    ASSERT_EQ(plan.rho.size(), 5u);
    EXPECT_NEAR(plan.rho[2], 50 * kDeg, 1e-15);
    const PliAnalysisMaps m = simulateAndAnalyse(slab(dir, 20), o, InclinationMethod::Retardation);
    for (double d : m.direction)
      EXPECT_LT(dirDiff(d / kDeg, dir), 1e-6) << dir;
  }
  // The same list in another order only permutes the components.
  PLIOptions a = slabOptions(), b = slabOptions();
  a.rotationAngles = { 0, 15, 50, 100, 170 };
  b.rotationAngles = { 170, 50, 0, 100, 15 };
  PLIImage ia, ib;
  ASSERT_TRUE(runPLI(slab(37, 20), a, fiberpli::GridRange{}, ia).ok());
  ASSERT_TRUE(runPLI(slab(37, 20), b, fiberpli::GridRange{}, ib).ok());
  const int perm[5] = { 4, 2, 0, 3, 1 }; // b[k] = a[perm[k]]
  for (int k = 0; k < 5; ++k)
    EXPECT_EQ(ib.views[0].at(3, 4, k), ia.views[0].at(3, 4, perm[k]));
}

TEST(PLISetUp, TiltFitReturnsTheInclinationForAnyTiltSet)
{
  struct Case
  {
    std::vector<double> angles, azimuths;
  };
  const Case cases[] = {
    { { 3.9 }, {} },
    { { 8 }, {} },
    { { 3.9, 8 }, {} },            // 8 tilted views
    { { 5.5 }, { 30, 150, 270 } }, // three azimuths, none on an axis
    { { 3.9, 8 }, { 45, 135, 225, 315 } },
  };
  for (const Case& c : cases)
    for (auto conv : { fiberpli::TiltConvention::Physical, fiberpli::TiltConvention::FastPLI })
      for (double incl : { -50.0, 20.0, 65.0 })
      {
        PLIOptions o = slabOptions();
        o.numberOfRotations = 9;
        o.tiltAngles = c.angles;
        o.tiltAzimuths = c.azimuths;
        o.tiltConvention = conv;
        const PliAnalysisMaps m = simulateAndAnalyse(slab(60, incl), o, InclinationMethod::Auto);
        ASSERT_EQ(m.method, InclinationMethod::Tilt);
        for (std::size_t p = 0; p < m.direction.size(); ++p)
        {
          // Noise-free data fit the model exactly: far inside the 1° a measurement would need.
          ASSERT_LT(
            angleBetweenAxesDeg(m.direction[p], m.inclinationSigned[p], 60 * kDeg, incl * kDeg),
            0.01)
            << c.angles.size() << " angles, " << c.azimuths.size() << " azimuths, inclination "
            << incl;
          ASSERT_NEAR(m.inclination[p] / kDeg, std::fabs(incl), 0.01);
        }
      }
}

TEST(PLISetUp, TiltedViewsAreEveryAngleWithEveryAzimuth)
{
  PLIOptions o = slabOptions();
  o.tiltAngles = { 3.9, 8 };
  o.tiltAzimuths = { 10, 200 };
  o.refractiveIndex = 1.5;
  PLIPlan plan;
  ASSERT_TRUE(planPLI(slab(0, 0), o, plan).ok());
  ASSERT_EQ(plan.views.size(), 5u);
  const double t1 = std::asin(std::sin(3.9 * kDeg) / 1.5), t2 = std::asin(std::sin(8 * kDeg) / 1.5);
  const double expect[4][2] = { { t1, 10 }, { t1, 200 }, { t2, 10 }, { t2, 200 } };
  for (int v = 0; v < 4; ++v)
  {
    EXPECT_NEAR(plan.views[v + 1].theta, expect[v][0], 1e-15);
    EXPECT_NEAR(plan.views[v + 1].phi, expect[v][1] * kDeg, 1e-15);
    EXPECT_NEAR(plan.tiltDeg[v], expect[v][0] / kDeg, 1e-12);
    EXPECT_EQ(plan.azimuthDeg[v], expect[v][1]);
  }
  EXPECT_NEAR(plan.tiltInTissue, t2, 1e-15);
  // TiltAngle is the one-angle shorthand: the same views as TiltAngles {5.5}.
  PLIOptions a = slabOptions(), b = slabOptions();
  a.tiltAngle = 5.5;
  b.tiltAngles = { 5.5 };
  PLIPlan pa, pb;
  ASSERT_TRUE(planPLI(slab(0, 0), a, pa).ok());
  ASSERT_TRUE(planPLI(slab(0, 0), b, pb).ok());
  ASSERT_EQ(pa.views.size(), 5u);
  ASSERT_EQ(pb.views.size(), 5u);
  for (int v = 0; v < 5; ++v)
  {
    EXPECT_EQ(pa.views[v].theta, pb.views[v].theta);
    EXPECT_EQ(pa.views[v].phi, pb.views[v].phi);
  }
}

TEST(PLISetUp, BadListsAreErrorsNamingThePropertyAndValue)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Bad
  {
    std::vector<double> rot, tilt, az;
    const char* words[2];
  };
  const Bad bad[] = {
    { { 0, 10 }, {}, {}, { "RotationAngles", "2 values" } },
    { { 0, 15, 15 }, {}, {}, { "RotationAngles[1] and [2]", "15" } },
    { { 0, nan, 90 }, {}, {}, { "RotationAngles[1]", "nan" } },
    { { 0, 90, 180 }, {}, {}, { "RotationAngles[2]", "180" } },
    { { -10, 30, 60 }, {}, {}, { "RotationAngles[0]", "-10" } },
    { {}, { 95 }, {}, { "TiltAngles[0]", "95" } },
    { {}, { 3.9, 45 }, {}, { "TiltAngles[1]", "45" } },
    { {}, { 0 }, {}, { "TiltAngles[0]", "0 deg" } },
    { {}, { 8, 8 }, {}, { "TiltAngles[0] and [1]", "8" } },
    { {}, { 5.5 }, { 0, 90, 90 }, { "TiltAzimuths[1] and [2]", "90" } },
    { {}, { 5.5 }, { 360 }, { "TiltAzimuths[0]", "360" } },
    { {}, { 5.5 }, { nan }, { "TiltAzimuths[0]", "nan" } },
  };
  for (const Bad& b : bad)
  {
    PLIOptions o = slabOptions();
    o.rotationAngles = b.rot;
    o.tiltAngles = b.tilt;
    o.tiltAzimuths = b.az;
    PLIPlan plan;
    const Status st = planPLI(slab(0, 0), o, plan);
    ASSERT_FALSE(st.ok()) << b.words[0];
    for (const char* w : b.words)
      EXPECT_NE(st.error.find(w), std::string::npos) << st.error;
  }
  // NumberOfRotations is only checked when it is used.
  PLIOptions o = slabOptions();
  o.numberOfRotations = 0;
  PLIPlan plan;
  EXPECT_NE(planPLI(slab(0, 0), o, plan).error.find("NumberOfRotations"), std::string::npos);
  o.rotationAngles = { 0, 60, 120 };
  EXPECT_TRUE(planPLI(slab(0, 0), o, plan).ok());
}

TEST(PLISetUp, AnalysisRefusesTiltStacksWithoutTheirSetUp)
{
  const std::vector<double> I(18 * 4, 1000.0);
  PliStack s;
  s.nx = 2;
  s.ny = 2;
  for (int k = 0; k < 18; ++k)
    s.rho.push_back(k * 10 * kDeg);
  s.intensity = I.data();
  s.tilts = { I.data(), I.data(), I.data(), I.data() };
  PliAnalysisOptions a;
  a.method = InclinationMethod::Tilt;
  PliAnalysisMaps m;
  // No tilt set-up for the four stacks (an empty tilt_angles list).
  std::string err = analysePli(s, a, wholeImage(2, 2), m).error;
  EXPECT_NE(err.find("4 tilted stacks"), std::string::npos) << err;
  EXPECT_NE(err.find("tilt_angles"), std::string::npos) << err;
  // Only one tilted view: the fit cannot separate direction, inclination and thickness.
  s.tilts = { I.data() };
  s.tiltViews = { TiltView{ 5 * kDeg, 0 } };
  err = analysePli(s, a, wholeImage(2, 2), m).error;
  EXPECT_NE(err.find("at least 2"), std::string::npos) << err;
  a.method = InclinationMethod::Auto;
  EXPECT_EQ(analysePli(s, a, wholeImage(2, 2), m).error, "");
  EXPECT_EQ(m.method, InclinationMethod::Retardation);
  // Two equal views.
  s.tilts = { I.data(), I.data() };
  s.tiltViews = { TiltView{ 5 * kDeg, 0 }, TiltView{ 5 * kDeg, 2 * M_PI } };
  a.method = InclinationMethod::Tilt;
  err = analysePli(s, a, wholeImage(2, 2), m).error;
  EXPECT_NE(err.find("are the same"), std::string::npos) << err;
}
