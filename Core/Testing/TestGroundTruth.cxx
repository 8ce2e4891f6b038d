// Orientation ground truth from fibers (docs/pli-analysis.md §5, test vector A-7), the orientation
// tensor, axis canonicalisation and the comparison metrics.
#include "Analysis/Axis.h"
#include "Analysis/GroundTruth.h"
#include "Analysis/OrientationTensor.h"
#include "Tissue/CubeGenerator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace fiberpli;

namespace
{
constexpr double kDeg = M_PI / 180.0;

Fiber straight(const Vec3& a, const Vec3& b, double r, int bundle = 0, std::int64_t id = 0)
{
  Fiber f;
  f.points = { a, b };
  f.radii = { r, r };
  f.bundle = bundle;
  f.id = id;
  return f;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b)
{
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}
} // namespace

// A-7 first bullet: 3 voxels along x, 1 along y (one of them given with the opposite sign).
TEST(GroundTruth, TensorOfFourVoxelsA7)
{
  TruthAccumulator acc(18, 9);
  acc.addTissue({ 1, 0, 0 });
  acc.addTissue({ -2, 0, 0 }); // sign and length of an axis do not matter
  acc.addTissue({ 1, 0, 0 });
  acc.addTissue({ 0, 1, 0 });
  std::vector<double> hist(18 * 9, -1.0);
  const PixelTruth t = acc.result(hist.data());
  EXPECT_DOUBLE_EQ(t.fraction, 1.0);
  EXPECT_NEAR(t.direction, 0.0, 1e-12);
  EXPECT_NEAR(t.inclinationSigned, 0.0, 1e-12);
  EXPECT_NEAR(t.anisotropy, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(hist[0], 0.75);
  EXPECT_DOUBLE_EQ(hist[9], 0.25); // φ bin 9 = [90°, 100°)
  double sum = 0;
  for (double h : hist)
  {
    sum += h;
  }
  EXPECT_DOUBLE_EQ(sum, 1.0);

  acc.addBackground(4);
  EXPECT_DOUBLE_EQ(acc.result(nullptr).fraction, 0.5);
  acc.reset();
  const PixelTruth empty = acc.result(hist.data());
  EXPECT_TRUE(std::isnan(empty.direction));
  EXPECT_TRUE(std::isnan(empty.fraction));
  EXPECT_EQ(hist[0], 0.0);
}

// A-7 second bullet: (30°, +20°) and (30°, −20°) in equal numbers average to (30°, 0°).
TEST(GroundTruth, SymmetricInclinationsAverageInPlaneA7)
{
  TruthAccumulator acc;
  for (int k = 0; k < 5; ++k)
  {
    acc.addTissue(axisFromAngles(30 * kDeg, 20 * kDeg));
    acc.addTissue(axisFromAngles(30 * kDeg, -20 * kDeg));
  }
  const PixelTruth t = acc.result(nullptr);
  EXPECT_NEAR(t.direction / kDeg, 30.0, 1e-9);
  EXPECT_NEAR(t.inclination / kDeg, 0.0, 1e-9);
  EXPECT_NEAR(t.anisotropy, 0.883022 - 0.116978, 2e-6);

  const Vec3 a = axisFromAngles(30 * kDeg, 20 * kDeg), b = axisFromAngles(30 * kDeg, -20 * kDeg);
  double m[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m[r][c] = 0.5 * (a[r] * a[c] + b[r] * b[c]);
    }
  }
  double values[3];
  Vec3 vectors[3];
  symmetricEigen3(m, values, vectors);
  EXPECT_NEAR(values[0], 0.883022, 1e-6);
  EXPECT_NEAR(values[1], 0.116978, 1e-6);
  EXPECT_NEAR(values[2], 0.0, 1e-12);
  for (int k = 0; k < 3; ++k) // M·v = λ·v
  {
    for (int r = 0; r < 3; ++r)
    {
      const double mv = m[r][0] * vectors[k].x + m[r][1] * vectors[k].y + m[r][2] * vectors[k].z;
      EXPECT_NEAR(mv, values[k] * vectors[k][r], 1e-12);
    }
  }
}

