// CATERPillar voxel.csv, CACTUS strand files and MC/DC cylinder lists: round trips point by point,
// the sphere-chain tolerance against its closed form, and malformed files.
#include "IO/CactusFormat.h"
#include "IO/CaterpillarFormat.h"
#include "IO/McdcCylinders.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>

using namespace fiberpli;

namespace
{

FiberModel curvedModel()
{
  FiberModel m;
  for (int f = 0; f < 3; ++f)
  {
    Fiber fiber;
    fiber.id = 10 + f;
    fiber.bundle = f % 2;
    for (int i = 0; i < 6; ++i)
    {
      const double t = 0.7 * i;
      fiber.points.push_back(
        { 3.0 * f + 0.4 * std::sin(t + f), 0.1 * std::cos(1.3 * t), 1.9 * i + 0.123456789 * f });
      fiber.radii.push_back(0.5 + 0.05 * i + 0.01 * f);
    }
    m.fibers.push_back(fiber);
  }
  return m;
}

/// Distance of p from the segment a-b.
double segmentDistance(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  double t = dot(p - a, ab) / dot(ab, ab);
  t = std::min(1.0, std::max(0.0, t));
  return norm(p - (a + ab * t));
}

} // namespace

TEST(CaterpillarFormat, SpacingKeepsTheGrooveWithinTheTolerance)
{
  for (double r : { 0.2, 1.0, 3.0 })
  {
    for (double tol : { 0.001, 0.05, 0.5 * r })
    {
      const double s = caterpillarSphereSpacing(r, tol);
      // Groove depth of two spheres of radius r at distance s: r - sqrt(r^2 - (s/2)^2).
      EXPECT_NEAR(r - std::sqrt(r * r - 0.25 * s * s), tol, 1e-12 * r);
    }
  }
  EXPECT_DOUBLE_EQ(caterpillarSphereSpacing(1.0, 2.0), 2.0);
}

TEST(CaterpillarFormat, RoundTripKeepsEveryPointAndFillsLinksWithinTolerance)
{
  FiberModel m = curvedModel();
  for (Fiber& f : m.fibers)
  {
    for (double r : f.radii)
    {
      f.innerRadii.push_back(0.7 * r);
    }
  }
  const double tol = 0.02;
  std::stringstream file;
  ASSERT_EQ(writeCaterpillarCsv(file, m, tol), "");
  EXPECT_TRUE(looksLikeCaterpillarCsv(file));
  const FiberReadResult back = readCaterpillarCsv(file, "voxel.csv");
  ASSERT_TRUE(back.ok()) << back.error;
  ASSERT_EQ(back.model.fibers.size(), m.fibers.size());
  for (std::size_t f = 0; f < m.fibers.size(); ++f)
  {
    const Fiber& a = m.fibers[f];
    const Fiber& b = back.model.fibers[f];
    ASSERT_EQ(b.innerRadii.size(), b.size());
    EXPECT_EQ(b.id, a.id);
    EXPECT_EQ(b.bundle, a.bundle);
    // Walk the read chain: every original point appears, bit for bit, in order; the spheres between
    // lie on the link, with spacing within the tolerance's bound.
    std::size_t j = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
      while (j < b.size() &&
        !(b.points[j].x == a.points[i].x && b.points[j].y == a.points[i].y &&
          b.points[j].z == a.points[i].z))
      {
        ASSERT_GT(i, 0u) << "the first sphere is the first point";
        EXPECT_LT(segmentDistance(b.points[j], a.points[i - 1], a.points[i]), 1e-12);
        ++j;
      }
      ASSERT_LT(j, b.size()) << "point " << i << " of fiber " << f << " is missing";
      EXPECT_EQ(b.radii[j], a.radii[i]);
      EXPECT_EQ(b.innerRadii[j], a.innerRadii[i]);
      ++j;
    }
    EXPECT_EQ(j, b.size());
    for (std::size_t k = 0; k + 1 < b.size(); ++k)
    {
      const double rMin = std::min(b.innerRadii[k], b.innerRadii[k + 1]);
      EXPECT_LE(
        norm(b.points[k + 1] - b.points[k]), caterpillarSphereSpacing(rMin, tol) * (1 + 1e-9));
    }
  }
}

