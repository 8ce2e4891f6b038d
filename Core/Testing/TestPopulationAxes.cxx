// Crossing angle, population shares and arrangement of the cube (docs/tissue-models.md §10.5).
#include "Tissue/CubeGenerator.h"
#include "Tissue/PopulationAxes.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace fiberpli;

namespace
{
CubeOptions twoPopulations()
{
  CubeOptions o;
  o.populations = 2;
  o.numberOfFibers = 80;
  o.edgeLength = 24.0;
  o.fiberRadius = 0.8;
  o.displacement = 0.0;
  o.seed = 3;
  return o;
}

double degrees(double radians)
{
  return radians * 180.0 / M_PI;
}
} // namespace

TEST(PopulationAxes, PeriodicAxesAreLatticeDirectionsNearTheAngle)
{
  EXPECT_TRUE(populationAxes(3, 90.0, true)[1].standard);
  EXPECT_EQ(populationAxes(2, 90.0, true)[1].lattice, (Vec3{ 0, 1, 0 }));
  EXPECT_EQ(populationAxes(2, 45.0, true)[1].lattice, (Vec3{ 1, 1, 0 }));
  EXPECT_EQ(populationAxes(2, 0.0, true)[1].lattice, (Vec3{ 1, 0, 0 }));
  // No direction (p, q) with |p|, |q| <= 6 lies within 1° of 25°: the nearest is (2, 1), 26.57°.
  EXPECT_EQ(populationAxes(2, 25.0, true)[1].lattice, (Vec3{ 2, 1, 0 }));
  for (double omega : { 10.0, 30.0, 40.0, 60.0, 75.0 })
  {
    const std::vector<PopulationAxis> axes = populationAxes(3, omega, true);
    EXPECT_NEAR(axesAngle(axes), omega, 1.0) << omega;
    const Vec3 l = axes[1].lattice;
    EXPECT_EQ(l.x, std::round(l.x));
    EXPECT_EQ(l.y, std::round(l.y));
    EXPECT_EQ(l.z, 0.0);
    EXPECT_EQ(axes[2].lattice, (Vec3{ 0, 0, 1 }));
  }
  EXPECT_NEAR(axesAngle(populationAxes(2, 40.0, false)), 40.0, 1e-12);
}

TEST(PopulationAxes, CubeFibersRunAlongTheCrossingAxisAndClose)
{
  CubeOptions o = twoPopulations();
  o.crossingAngle = 45.0;
  for (bool periodic : { false, true })
  {
    o.periodic = periodic;
    const FiberModel m = generateCube(o);
    ASSERT_EQ(m.fibers.size(), 80u);
    double lo = 1e9, hi = -1e9;
    for (const Fiber& f : m.fibers)
    {
      const Vec3 d = f.points.back() - f.points.front();
      const double angle = degrees(std::atan2(d.y, d.x));
      EXPECT_NEAR(angle, f.bundle == 0 ? 0.0 : 45.0, 1e-9);
      if (periodic && f.bundle == 1)
      {
        Vec3 closure;
        ASSERT_TRUE(isClosedFiber(f, cubeCell(o), closure));
        EXPECT_EQ(f.points.back(), f.points.front() + (Vec3{ 24.0, 24.0, 0.0 }));
        // Points SegmentLength apart along the √2 L long fiber.
        EXPECT_EQ(
          f.points.size(), static_cast<std::size_t>(std::lround(std::sqrt(2.0) * 24.0 / 2.0)) + 1);
      }
      if (f.bundle == 1)
      {
        // The start is spread across the cell, not in one plane.
        lo = std::min(lo, f.points.front().y);
        hi = std::max(hi, f.points.front().y);
      }
    }
    EXPECT_GT(hi - lo, 12.0);
  }
}

