// Cube benchmark generator (docs/tissue-models.md §6.1): counts, directions, displacement bound,
// seeds.
#include "MemoryLimitGuard.h"
#include "Tissue/BundleOptions.h"
#include "Tissue/CubeGenerator.h"
#include "Tissue/RadiusDistribution.h"
#include "Util/NumberFormat.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace fiberpli;

namespace
{
CubeOptions smallCube(int populations)
{
  CubeOptions o;
  o.populations = populations;
  o.numberOfFibers = 100;
  o.edgeLength = 20.0;
  o.segmentLength = 2.0;
  o.displacement = 0.5;
  o.fiberRadius = 0.8;
  o.seed = 7;
  return o;
}
} // namespace

TEST(CubeGenerator, SplitsFibersEvenlyOverPopulations)
{
  for (int pops = 1; pops <= 3; ++pops)
  {
    CubeOptions o = smallCube(pops);
    FiberModel m = generateCube(o);
    ASSERT_EQ(m.fibers.size(), 100u);
    int count[3] = { 0, 0, 0 };
    for (const Fiber& f : m.fibers)
    {
      ASSERT_GE(f.bundle, 0);
      ASSERT_LT(f.bundle, pops);
      ++count[f.bundle];
    }
    // 100 over 3 populations is 34 + 33 + 33, as in the reference construction.
    for (int k = 0; k < pops; ++k)
    {
      EXPECT_EQ(count[k], 100 / pops + (k < 100 % pops ? 1 : 0));
    }
  }
  EXPECT_EQ(cubePopulationSize(smallCube(3), 0), 34);
}

TEST(CubeGenerator, FibersRunAlongTheirPopulationAxisWithinDisplacement)
{
  CubeOptions o = smallCube(3);
  FiberModel m = generateCube(o);
  const double half = o.edgeLength / 2.0;
  const int n = static_cast<int>(std::lround(o.edgeLength / o.segmentLength)) + 1;
  for (const Fiber& f : m.fibers)
  {
    ASSERT_EQ(static_cast<int>(f.points.size()), n);
    const int axis = f.bundle;
    // The undisplaced fiber is a line along 'axis'; estimate its transverse position by the mean.
    Vec3 mean;
    for (const Vec3& p : f.points)
    {
      mean += p;
    }
    mean = mean / static_cast<double>(n);
    for (int i = 0; i < n; ++i)
    {
      const Vec3& p = f.points[static_cast<std::size_t>(i)];
      const double nominal = -half + o.edgeLength * i / (n - 1);
      EXPECT_LE(std::abs(p[axis] - nominal), o.displacement + 1e-12);
      for (int a = 0; a < 3; ++a)
      {
        if (a == axis)
        {
          continue;
        }
        // Every point is within 2D of every other point transversally (both displaced by <= D).
        EXPECT_LE(std::abs(p[a] - mean[a]), 2.0 * o.displacement + 1e-12);
        EXPECT_LE(std::abs(p[a]), half + o.displacement + 1e-12);
      }
      EXPECT_EQ(f.radii[static_cast<std::size_t>(i)], o.fiberRadius);
    }
  }
}

TEST(CubeGenerator, TransversePositionsAreUniformOverTheCube)
{
  CubeOptions o = smallCube(1);
  o.numberOfFibers = 4000;
  o.displacement = 0.0;
  FiberModel m = generateCube(o);
  double sum = 0.0;
  double sumSq = 0.0;
  for (const Fiber& f : m.fibers)
  {
    const double y = f.points[0].y;
    sum += y;
    sumSq += y * y;
  }
  const double n = static_cast<double>(m.fibers.size());
  const double mean = sum / n;
  const double var = sumSq / n - mean * mean;
  const double L = o.edgeLength;
  // U[-L/2, L/2]: mean 0, variance L²/12; 4000 samples → standard error of the mean ≈ 0.09.
  EXPECT_NEAR(mean, 0.0, 0.5);
  EXPECT_NEAR(var, L * L / 12.0, 0.08 * L * L / 12.0);
}

TEST(CubeGenerator, SameSeedSameModelOtherSeedOtherModel)
{
  CubeOptions o = smallCube(2);
  FiberModel a = generateCube(o);
  FiberModel b = generateCube(o);
  o.seed = 8;
  FiberModel c = generateCube(o);
  ASSERT_EQ(a.fibers.size(), b.fibers.size());
  bool anyDifferent = false;
  for (std::size_t i = 0; i < a.fibers.size(); ++i)
  {
    ASSERT_EQ(a.fibers[i].points.size(), b.fibers[i].points.size());
    for (std::size_t j = 0; j < a.fibers[i].points.size(); ++j)
    {
      EXPECT_EQ(a.fibers[i].points[j], b.fibers[i].points[j]);
      anyDifferent = anyDifferent || a.fibers[i].points[j] != c.fibers[i].points[j];
    }
    EXPECT_EQ(a.fibers[i].id, static_cast<std::int64_t>(i));
  }
  EXPECT_TRUE(anyDifferent);
}