TEST(CaterpillarFormat, ReadsCaterpillarOwnLayoutAndSkipsGlia)
{
  std::istringstream in("cell_type cell_id component component_id X Y Z inner_radius outer_radius\n"
                        "axon 4 axon 0 1 2 3 0.5 0.8\n"
                        "axon 4 axon 0 1 2 4 0.5 0.8\n"
                        "axon 4 axon 0 1 2 5 0.6 0.9\n"
                        "axon 7 axon 0 5 5 5 1 1\n"
                        "glial_cell 9 soma 0 0 0 0 3 3\n"
                        "glial_cell 9 branch 1 0 0 1 1 1\n"
                        "glial_cell 9 branch 1 0 0 2 1 1\n");
  const FiberReadResult r = readCaterpillarCsv(in, "voxel.csv");
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.model.fibers.size(), 1u);
  EXPECT_EQ(r.model.fibers[0].id, 4);
  EXPECT_EQ(r.model.fibers[0].size(), 3u);
  EXPECT_EQ(r.model.fibers[0].radii[2], 0.9);
  EXPECT_EQ(r.model.fibers[0].innerRadii[2], 0.6);
  EXPECT_EQ(r.droppedFibers, 1u); // axon 7: one sphere
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("3 spheres"), std::string::npos);
}

TEST(CaterpillarFormat, MalformedFilesNameTheLine)
{
  const std::string header = std::string(kCaterpillarHeader) + "\n";
  struct Case
  {
    std::string text;
    std::string expected;
  };
  const Case cases[] = {
    { "x,y,z\n1,2,3\n", "voxel.csv line 1: expected the CATERPillar header" },
    { header + "axon 1 axon 0 1 2 3 0.5 0.8\naxon 1 axon 0 1 2\n",
      "voxel.csv line 3: expected 9 fields" },
    { header + "axon 1 axon 0 1 nan 3 0.5 0.8\n",
      "voxel.csv line 2: 'nan' is not a finite number" },
    { header + "axon 1 axon 0 1 2 3 0.5 -0.8\n",
      "voxel.csv line 2: outer_radius -0.8 must be > 0" },
    { header + "axon 1 axon 0 1 2 3 -0.5 0.8\n",
      "voxel.csv line 2: inner_radius -0.5 must be > 0" },
    { header + "axon 1 axon 0 1 2 3 0.9 0.8\n",
      "voxel.csv line 2: inner_radius 0.9 exceeds outer_radius 0.8" },
    { header + "axon 1.5 axon 0 1 2 3 0.5 0.8\n", "voxel.csv line 2: '1.5' is not an integer id" },
    { header +
        "axon 1 axon 0 1 2 3 1 1\naxon 1 axon 0 1 2 4 1 1\naxon 2 axon 0 0 0 0 1 1\n"
        "axon 1 axon 0 1 2 9 1 1\n",
      "voxel.csv line 5: axon 1 starts a second sphere chain" },
    { "", "voxel.csv line 1: no CATERPillar header" },
  };
  for (const Case& c : cases)
  {
    std::istringstream in(c.text);
    const FiberReadResult r = readCaterpillarCsv(in, "voxel.csv");
    EXPECT_EQ(r.error.rfind(c.expected, 0), 0u) << r.error;
    EXPECT_TRUE(r.model.empty());
  }
}

TEST(CaterpillarFormat, OrdinaryCsvIsNotClaimed)
{
  std::istringstream plain("a,b,c\n1,2,3\n");
  EXPECT_FALSE(looksLikeCaterpillarCsv(plain));
  std::istringstream mine(std::string("\n") + kCaterpillarHeader + "\n");
  EXPECT_TRUE(looksLikeCaterpillarCsv(mine));
}

TEST(CactusFormat, RoundTripPointByPoint)
{
  const FiberModel m = curvedModel();
  std::stringstream file;
  ASSERT_EQ(writeCactusStrands(file, m, 40.0), "");
  EXPECT_TRUE(looksLikeCactusStrands(file));
  const std::string text = file.str();
  const CactusReadResult back = readCactusStrands(file, "s.txt", text.size());
  ASSERT_TRUE(back.ok()) << back.error;
  EXPECT_EQ(back.boxSize, 40.0);
  ASSERT_EQ(back.model.fibers.size(), m.fibers.size());
  for (std::size_t f = 0; f < m.fibers.size(); ++f)
  {
    const Fiber& a = m.fibers[f];
    const Fiber& b = back.model.fibers[f];
    EXPECT_EQ(b.id, static_cast<std::int64_t>(f));
    ASSERT_EQ(b.size(), a.size());
    for (std::size_t i = 0; i < a.size(); ++i)
    {
      EXPECT_EQ(b.points[i].x, a.points[i].x);
      EXPECT_EQ(b.points[i].y, a.points[i].y);
      EXPECT_EQ(b.points[i].z, a.points[i].z);
      EXPECT_EQ(b.radii[i], a.radii[i]);
    }
  }
}