TEST(PopulationAxes, SharesSplitFibersAndVolume)
{
  CubeOptions o = twoPopulations();
  o.populationShares = { 3.0, 1.0 };
  EXPECT_EQ(cubePopulationSize(o, 0), 60);
  EXPECT_EQ(cubePopulationSize(o, 1), 20);
  o.numberOfFibers = 10;
  o.populationShares = { 1.0, 1.0, 1.0 };
  o.populations = 3;
  EXPECT_EQ(cubePopulationSize(o, 0), 4); // equal shares: today's split
  o.populationShares = { 1.0, 2.0, 2.0 };
  EXPECT_EQ(cubePopulationSize(o, 0) + cubePopulationSize(o, 1) + cubePopulationSize(o, 2), 10);
  EXPECT_EQ(cubePopulationSize(o, 0), 2);

  CubeOptions v = twoPopulations();
  v.periodic = true;
  v.volumeFraction = 0.4;
  v.radiusSpread = 0.4;
  v.radiusDistribution = RadiusDistribution::Gamma;
  v.populationShares = { 2.0, 1.0 };
  const FiberModel m = generateCube(v);
  double volume[2] = { 0.0, 0.0 };
  double rmax = 0.0;
  for (const Fiber& f : m.fibers)
  {
    volume[f.bundle] += M_PI * f.radii[0] * f.radii[0] * v.edgeLength;
    rmax = std::max(rmax, f.radii[0]);
  }
  EXPECT_NEAR(volume[0] / (volume[0] + volume[1]), 2.0 / 3.0,
    M_PI * rmax * rmax * v.edgeLength / (volume[0] + volume[1]));
}

TEST(PopulationAxes, SheetsSeparateAndInterwovenMixesThePopulations)
{
  CubeOptions o = twoPopulations();
  o.periodic = true;
  o.arrangement = CubeArrangement::Sheets;
  // Random seeding: population 0 below, population 1 above (equal radii: the middle).
  for (const Fiber& f : generateCube(o).fibers)
    for (const Vec3& p : f.points)
    {
      if (f.bundle == 0)
        EXPECT_LE(p.z, 0.0 - 0.8 + 1e-9);
      else
        EXPECT_GE(p.z, 0.0 + 0.8 - 1e-9);
    }
  // Lattice seeding with Sheets packs the two slabs even for equal radii.
  o.seeding = CubeSeeding::Lattice;
  int wrongSide = 0;
  for (const Fiber& f : generateCube(o).fibers)
    wrongSide += (f.bundle == 0) != (f.points.front().z < 0.0) ? 1 : 0;
  EXPECT_EQ(wrongSide, 0);
  // Interwoven with varying radii uses the alternating layers: both populations in both halves.
  o.arrangement = CubeArrangement::Interwoven;
  o.radiusSpread = 0.3;
  o.radiusDistribution = RadiusDistribution::Gamma;
  int below[2] = { 0, 0 };
  for (const Fiber& f : generateCube(o).fibers)
    below[f.bundle] += f.points.front().z < 0.0 ? 1 : 0;
  EXPECT_GT(below[0], 10);
  EXPECT_GT(below[1], 10);
  EXPECT_LT(below[0], 30);
  EXPECT_LT(below[1], 30);
}

TEST(PopulationAxes, BadValuesNameTheProperty)
{
  CubeOptions o = twoPopulations();
  o.crossingAngle = 100.0;
  EXPECT_NE(validateCubeOptions(o).find("CrossingAngle is 100"), std::string::npos);
  o.crossingAngle = NAN;
  EXPECT_NE(validateCubeOptions(o).find("CrossingAngle is nan"), std::string::npos);
  o.crossingAngle = 45.0;
  o.periodic = true;
  o.seeding = CubeSeeding::Lattice;
  EXPECT_NE(validateCubeOptions(o).find("CrossingAngle is 45, which needs Seeding Random"),
    std::string::npos);
  o = twoPopulations();
  o.populationShares = { 1.0, -2.0 };
  EXPECT_NE(validateCubeOptions(o).find("PopulationShares value 1 is -2"), std::string::npos);
  o.populationShares = { 0.0, 0.0 };
  EXPECT_NE(validateCubeOptions(o).find("PopulationShares value 0 is 0"), std::string::npos);
  o.populationShares = {};
  o.populations = 3;
  o.arrangement = CubeArrangement::Sheets;
  EXPECT_NE(validateCubeOptions(o).find("Arrangement is Sheets, which needs Populations 2"),
    std::string::npos);
}