// A-7 metrics.
TEST(GroundTruth, ComparisonMetricsA7)
{
  EXPECT_NEAR(directionDifference(10 * kDeg, 170 * kDeg) / kDeg, 20.0, 1e-9);
  EXPECT_NEAR(axisAngle(10 * kDeg, 0, 170 * kDeg, 0) / kDeg, 20.0, 1e-9);
  EXPECT_NEAR(axisAngle(30 * kDeg, 20 * kDeg, 30 * kDeg, -20 * kDeg) / kDeg, 40.0, 1e-9);
  EXPECT_NEAR(unsignedAxisAngle(30 * kDeg, 20 * kDeg, 30 * kDeg, -20 * kDeg) / kDeg, 0.0, 1e-9);
  EXPECT_NEAR(axisAngle(0, 0, 90 * kDeg, 0) / kDeg, 90.0, 1e-9);
  EXPECT_NEAR(axisAngle(0, 45 * kDeg, 180 * kDeg, -45 * kDeg) / kDeg, 0.0, 1e-6);
  EXPECT_NEAR(axisAngle(30 * kDeg, 20 * kDeg, 35 * kDeg, 25 * kDeg) / kDeg, 6.805610, 1e-6);
}

TEST(GroundTruth, CanonicalAxisAndAngles)
{
  double d, i;
  axisAngles({ -1, 0, 1 }, d, i); // (180°, 45°) ≡ (0°, −45°)
  EXPECT_EQ(d, 0.0);
  EXPECT_NEAR(i / kDeg, -45.0, 1e-12);
  axisAngles({ 0, 0, -3 }, d, i); // vertical-axis rule
  EXPECT_EQ(d, 0.0);
  EXPECT_NEAR(i / kDeg, 90.0, 1e-12);
  axisAngles({ 1, -1, 0 }, d, i);
  EXPECT_NEAR(d / kDeg, 135.0, 1e-12);
  // (π, α) computed in floating point has v_y = +1e-16: the angles must still describe that axis.
  axisAngles(axisFromAngles(M_PI, -45 * kDeg), d, i);
  EXPECT_LT(d, M_PI);
  EXPECT_LE(norm(cross(axisFromAngles(d, i), axisFromAngles(0, 45 * kDeg))), 1e-12);
  axisAngles({ 0, 0, 0 }, d, i);
  EXPECT_TRUE(std::isnan(d));
}

// A-7 third bullet: the S-6 fiber fills the whole VOI; every pixel is (30°, +20°), fraction 1.
TEST(GroundTruth, UniformSlabS6)
{
  const Vec3 u = axisFromAngles(30 * kDeg, 20 * kDeg);
  FiberModel m;
  m.fibers.push_back(straight(-2000.0 * u, 2000.0 * u, 1000.0));
  PixelGrid lat;
  lat.lattice.origin[0] = -10;
  lat.lattice.origin[1] = -10;
  lat.lattice.origin[2] = -30;
  lat.lattice.voxel = 1;
  lat.lattice.n[0] = 20;
  lat.lattice.n[1] = 20;
  lat.lattice.n[2] = 60;
  lat.pixelSize = 2;
  GroundTruthMaps maps;
  GroundTruthOptions o;
  o.threads = 2;
  o.histogram = true;
  ASSERT_EQ(computeGroundTruth(m, lat, o, wholeImage(10, 10), maps).error, "");
  ASSERT_EQ(maps.nx, 10);
  ASSERT_EQ(maps.ny, 10);
  for (std::size_t p = 0; p < 100; ++p)
  {
    EXPECT_EQ(maps.fraction[p], 1.0);
    EXPECT_NEAR(maps.direction[p] / kDeg, 30.0, 1e-9);
    EXPECT_NEAR(maps.inclinationSigned[p] / kDeg, 20.0, 1e-9);
    EXPECT_NEAR(maps.inclination[p] / kDeg, 20.0, 1e-9);
    EXPECT_NEAR(maps.anisotropy[p], 1.0, 1e-12);
    // Histogram: φ bin 3 = [30°, 40°), |α| bin 2 = [20°, 30°) — or bin 1 if 20° rounds below.
    const double* h = maps.histogram.data() + p * 18 * 9;
    EXPECT_DOUBLE_EQ(h[2 * 18 + 3] + h[1 * 18 + 3] + h[2 * 18 + 2] + h[1 * 18 + 2], 1.0);
  }
}

