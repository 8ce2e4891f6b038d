// End-to-end PLI simulation (docs/pli-simulation.md §8 S-6, S-7), determinism over threads and
// tiles, pixel sub-rectangles equal to the crop of the whole image, option validation.
#include "PLI/PLIPipeline.h"
#include "PLI/Simulator.h"
#include "PLI/TissueSpec.h"
#include "PLITestUtil.h"
#include "Tissue/CubeGenerator.h"

#include <gtest/gtest.h>

using namespace fiberpli;
using namespace fiberpli::pli;
using namespace plitest;

namespace
{
PLIOptions slabOptions()
{
  PLIOptions o;
  const double voi[6] = { -10, 10, -10, 10, -30, 30 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  o.voxelSize = 1;
  o.pixelSize = 2;
  o.opticalSigma = 0.71;
  o.noiseGain = 0;
  o.numberOfRotations = 18;
  o.tiltAngle = 5.5;
  o.layers = "1 -0.001 0 p";
  o.numberOfThreads = 1;
  return o;
}

FiberModel slabFiber()
{
  FiberModel m;
  m.fibers.push_back(line({ 0, 0, 0 }, dirVec(30, 20), 2000, 1000));
  return m;
}

void expectViews(const PLIImage& img, const double dir[5], const double ret[5])
{
  ASSERT_EQ(img.views.size(), 5u);
  for (int v = 0; v < 5; ++v)
  {
    const Stack& s = img.views[v];
    ASSERT_EQ(s.nx, 10);
    ASSERT_EQ(s.ny, 10);
    for (std::int64_t p = 0; p < s.nx * s.ny; ++p)
    {
      const Epa e = epa(&s.data[p * 18], 18);
      ASSERT_LT(dirDiff(e.dirDeg, dir[v]), 1e-4) << "view " << v << " pixel " << p;
      ASSERT_NEAR(e.ret, ret[v], 1e-6) << "view " << v << " pixel " << p;
      ASSERT_NEAR(e.T, 13000, 13000 * 1e-6) << "view " << v;
    }
  }
}

FiberModel smallCube()
{
  CubeOptions c;
  c.populations = 2;
  c.numberOfFibers = 60;
  c.edgeLength = 12;
  c.seed = 3;
  return generateCube(c);
}

PLIOptions cubeOptions()
{
  PLIOptions o;
  const double voi[6] = { -4, 4, -4, 4, -3, 3 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  o.voxelSize = 0.25;
  o.pixelSize = 1.0;
  o.numberOfRotations = 9;
  o.tiltAngle = 5.5;
  o.layers = "0.666 0 5 b; 1 0.004 1 r";
  o.tileSize = 16;
  o.numberOfThreads = 1;
  o.seed = 17;
  return o;
}
} // namespace

TEST(PLIPipeline, S6UniformSlabPhysical)
{
  PLIImage img;
  const Status st = runPLI(slabFiber(), slabOptions(), GridRange{}, img);
  ASSERT_TRUE(st.ok()) << st.error;
  EXPECT_FALSE(img.emptySection);
  EXPECT_EQ(img.plan.pixels[0], 10);
  EXPECT_DOUBLE_EQ(img.plan.thickness, 60.0);
  EXPECT_DOUBLE_EQ(img.plan.imageOrigin[0], -9.0);
  const double dir[5] = { 30.0, 31.1522, 28.1205, 29.1380, 31.5904 };
  const double ret[5] = { 0.592436, 0.560579, 0.576308, 0.622326, 0.611887 };
  expectViews(img, dir, ret);
}

TEST(PLIPipeline, S6UniformSlabFastPLIConventionAndAbsorption)
{
  PLIOptions o = slabOptions();
  o.tiltConvention = TiltConvention::FastPLI;
  PLIImage img;
  ASSERT_TRUE(runPLI(slabFiber(), o, GridRange{}, img).ok());
  const double dir[5] = { 30.0, 29.1380, 31.5904, 31.1522, 28.1205 };
  const double ret[5] = { 0.592436, 0.622326, 0.611887, 0.560579, 0.576308 };
  expectViews(img, dir, ret);

  o = slabOptions();
  o.layers = "1 -0.001 5 p";
  ASSERT_TRUE(runPLI(slabFiber(), o, GridRange{}, img).ok());
  EXPECT_NEAR(epa(img.views[0].data.data(), 18).T, 9630.6369, 1e-3);
  for (int v = 1; v < 5; ++v)
    EXPECT_NEAR(epa(img.views[v].data.data(), 18).T, 9617.2834, 1e-3);

  o = slabOptions();
  o.stepRule = StepRule::FastPLIMidpoint;
  ASSERT_TRUE(runPLI(slabFiber(), o, GridRange{}, img).ok());
  EXPECT_NEAR(epa(img.views[1].data.data(), 18).ret, 0.558309, 1e-6);
}

TEST(PLIPipeline, S7RadialMyelinColumns)
{
  FiberModel m;
  m.fibers.push_back(line({ 0, 0, 0 }, { 1, 0, 0 }, 1000, 10));
  TissueSpec spec;
  ASSERT_TRUE(makeTissueSpec("1 0.004 0 r", { 0 }, 0, 0, 0, spec).ok());
  SectionLattice lat;
  lat.origin[0] = 0;
  lat.origin[1] = -12;
  lat.origin[2] = -12;
  lat.n[0] = 2;
  lat.n[1] = 24;
  lat.n[2] = 24;
  SimParams p;
  for (int k = 0; k < 6; ++k)
    p.rho.push_back(k * M_PI / 6);
  p.threads = 1;
  std::vector<Stack> out;
  ASSERT_TRUE(simulate(m, spec, lat, p, { View{} }, { 0, 2, 0, 24 }, out).status.ok());
  const std::pair<int, double> rows[] = { { 12, 0.066528 }, { 13, 0.202773 }, { 16, 0.459252 },
    { 20, 0.419627 } };
  for (const auto& r : rows)
    for (int i = 0; i < 2; ++i)
    {
      const Epa e = epa(&out[0].at(i, r.first, 0), 6);
      EXPECT_NEAR(e.ret, r.second, 1e-6) << "y " << r.first - 11.5;
      EXPECT_LT(dirDiff(e.dirDeg, 0), 1e-4) << "y " << r.first - 11.5;
    }
}

TEST(PLIPipeline, ThreadsAndTilesGiveBitIdenticalImages)
{
  const FiberModel m = smallCube();
  PLIOptions o = cubeOptions();
  PLIImage a, b, c;
  ASSERT_TRUE(runPLI(m, o, GridRange{}, a).ok());
  EXPECT_FALSE(a.emptySection);
  o.numberOfThreads = 2;
  ASSERT_TRUE(runPLI(m, o, GridRange{}, b).ok());
  o.tileSize = 7;
  ASSERT_TRUE(runPLI(m, o, GridRange{}, c).ok());
  ASSERT_EQ(a.views.size(), 5u);
  for (int v = 0; v < 5; ++v)
  {
    EXPECT_EQ(a.views[v].data, b.views[v].data) << "view " << v;
    EXPECT_EQ(a.views[v].data, c.views[v].data) << "view " << v;
  }
  // Real structure: the image is not flat.
  const auto mm = std::minmax_element(a.views[0].data.begin(), a.views[0].data.end());
  EXPECT_LT(*mm.first, 0.9 * *mm.second);
}

TEST(PLIPipeline, SubRectangleEqualsCropOfWholeImage)
{
  const FiberModel m = smallCube();
  const PLIOptions o = cubeOptions();
  PLIImage whole;
  ASSERT_TRUE(runPLI(m, o, GridRange{}, whole).ok());
  ASSERT_EQ(whole.plan.pixels[0], 8);
  const GridRange pieces[] = { { 0, 3, 0, 8 }, { 3, 8, 0, 2 }, { 3, 8, 2, 8 }, { 5, 6, 4, 5 } };
  for (const GridRange& r : pieces)
  {
    PLIImage piece;
    ASSERT_TRUE(runPLI(m, o, r, piece).ok());
    for (int v = 0; v < 5; ++v)
      for (std::int64_t j = r.j0; j < r.j1; ++j)
        for (std::int64_t i = r.i0; i < r.i1; ++i)
          for (int k = 0; k < 9; ++k)
            ASSERT_EQ(piece.views[v].at(i, j, k), whole.views[v].at(i, j, k))
              << "view " << v << " pixel " << i << "," << j;
  }
}

TEST(PLIPipeline, SeededNoiseIsReproducible)
{
  const FiberModel m = smallCube();
  PLIOptions o = cubeOptions();
  PLIImage a, b, c;
  ASSERT_TRUE(runPLI(m, o, GridRange{}, a).ok());
  ASSERT_TRUE(runPLI(m, o, GridRange{}, b).ok());
  o.seed = 18;
  ASSERT_TRUE(runPLI(m, o, GridRange{}, c).ok());
  EXPECT_EQ(a.views[0].data, b.views[0].data);
  EXPECT_NE(a.views[0].data, c.views[0].data);
  for (double v : a.views[0].data)
    EXPECT_EQ(v, std::floor(v)); // counts
}

TEST(PLIPipeline, EmptySectionGivesBackgroundAndWarning)
{
  PLIOptions o = cubeOptions();
  const double voi[6] = { 100, 104, 100, 104, -3, 3 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  o.noiseGain = 0;
  o.backgroundAbsorption = 2;
  PLIImage img;
  const Status st = runPLI(smallCube(), o, GridRange{}, img);
  ASSERT_TRUE(st.ok());
  EXPECT_TRUE(img.emptySection);
  EXPECT_FALSE(st.warnings.empty());
  // Path 6 µm untilted, 6/cos 5.5° µm in the tilted views.
  for (std::size_t v = 0; v < img.views.size(); ++v)
    for (double x : img.views[v].data)
      EXPECT_NEAR(x, 6500 * std::exp(-2.0 * 0.006 / (v == 0 ? 1.0 : std::cos(5.5 * M_PI / 180))),
        1e-9 * 6500);
}

TEST(PLIPipeline, OptionsAreValidatedBeforeAllocation)
{
  const FiberModel m = smallCube();
  PLIImage img;
  PLIOptions o = cubeOptions();
  o.voxelSize = 0;
  EXPECT_NE(runPLI(m, o, GridRange{}, img).error.find("VoxelSize"), std::string::npos);
  o = cubeOptions();
  o.volumeOfInterest[2] = 5; // y min > y max only
  EXPECT_NE(runPLI(m, o, GridRange{}, img).error.find("VolumeOfInterest y"), std::string::npos);
  o = cubeOptions();
  o.pixelSize = 0.1;
  EXPECT_NE(runPLI(m, o, GridRange{}, img).error.find("PixelSize"), std::string::npos);
  o = cubeOptions();
  const double huge[6] = { -5000, 5000, -5000, 5000, -30, 30 };
  std::copy(huge, huge + 6, o.volumeOfInterest);
  o.voxelSize = 0.05;
  const Status st = runPLI(m, o, GridRange{}, img);
  EXPECT_NE(st.error.find("GiB"), std::string::npos) << st.error;
  EXPECT_NE(st.error.find("VoxelSize"), std::string::npos);
  o = cubeOptions();
  o.tiltAngle = 45;
  EXPECT_NE(runPLI(m, o, GridRange{}, img).error.find("TiltAngle"), std::string::npos);
  o = cubeOptions();
  o.noiseGain = 0.5;
  EXPECT_NE(runPLI(m, o, GridRange{}, img).error.find("NoiseGain"), std::string::npos);
  o = cubeOptions();
  EXPECT_FALSE(runPLI(m, o, GridRange{ 0, 9, 0, 2 }, img).ok()); // outside the 8 x 8 image

  PLIPlan plan;
  ASSERT_TRUE(planPLI(m, cubeOptions(), plan).ok());
  EXPECT_EQ(plan.bytesPerVoxel, 16u);
  EXPECT_GT(plan.estimatedBytes, 0.0);
  EXPECT_EQ(plan.views.size(), 5u);
  EXPECT_EQ(plan.lattice.n[2], 24);
}
