// PLISimulation options that used to crash, hang or silently give inf/NaN/zero images:
// each is refused with an error naming the property and the value, and the largest accepted value
// still gives a finite image.
#include "MemoryLimitGuard.h"
#include "PLITestUtil.h"

#include "PLI/Optics.h"
#include "PLI/OptionLimits.h"
#include "PLI/PLIPipeline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>

using namespace fiberpli;
using namespace fiberpli::pli;
using plitest::dirVec;
using plitest::line;

namespace
{

FiberModel oneFiber()
{
  FiberModel m;
  m.fibers.push_back(line({ 0, 0, 0 }, dirVec(30, 10), 10, 1.5));
  return m;
}

/// 8 x 8 pixels of 1 µm, 0.5 µm voxels, no tilt, no noise.
PLIOptions smallOptions()
{
  PLIOptions o;
  const double voi[6] = { -4, 4, -4, 4, -2, 2 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  o.voxelSize = 0.5;
  o.pixelSize = 1.0;
  o.numberOfRotations = 6;
  o.noiseGain = 0.0;
  o.numberOfThreads = 1;
  return o;
}

bool allFinite(const PLIImage& img)
{
  for (const Stack& s : img.views)
    for (double v : s.data)
      if (!std::isfinite(v))
        return false;
  return !img.views.empty();
}

std::string errorOf(const PLIOptions& o)
{
  PLIImage img;
  return runPLI(oneFiber(), o, GridRange{}, img).error;
}

void expectNames(const std::string& error, const char* property, const char* value)
{
  EXPECT_NE(error.find(property), std::string::npos) << error;
  EXPECT_NE(error.find(value), std::string::npos) << error;
}

} // namespace

// 1e9 segfaulted (int overflow of the kernel radius), 1e7 hung, 1e5 took minutes.
TEST(PLILimits, HugeOpticalSigmaIsRefused)
{
  for (double sigma : { 1e9, 1e7, 1e5, 2.01 })
  {
    PLIOptions o = smallOptions();
    o.opticalSigma = sigma;
    const std::string e = errorOf(o);
    EXPECT_NE(e.find("OpticalSigma"), std::string::npos) << sigma << ": " << e;
    EXPECT_NE(e.find("8 x 8"), std::string::npos) << e;
  }
}

// The widest accepted kernel (4σ = the 8-pixel side) runs and a blur keeps a uniform image
// uniform: a section without fibers is background everywhere.
TEST(PLILimits, WidestOpticalSigmaStillWorks)
{
  PLIOptions o = smallOptions();
  o.opticalSigma = 2.0;
  PLIImage img;
  const Status st = runPLI(FiberModel{}, o, GridRange{}, img);
  ASSERT_TRUE(st.ok()) << st.error;
  ASSERT_TRUE(allFinite(img));
  PLIOptions sharp = o;
  sharp.opticalSigma = 0.0;
  PLIImage ref;
  ASSERT_TRUE(runPLI(FiberModel{}, sharp, GridRange{}, ref).ok());
  ASSERT_EQ(img.views[0].data.size(), ref.views[0].data.size());
  for (std::size_t k = 0; k < ref.views[0].data.size(); ++k)
    EXPECT_NEAR(img.views[0].data[k], ref.views[0].data[k], 1e-9 * o.lightIntensity);
}

// A kernel several image periods long (mirror edges) is a weighted average: a constant image
// stays constant and, the mirror operator being symmetric, the total is preserved.
TEST(PLILimits, BlurLongerThanTheImageKeepsTotals)
{
  const std::int64_t n = 5;
  Stack in;
  in.resize(GridRange{ 0, n, 0, n }, 1);
  for (std::size_t k = 0; k < in.data.size(); ++k)
    in.data[k] = static_cast<double>((k * 7919) % 13);
  const double total = std::accumulate(in.data.begin(), in.data.end(), 0.0);
  Stack out;
  ASSERT_TRUE(blurStack(in, n, n, 2.4, GridRange{ 0, n, 0, n }, out).ok()); // R = 10 = 2n
  EXPECT_NEAR(std::accumulate(out.data.begin(), out.data.end(), 0.0), total, 1e-9 * total);
  Stack flat = in, flatOut;
  std::fill(flat.data.begin(), flat.data.end(), 3.0);
  ASSERT_TRUE(blurStack(flat, n, n, 2.4, GridRange{ 0, n, 0, n }, flatOut).ok());
  for (double v : flatOut.data)
    EXPECT_NEAR(v, 3.0, 1e-12);
}

TEST(PLILimits, GaussianRadiusCannotOverflow)
{
  EXPECT_EQ(gaussianRadius(0.0), 0);
  EXPECT_EQ(gaussianRadius(1.0), 4);
  EXPECT_EQ(gaussianRadius(1e9), -1);
  EXPECT_EQ(gaussianRadius(INFINITY), -1);
  EXPECT_TRUE(gaussianWeights(1e9).empty());
  Stack in, out;
  in.resize(GridRange{ 0, 4, 0, 4 }, 1);
  EXPECT_FALSE(blurStack(in, 4, 4, 1e9, GridRange{ 0, 4, 0, 4 }, out).ok());
  EXPECT_FALSE(blurStack(in, 4, 4, 3.0, GridRange{ 0, 4, 0, 4 }, out).ok()); // R = 12 > 2·4
}

// 1e308 gave inf images.
TEST(PLILimits, LightIntensityAboveTheLimitIsRefused)
{
  PLIOptions o = smallOptions();
  o.lightIntensity = 1e308;
  expectNames(errorOf(o), "LightIntensity", "1e+308");
  o.lightIntensity = kMaxLightIntensity;
  o.noiseGain = 3.0;
  PLIImage img;
  ASSERT_TRUE(runPLI(oneFiber(), o, GridRange{}, img).ok());
  EXPECT_TRUE(allFinite(img));
}

// 1e300 gave all-zero images (the Gamma shape underflows).
TEST(PLILimits, NoiseGainAboveTheLimitIsRefused)
{
  PLIOptions o = smallOptions();
  o.noiseGain = 1e300;
  expectNames(errorOf(o), "NoiseGain", "1e+300");
  o.noiseGain = kMaxNoiseGain;
  PLIImage img;
  ASSERT_TRUE(runPLI(oneFiber(), o, GridRange{}, img).ok());
  ASSERT_TRUE(allFinite(img));
  // Mean I, variance g·I: over 8·8·6 counts of mean ~13000 the average stays within a few σ.
  double sum = 0.0, expected = 0.0;
  PLIOptions quiet = o;
  quiet.noiseGain = 0.0;
  PLIImage ref;
  ASSERT_TRUE(runPLI(oneFiber(), quiet, GridRange{}, ref).ok());
  for (std::size_t k = 0; k < img.views[0].data.size(); ++k)
  {
    sum += img.views[0].data[k];
    expected += ref.views[0].data[k];
  }
  const double n = static_cast<double>(img.views[0].data.size());
  EXPECT_NEAR(sum / n, expected / n, 6.0 * std::sqrt(kMaxNoiseGain * expected / n / n));
}

// Δn 1e308 gave NaN images.
TEST(PLILimits, BirefringenceAboveOneIsRefused)
{
  PLIOptions o = smallOptions();
  o.layers = "1 1e308 0 p";
  expectNames(errorOf(o), "Layers", "1e+308");
  o.layers = "0.5 0 0 b; 1 -2 0 p";
  expectNames(errorOf(o), "Layers", "-2");
  o.layers = "";
  o.birefringence = 1e308;
  expectNames(errorOf(o), "Birefringence", "1e+308");
  o.birefringence = -kMaxBirefringence;
  PLIImage img;
  ASSERT_TRUE(runPLI(oneFiber(), o, GridRange{}, img).ok());
  EXPECT_TRUE(allFinite(img));
}

// The size guard is the machine's memory budget (FIBERPLI_MEMORY_LIMIT here), not 16 GiB.
TEST(PLILimits, SimulationSizeFollowsTheMemoryBudget)
{
  PLIOptions o = smallOptions();
  PLIImage img;
  {
    fiberpli::testing::MemoryLimitGuard limit("64K");
    const Status st = runPLI(oneFiber(), o, GridRange{}, img);
    EXPECT_NE(st.error.find("VoxelSize"), std::string::npos) << st.error;
    EXPECT_NE(st.error.find("memory budget"), std::string::npos) << st.error;
  }
  fiberpli::testing::MemoryLimitGuard limit("64M");
  EXPECT_TRUE(runPLI(oneFiber(), o, GridRange{}, img).ok());
}

// The budget is per piece: a whole image above it is refused, but its quarter (one MPI rank's
// piece of a split) runs and equals the crop of the whole image computed without the limit.
TEST(PLILimits, MemoryBudgetIsCheckedPerPiece)
{
  PLIOptions o = smallOptions();
  const double voi[6] = { -8, 8, -8, 8, -2, 2 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  PLIPlan plan;
  ASSERT_TRUE(planPLI(oneFiber(), o, plan).ok());
  const GridRange whole{ 0, plan.pixels[0], 0, plan.pixels[1] };
  const GridRange quarter{ 0, plan.pixels[0] / 2, 0, plan.pixels[1] / 2 };
  const double wholeBytes = estimatePieceBytes(plan, o, whole);
  const double pieceBytes = estimatePieceBytes(plan, o, quarter);
  ASSERT_LT(1.5 * pieceBytes, wholeBytes);
  EXPECT_EQ(plan.estimatedBytes, wholeBytes);
  PLIImage full;
  ASSERT_TRUE(runPLI(oneFiber(), o, whole, full).ok());
  const std::string between =
    std::to_string(static_cast<long long>(std::sqrt(wholeBytes * pieceBytes)));
  fiberpli::testing::MemoryLimitGuard limit(between.c_str());
  EXPECT_TRUE(planPLI(oneFiber(), o, plan).ok()); // planning never refuses a job that may be split
  PLIImage img;
  const Status refused = runPLI(oneFiber(), o, whole, img);
  EXPECT_NE(refused.error.find("memory budget"), std::string::npos) << refused.error;
  EXPECT_NE(refused.error.find("MPI"), std::string::npos) << refused.error;
  ASSERT_TRUE(runPLI(oneFiber(), o, quarter, img).ok());
  for (std::int64_t j = quarter.j0; j < quarter.j1; ++j)
    for (std::int64_t i = quarter.i0; i < quarter.i1; ++i)
      for (int k = 0; k < img.views[0].nrho; ++k)
        ASSERT_EQ(img.views[0].at(i, j, k), full.views[0].at(i, j, k)) << i << " " << j << " " << k;
}

TEST(PLILimits, EnumerationCodesAreCheckedNotCast)
{
  // Interp and TiltConvention are 8-bit enums: a cast of 256 would silently give NN / Physical.
  Interp interp = Interp::Slerp;
  for (int bad : { -1, 3, 256 })
  {
    EXPECT_EQ(interpolationFromCode(bad, interp),
      "Interpolation is " + std::to_string(bad) + ", must be 0 (nearest), 1 (linear) or 2 (Slerp)");
    EXPECT_EQ(interp, Interp::Slerp); // untouched on error
  }
  EXPECT_EQ(interpolationFromCode(0, interp), "");
  EXPECT_EQ(interp, Interp::NN);
  EXPECT_EQ(interpolationFromCode(1, interp), "");
  EXPECT_EQ(interp, Interp::Lerp);
  TiltConvention convention = TiltConvention::Physical;
  for (int bad : { -1, 2, 256 })
  {
    EXPECT_NE(
      tiltConventionFromCode(bad, convention).find("TiltConvention is " + std::to_string(bad)),
      std::string::npos);
    EXPECT_EQ(convention, TiltConvention::Physical);
  }
  EXPECT_EQ(tiltConventionFromCode(1, convention), "");
  EXPECT_EQ(convention, TiltConvention::FastPLI);
}
