// CATERPillar .csv and CACTUS .txt through the path-level entry points (writeFiberFile,
// readFiberFile): myelinated axons keep their inner radii in Fiber::innerRadii both ways, and a
// strand list keeps its box size.
#include "IO/FiberFile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <string>

#include <unistd.h>

using namespace fiberpli;

namespace
{

struct ScratchDir
{
  std::string path;
  ScratchDir()
  {
    char tmpl[] = "/tmp/fiberpli-substrate-XXXXXX";
    const char* made = ::mkdtemp(tmpl);
    path = made != nullptr ? made : "";
  }
  ~ScratchDir()
  {
    if (!path.empty())
    {
      std::system(("rm -rf '" + path + "'").c_str());
    }
  }
};

/// Two undulating myelinated axons (g-ratios 0.6 and 0.75) and one unmyelinated fiber.
FiberModel myelinatedModel(bool withSheaths)
{
  FiberModel m;
  for (int f = 0; f < 3; ++f)
  {
    Fiber fiber;
    fiber.id = 3 + 2 * f;
    fiber.bundle = f;
    for (int i = 0; i < 5; ++i)
    {
      fiber.points.push_back(
        { 4.0 * f + 0.3 * std::sin(0.9 * i), 0.2 * std::cos(0.7 * i + f), 2.3 * i });
      fiber.radii.push_back(0.9 + 0.04 * i);
      if (withSheaths && f < 2)
      {
        fiber.innerRadii.push_back((f == 0 ? 0.6 : 0.75) * fiber.radii.back());
      }
    }
    m.fibers.push_back(fiber);
  }
  return m;
}

std::string firstLine(const std::string& path)
{
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  return line;
}

} // namespace

TEST(SubstrateFiles, CaterpillarInnerRadiiTravelWithTheFibers)
{
  ScratchDir dir;
  ASSERT_FALSE(dir.path.empty());
  const std::string path = dir.path + "/voxel.csv";
  const FiberModel m = myelinatedModel(true);
  ASSERT_EQ(writeFiberFile(path, m), "");
  const FiberReadResult back = readFiberFile(path, 1.0);
  ASSERT_TRUE(back.ok()) << back.error;
  ASSERT_EQ(back.model.fibers.size(), m.fibers.size());
  for (std::size_t f = 0; f < m.fibers.size(); ++f)
  {
    const Fiber& a = m.fibers[f];
    const Fiber& b = back.model.fibers[f];
    ASSERT_EQ(b.innerRadii.size(), b.size()) << "fiber " << f;
    // Every original point comes back bit for bit with its outer and inner radius; the spheres
    // between carry inner radii strictly inside their outer radii where the fiber is myelinated.
    std::size_t j = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
      while (j < b.size() &&
        !(b.points[j].x == a.points[i].x && b.points[j].y == a.points[i].y &&
          b.points[j].z == a.points[i].z))
      {
        ++j;
      }
      ASSERT_LT(j, b.size()) << "fiber " << f << " lost point " << i;
      EXPECT_EQ(b.radii[j], a.radii[i]);
      EXPECT_EQ(b.innerRadii[j], a.innerRadii.empty() ? a.radii[i] : a.innerRadii[i]);
    }
    for (std::size_t k = 0; k < b.size(); ++k)
    {
      if (a.innerRadii.empty())
      {
        EXPECT_EQ(b.innerRadii[k], b.radii[k]); // no sheath: inner = outer, as CATERPillar writes
      }
      else
      {
        EXPECT_LT(b.innerRadii[k], b.radii[k]);
      }
    }
  }
}

TEST(SubstrateFiles, CaterpillarWithoutMyelinGivesNoInnerRadii)
{
  ScratchDir dir;
  ASSERT_FALSE(dir.path.empty());
  const std::string path = dir.path + "/plain.csv";
  ASSERT_EQ(writeFiberFile(path, myelinatedModel(false)), "");
  const FiberReadResult back = readFiberFile(path, 1.0);
  ASSERT_TRUE(back.ok()) << back.error;
  for (const Fiber& f : back.model.fibers)
  {
    EXPECT_TRUE(f.innerRadii.empty());
  }
}

TEST(SubstrateFiles, CaterpillarRefusesInnerRadiiAboveTheRadiusNamingTheFiber)
{
  ScratchDir dir;
  ASSERT_FALSE(dir.path.empty());
  FiberModel m = myelinatedModel(true);
  m.fibers[1].innerRadii[2] = 2.0 * m.fibers[1].radii[2];
  const std::string error = writeFiberFile(dir.path + "/bad.csv", m);
  EXPECT_NE(error.find("inner_radius of fiber 1 (fiber_id 5) point 2"), std::string::npos) << error;
}

TEST(SubstrateFiles, CactusKeepsItsBoxSize)
{
  ScratchDir dir;
  ASSERT_FALSE(dir.path.empty());
  const FiberModel m = myelinatedModel(false);
  const std::string path = dir.path + "/strands.txt";

  FiberFileExtras box;
  box.boxSize = 37.25;
  ASSERT_EQ(writeFiberFile(path, m, &box), "");
  EXPECT_EQ(firstLine(path), "37.25");
  const FiberReadResult back = readFiberFile(path, 1.0);
  ASSERT_TRUE(back.ok()) << back.error;
  EXPECT_EQ(back.boxSize, 37.25);

  // Written again from what was read: the same file, byte for byte.
  FiberFileExtras again;
  again.boxSize = back.boxSize;
  const std::string second = dir.path + "/again.txt";
  ASSERT_EQ(writeFiberFile(second, back.model, &again), "");
  std::ifstream a(path), b(second);
  const std::string textA((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>());
  const std::string textB((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
  EXPECT_EQ(textA, textB);

  // A periodic cell is the box: its largest edge wins over a box size.
  FiberFileExtras cell = box;
  cell.cell.lo = { -5, -6, 0 };
  cell.cell.hi = { 5, 14, 12 };
  ASSERT_EQ(writeFiberFile(path, m, &cell), "");
  EXPECT_EQ(firstLine(path), "20");

  // Neither: -1, what CACTUS writes without a box, and read back as none.
  ASSERT_EQ(writeFiberFile(path, m), "");
  EXPECT_EQ(firstLine(path), "-1");
  EXPECT_EQ(readFiberFile(path, 1.0).boxSize, -1.0);
}
