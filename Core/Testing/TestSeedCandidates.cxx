// Spread seeding of the field source (docs/field-source.md §4.1): the occupancy grid's overlap
// measure, and candidate lines that start a dense model with fewer overlapping capsules.
#include "BruteForceOverlap.h"
#include "Field/FieldFibers.h"
#include "Field/OccupancyGrid.h"
#include "FieldTestFields.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace fiberpli;
using fiberpli::testing::bendAbout;
using fiberpli::testing::makeField;

namespace
{
std::vector<Vec3> lineAlongX(double y, double z)
{
  std::vector<Vec3> line;
  for (int i = 0; i <= 10; ++i)
  {
    line.push_back({ 2.0 * i, y, z });
  }
  return line;
}

double totalVolume(const FiberModel& model)
{
  double v = 0.0;
  for (const Fiber& f : model.fibers)
  {
    for (std::size_t i = 1; i < f.points.size(); ++i)
    {
      v += M_PI * f.radii[i] * f.radii[i] * distance(f.points[i - 1], f.points[i]);
    }
  }
  return v;
}
} // namespace

TEST(OccupancyGrid, OverlapIsZeroApartAndFallsWithDistance)
{
  OccupancyGrid grid({ 0, 0, 0 }, { 20, 20, 20 }, 0.5, 1u << 20);
  EXPECT_DOUBLE_EQ(grid.edge(), 0.5);
  const std::vector<double> radii(11, 1.0);
  EXPECT_EQ(grid.overlap(lineAlongX(10, 10), 1.0), 0u); // nothing placed yet
  grid.add(lineAlongX(10, 10), radii);
  // Farther than two radii and a voxel diagonal: no voxel shared.
  EXPECT_EQ(grid.overlap(lineAlongX(10, 13.0), 1.0), 0u);
  std::uint64_t previous = grid.overlap(lineAlongX(10, 10), 1.0);
  EXPECT_GT(previous, 0u);
  for (double d : { 0.5, 1.0, 1.5, 2.0 })
  {
    const std::uint64_t o = grid.overlap(lineAlongX(10, 10 + d), 1.0);
    EXPECT_LT(o, previous) << "at distance " << d;
    previous = o;
  }
  // A line outside the box counts nothing and does not crash.
  EXPECT_EQ(grid.overlap(lineAlongX(-50, -50), 1.0), 0u);
}

TEST(OccupancyGrid, CoarsensToStayWithinItsVoxelBudget)
{
  const OccupancyGrid grid({ 0, 0, 0 }, { 100, 100, 100 }, 0.1, 1000000);
  EXPECT_GE(grid.edge(), 1.0); // (100 / edge)³ <= 10⁶
  EXPECT_LT(grid.edge(), 1.25 * 1.25);
}

TEST(SeedCandidates, FewerOverlapsAtTheSameVolumeFraction)
{
  const OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 31, 16, 16 },
    [](const Vec3&) {
      return Vec3{ 1, 0.2, 0 };
    });
  FieldFiberOptions o;
  o.volumeFraction = 0.4;
  o.fiberRadius = 0.6;
  o.trace.segmentLength = 1.5;
  o.seed = 3;
  const FieldFiberResult random = generateFieldFibers({ &f }, o);
  o.seedCandidates = 32;
  const FieldFiberResult spread = generateFieldFibers({ &f }, o);
  ASSERT_TRUE(random.ok() && spread.ok()) << random.error << spread.error;
  // Both stop at the first fiber that reaches the target volume.
  const double target = 0.4 * 30.0 * 15.0 * 15.0;
  EXPECT_NEAR(totalVolume(random.model), target, 0.05 * target);
  EXPECT_NEAR(totalVolume(spread.model), target, 0.05 * target);
  const std::size_t before = fiberpli_test::refCollisionCount(random.model);
  const std::size_t after = fiberpli_test::refCollisionCount(spread.model);
  EXPECT_GT(before, 100u);
  EXPECT_LT(2 * after, before) << "random " << before << ", 32 candidates " << after;
}

TEST(SeedCandidates, TheThreadCountDoesNotChangeTheFibers)
{
  const OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 21, 21, 7 }, bendAbout(5.0, 18.0));
  FieldFiberOptions o;
  o.volumeFraction = 0.35;
  o.fiberRadius = 0.5;
  o.trace.segmentLength = 1.0;
  o.seedCandidates = 20;
  o.threads = 1;
  const FieldFiberResult one = generateFieldFibers({ &f }, o);
  o.threads = 3;
  const FieldFiberResult three = generateFieldFibers({ &f }, o);
  ASSERT_TRUE(one.ok() && three.ok());
  ASSERT_EQ(one.model.fibers.size(), three.model.fibers.size());
  for (std::size_t i = 0; i < one.model.fibers.size(); ++i)
  {
    EXPECT_EQ(one.model.fibers[i].points, three.model.fibers[i].points);
    EXPECT_EQ(one.model.fibers[i].radii, three.model.fibers[i].radii);
  }
}

TEST(SeedCandidates, OutOfRangeNamesTheProperty)
{
  const OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 11, 11, 11 },
    [](const Vec3&) {
      return Vec3{ 1, 0, 0 };
    });
  FieldFiberOptions o;
  o.seedCandidates = 0;
  EXPECT_EQ(validateFieldFiberOptions(o, f, 1), "SeedCandidates is 0, must be in [1, 64]");
  o.seedCandidates = 65;
  EXPECT_EQ(validateFieldFiberOptions(o, f, 1), "SeedCandidates is 65, must be in [1, 64]");
  o.seedCandidates = 64;
  EXPECT_EQ(validateFieldFiberOptions(o, f, 1), "");
}