// A-7 fourth bullet (S-8a voxeliser case): fiber along z, pixel = voxel, 10 tissue pixels.
TEST(GroundTruth, VerticalFiberS8a)
{
  const int tissue[3][5] = { { 0, 1, 1, 1, 1 }, { 0, 1, 1, 1, 1 }, { 0, 0, 1, 1, 0 } }; // [x][y]
  for (bool reversed : { false, true })
  {
    FiberModel m;
    m.fibers.push_back(
      reversed ? straight({ 1, 3, 7 }, { 1, 3, 0 }, 2) : straight({ 1, 3, 0 }, { 1, 3, 7 }, 2));
    PixelGrid lat;
    lat.lattice.n[0] = 3;
    lat.lattice.n[1] = 5;
    lat.lattice.n[2] = 7;
    GroundTruthMaps maps;
    GroundTruthOptions o;
    o.threads = 1;
    o.histogram = true;
    ASSERT_EQ(computeGroundTruth(m, lat, o, wholeImage(3, 5), maps).error, "");
    int count = 0;
    for (int y = 0; y < 5; ++y)
    {
      for (int x = 0; x < 3; ++x)
      {
        const std::size_t p = x + 3 * y;
        if (tissue[x][y])
        {
          ++count;
          EXPECT_EQ(maps.fraction[p], 1.0) << x << "," << y;
          EXPECT_EQ(maps.direction[p], 0.0);
          EXPECT_NEAR(maps.inclinationSigned[p] / kDeg, 90.0, 1e-12);
          EXPECT_NEAR(maps.inclination[p] / kDeg, 90.0, 1e-12);
        }
        else
        {
          EXPECT_EQ(maps.fraction[p], 0.0) << x << "," << y;
          EXPECT_TRUE(std::isnan(maps.direction[p]));
          EXPECT_TRUE(std::isnan(maps.inclination[p]));
          EXPECT_EQ(maps.histogram[p * 18 * 9], 0.0);
        }
      }
    }
    EXPECT_EQ(count, 10);
  }
}

// A horizontal fiber of radius 1.2 at (y, z) = (2, 5) in a 4×4×10 lattice: per voxel column at
// y = 1.5 or 2.5 exactly the voxels z = 4.5 and 5.5 are tissue, so every 2×2 pixel holds 4 of
// 40 tissue voxels.
TEST(GroundTruth, PartialCoverageFraction)
{
  FiberModel m;
  m.fibers.push_back(straight({ -5, 2, 5 }, { 9, 2, 5 }, 1.2));
  const PixelGrid lat = latticeForPixelGrid({ 0, 0, 0 }, 2.0, 2, 2, 0.0, 10.0, 2);
  EXPECT_EQ(lat.lattice.voxel, 1.0);
  EXPECT_EQ(lat.lattice.n[2], 10);
  GroundTruthMaps maps;
  ASSERT_EQ(computeGroundTruth(m, lat, GroundTruthOptions{}, wholeImage(2, 2), maps).error, "");
  for (std::size_t p = 0; p < 4; ++p)
  {
    EXPECT_DOUBLE_EQ(maps.fraction[p], 0.1);
    EXPECT_EQ(maps.direction[p], 0.0);
    EXPECT_NEAR(maps.inclination[p], 0.0, 1e-15);
  }
  // Radius scale 2 (the outer layer of a layered fiber) also counts: d <= 2.4.
  GroundTruthOptions o;
  o.radiusScale = 2.0;
  ASSERT_EQ(computeGroundTruth(m, lat, o, wholeImage(2, 2), maps).error, "");
  // r² = 5.76. y = 0.5 (dy² 2.25): dz² <= 3.51 → z 3.5 … 6.5 (4 voxels); y = 1.5 (dy² 0.25):
  // dz² <= 5.51 → again z 3.5 … 6.5 (2.5² > 5.51). Pixel (0, 0): 2 columns × (4 + 4) of 40.
  EXPECT_DOUBLE_EQ(maps.fraction[0], (4 + 4) * 2 / 40.0);
}

// docs/pli-simulation.md §3.3 tie rule: a voxel equidistant from two links belongs to the larger
// global link index, and links are numbered bundle by bundle, not in the order of the fiber list.
TEST(GroundTruth, TiesGoToTheLaterLinkInBundleOrder)
{
  for (int swap = 0; swap < 2; ++swap)
  {
    FiberModel m;
    m.fibers.push_back(straight({ -5, 2, 1.5 }, { 9, 2, 1.5 }, 1.0, swap ? 1 : 0)); // along x
    m.fibers.push_back(straight({ 2, -5, 1.5 }, { 2, 9, 1.5 }, 1.0, swap ? 0 : 1)); // along y
    PixelGrid lat;
    lat.lattice.n[0] = 4;
    lat.lattice.n[1] = 4;
    lat.lattice.n[2] = 3;
    GroundTruthMaps maps;
    ASSERT_EQ(computeGroundTruth(m, lat, GroundTruthOptions{}, wholeImage(4, 4), maps).error, "");
    // Column (1, 1), centres (1.5, 1.5, z): both axes at distance √(0.25 + (z − 1.5)²).
    const std::size_t p = 1 + 4 * 1;
    EXPECT_NEAR(maps.direction[p] / kDeg, swap ? 0.0 : 90.0, 1e-12) << "swap " << swap;
    EXPECT_NEAR(maps.anisotropy[p], 1.0, 1e-12);
  }
}