TEST(CubeGenerator, RejectsBadOptionsByName)
{
  CubeOptions o = smallCube(1);
  EXPECT_TRUE(validateCubeOptions(o).empty());
  o.populations = 4;
  EXPECT_NE(validateCubeOptions(o).find("Populations"), std::string::npos);
  o = smallCube(1);
  o.fiberRadius = -1.0;
  EXPECT_NE(validateCubeOptions(o).find("FiberRadius"), std::string::npos);
  o = smallCube(1);
  o.segmentLength = std::nan("");
  EXPECT_NE(validateCubeOptions(o).find("SegmentLength"), std::string::npos);
  o = smallCube(1);
  o.numberOfFibers = 2000000000;
  o.segmentLength = 0.001;
  EXPECT_NE(validateCubeOptions(o).find("would need"), std::string::npos);
}

TEST(CubeGenerator, LogNormalSpreadThatUnderflowsTheRadiiIsRefused)
{
  // RadiusSpread 1e300 (or 1000) made LogNormal radii r·exp(s·z) underflow to 0: the disk packing
  // of Lattice seeding then placed nothing and was read anyway (a crash), and Random seeding gave
  // fibers of radius 0. Both sources check the spread with the same rule, naming it and its value.
  CubeOptions o;
  o.populations = 1;
  o.edgeLength = 20.0;
  o.periodic = true;
  o.numberOfFibers = 50;
  o.radiusDistribution = RadiusDistribution::LogNormal;
  o.seeding = CubeSeeding::Lattice;
  for (double spread : { 1e300, 1000.0, 2.5 })
  {
    o.radiusSpread = spread;
    const std::string e = validateCubeOptions(o);
    EXPECT_NE(e.find("RadiusSpread is " + formatNumber(spread)), std::string::npos) << e;
    EXPECT_NE(e.find("LogNormal"), std::string::npos) << e;
    EXPECT_LT(e.size(), 200u) << "a number in long form: " << e;
  }
  BundleOptions b;
  b.radiusDistribution = RadiusDistribution::LogNormal;
  b.radiusSpread = 1e300;
  EXPECT_NE(validateBundleOptions(b).find("RadiusSpread is 1e+300"), std::string::npos)
    << validateBundleOptions(b);
  // The largest accepted spread still gives radii that are positive normal numbers.
  o.radiusSpread = kMaxLogNormalSpread;
  o.populations = 2;
  ASSERT_EQ(validateCubeOptions(o), "");
  const FiberModel m = generateCube(o);
  ASSERT_EQ(m.fibers.size(), 50u);
  for (const Fiber& f : m.fibers)
  {
    EXPECT_GE(f.radii[0], o.fiberRadius * std::exp(-3.0 * o.radiusSpread) * (1 - 1e-12));
  }
}

TEST(CubeGenerator, VolumeFractionRefusalNamesItAndTheRealCount)
{
  // A broad radius spread with VolumeFraction used to be refused as "NumberOfFibers 1.1e+08 ..."
  // (every fiber assumed as thin as the thinnest radius, and a property the user did not set).
  // The message names VolumeFraction and the count generateCube really makes.
  CubeOptions o;
  o.populations = 2;
  o.periodic = true;
  o.edgeLength = 400.0;
  o.volumeFraction = 0.3;
  o.radiusDistribution = RadiusDistribution::LogNormal;
  o.radiusSpread = 1.0;
  std::string e;
  {
    fiberpli::testing::MemoryLimitGuard limit("1M");
    e = validateCubeOptions(o);
  }
  ASSERT_NE(e, "");
  EXPECT_NE(e.find("VolumeFraction 0.3 ("), std::string::npos) << e;
  EXPECT_EQ(e.find("NumberOfFibers"), std::string::npos) << e;
  // The count in the message is the count generateCube makes.
  const std::size_t made = generateCube(o).fibers.size();
  EXPECT_NE(e.find("(" + std::to_string(made) + " fibers)"), std::string::npos)
    << made << ": " << e;
  // ... far below the old estimate, every fiber as thin as the thinnest radius r e^-3s.
  const double thinnest = o.fiberRadius * std::exp(-3.0 * o.radiusSpread);
  EXPECT_LT(static_cast<double>(made),
    0.01 * o.volumeFraction * o.edgeLength * o.edgeLength / (M_PI * thinnest * thinnest));
}