TEST(CactusFormat, MalformedFilesNameTheLineWithoutReadingPastTheFile)
{
  struct Case
  {
    std::string text;
    std::string expected;
  };
  const Case cases[] = {
    { "40\n10000000000\n2\n0 0 0 1\n0 0 1 1\n",
      "s.txt line 2: strand count 10000000000 needs at least" },
    { "40\n1\n10000000000\n0 0 0 1\n", "s.txt line 3: point count 10000000000 of strand 0 needs" },
    { "40\n2\n2\n0 0 0 1\n0 0 1 1\n",
      "s.txt line 6: strand 1 of 2: file ends where a point count is expected" },
    { "40\n1\n3\n0.000 0 0 1\n0.000 0 1 1\n",
      "s.txt line 6: file ends after 2 of the 3 points of strand 0" },
    { "40\n1\n2\n0 0 0 1\n0 0 1 1\n2\n0 0 0 1\n0 0 1 1\n",
      "s.txt line 6: content after the last of the 1 strands" },
    { "40\n1\n2\n0 0 0 1\n0 nan 1 1\n", "s.txt line 5: 'nan' is not a finite number" },
    { "40\n1\n2\n0 0 0 1\n0 0 1 -1\n", "s.txt line 5: radius -1 must be > 0" },
    { "40\n1\n2\n0 0 0 1.000\n0 0 1.000\n", "s.txt line 5: expected 4 numbers" },
    { "40\n-1\n", "s.txt line 2: strand '-1' is not a non-negative integer count" },
    { "", "s.txt line 1: file ends where the box size is expected" },
  };
  for (const Case& c : cases)
  {
    std::istringstream in(c.text);
    const CactusReadResult r = readCactusStrands(in, "s.txt", c.text.size());
    EXPECT_EQ(r.error.rfind(c.expected, 0), 0u) << c.expected << " | got: " << r.error;
    EXPECT_TRUE(r.model.empty());
  }
}

TEST(McdcCylinders, StraightFibersBecomeCylindersAndBentOnesAreRefusedByName)
{
  FiberModel m;
  Fiber a;
  a.id = 5;
  a.points = { { 1, 2, 0 }, { 1, 2, 5 }, { 1, 2, 10 } };
  a.radii = { 0.5, 0.7, 0.6 };
  m.fibers.push_back(a);
  std::ostringstream z;
  ASSERT_EQ(writeMcdcCylinders(z, m, McdcCylinderList::ZAligned), "");
  EXPECT_EQ(z.str(), "0.001\n1 2 0 0.7\n");

  Fiber tilted;
  tilted.id = 6;
  tilted.points = { { 0, 0, 0 }, { 1, 1, 1 }, { 2, 2, 2 } };
  tilted.radii = { 1, 1, 1 };
  m.fibers.push_back(tilted);
  std::ostringstream o;
  ASSERT_EQ(writeMcdcCylinders(o, m, McdcCylinderList::Oriented), "");
  EXPECT_EQ(o.str(), "0.001\n1 2 0 1 2 10 0.7\n0 0 0 2 2 2 1\n");
  // A tilted fiber is no z-parallel cylinder: its end is sqrt(8) from the z-line.
  std::ostringstream refused;
  const std::string error = writeMcdcCylinders(refused, m, McdcCylinderList::ZAligned);
  EXPECT_NE(error.find("fiber 1 (id 6) deviates 2.82843"), std::string::npos) << error;

  // A bent fiber: its middle point lies 0.3 off the chord; the worst of two bent ones is named.
  m.fibers[1].points[1] = { 1.0 + 0.3 / std::sqrt(2.0), 1.0 - 0.3 / std::sqrt(2.0), 1.0 };
  Fiber slightly = a;
  slightly.id = 7;
  slightly.points[1].x += 0.1;
  m.fibers.push_back(slightly);
  const std::string bent = writeMcdcCylinders(refused, m, McdcCylinderList::Oriented, 0.05);
  EXPECT_NE(bent.find("fiber 1 (id 6) deviates 0.3 µm"), std::string::npos) << bent;
  EXPECT_EQ(writeMcdcCylinders(refused, m, McdcCylinderList::Oriented, 0.31), "");
}