TEST(GroundTruth, ThreadsAndSubRangesGiveIdenticalMaps)
{
  CubeOptions co;
  co.populations = 3;
  co.numberOfFibers = 40;
  co.edgeLength = 20;
  co.fiberRadius = 1.0;
  co.seed = 5;
  const FiberModel m = generateCube(co);
  const PixelGrid lat = latticeForPixelGrid({ -10, -10, 0 }, 2.0, 10, 10, -4.0, 4.0, 2);
  GroundTruthOptions o1, o2;
  o1.threads = 1;
  o2.threads = 2;
  o1.histogram = o2.histogram = true;
  GroundTruthMaps a, b, part;
  ASSERT_EQ(computeGroundTruth(m, lat, o1, wholeImage(10, 10), a).error, "");
  ASSERT_EQ(computeGroundTruth(m, lat, o2, wholeImage(10, 10), b).error, "");
  EXPECT_TRUE(sameBits(a.direction, b.direction));
  EXPECT_TRUE(sameBits(a.inclinationSigned, b.inclinationSigned));
  EXPECT_TRUE(sameBits(a.fraction, b.fraction));
  EXPECT_TRUE(sameBits(a.histogram, b.histogram));
  int tissuePixels = 0;
  for (double f : a.fraction)
  {
    tissuePixels += f > 0.0;
  }
  EXPECT_GT(tissuePixels, 50); // the test must look at real tissue

  ASSERT_EQ(computeGroundTruth(m, lat, o2, GridRange{ 3, 8, 2, 6 }, part).error, "");
  for (std::int64_t j = 0; j < 10; ++j)
  {
    for (std::int64_t i = 0; i < 10; ++i)
    {
      const std::size_t p = i + 10 * j;
      if (i >= 3 && i < 8 && j >= 2 && j < 6)
      {
        EXPECT_EQ(std::memcmp(&part.fraction[p], &a.fraction[p], sizeof(double)), 0);
        EXPECT_EQ(std::memcmp(&part.direction[p], &a.direction[p], sizeof(double)), 0);
      }
      else
      {
        EXPECT_TRUE(std::isnan(part.fraction[p]));
      }
    }
  }
  // Bad input is reported, naming the problem.
  PixelGrid bad = lat;
  bad.pixelSize = 0.5;
  EXPECT_NE(computeGroundTruth(m, bad, o1, wholeImage(10, 10), part).error.find("PixelSize"),
    std::string::npos);
  FiberModel broken = m;
  broken.fibers[3].radii[0] = -1;
  EXPECT_NE(computeGroundTruth(broken, lat, o1, wholeImage(10, 10), part).error, "");
  EXPECT_NE(computeGroundTruth(m, lat, o1, GridRange{ 0, 11, 0, 10 }, part).error, "");
}

// Whole-model histogram (fastPLI orientation.py): links along +x, −x, +y, −z and a 45° link.
TEST(GroundTruth, ModelOrientationHistogram)
{
  FiberModel m;
  m.fibers.push_back(straight({ 0, 0, 0 }, { 1, 0, 0 }, 1));  // φ 0, θ 90 → (2, 0)
  m.fibers.push_back(straight({ 0, 0, 0 }, { -1, 0, 0 }, 1)); // φ 180, θ 90 → (2, 2)
  m.fibers.push_back(straight({ 0, 0, 0 }, { 0, 0, -1 }, 1)); // antipode +z: θ 0 → (0, 0)
  m.fibers.push_back(
    straight({ 0, 0, 0 }, { 0, -1, -1 }, 1)); // antipode (0,1,1): φ 90, θ 45 → (1, 1)
  const std::vector<double> h = modelOrientationHistogram(m, 4, 3, false, false);
  ASSERT_EQ(h.size(), 12u);
  EXPECT_EQ(h[2 * 4 + 0], 1.0);
  EXPECT_EQ(h[2 * 4 + 2], 1.0);
  EXPECT_EQ(h[0 * 4 + 0], 1.0);
  EXPECT_EQ(h[1 * 4 + 1], 1.0);
  const std::vector<double> n = modelOrientationHistogram(m, 4, 3, true, false);
  EXPECT_DOUBLE_EQ(n[0], 0.25);
  const std::vector<double> s = modelOrientationHistogram(m, 4, 3, true, true);
  // Σ density·solid angle = 1, and the total solid angle of the bins is the half sphere 2π.
  double total = 0;
  for (int it = 0; it < 3; ++it)
  {
    const double omega = (std::cos(it * 30 * kDeg) - std::cos((it + 1) * 30 * kDeg)) * (M_PI / 2);
    for (int ip = 0; ip < 4; ++ip)
    {
      total += s[it * 4 + ip] * omega;
    }
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
  EXPECT_TRUE(modelOrientationHistogram(m, 0, 3, true, true).empty());
}
