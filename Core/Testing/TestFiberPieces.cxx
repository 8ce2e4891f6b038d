// Pieces of the generated models (docs/tissue-models.md §9): the pieces of FiberCubeSource and
// FiberBundleSource, put one after the other, are exactly the whole model (same fibers, ids,
// points bit for bit, same order) for any piece count, and each piece holds only its own range.
#include "MemoryLimitGuard.h"
#include "Model/FiberPieces.h"
#include "Tissue/BundleGenerator.h"
#include "Tissue/CubeGenerator.h"

#include <gtest/gtest.h>

#include <cstring>
#include <functional>
#include <string>

using namespace fiberpli;

namespace
{
bool sameFiber(const Fiber& a, const Fiber& b)
{
  return a.id == b.id && a.bundle == b.bundle && a.points.size() == b.points.size() &&
    a.radii.size() == b.radii.size() &&
    std::memcmp(a.points.data(), b.points.data(), a.points.size() * sizeof(Vec3)) == 0 &&
    std::memcmp(a.radii.data(), b.radii.data(), a.radii.size() * sizeof(double)) == 0;
}

// generate(piece, pieces) for 1..5 pieces against generate(0, 1).
void expectPiecesMakeTheWhole(
  const std::function<FiberModel(int, int)>& generate, const std::string& what)
{
  const FiberModel whole = generate(0, 1);
  ASSERT_GE(whole.fibers.size(), 5u) << what << ": too few fibers to split";
  for (int pieces = 1; pieces <= 5; ++pieces)
  {
    std::size_t next = 0;
    for (int piece = 0; piece < pieces; ++piece)
    {
      const FiberModel part = generate(piece, pieces);
      const FiberRange range = pieceRange(whole.fibers.size(), piece, pieces);
      ASSERT_EQ(part.fibers.size(), range.size()) << what << " piece " << piece << " of " << pieces;
      ASSERT_EQ(range.begin, next) << what;
      for (const Fiber& f : part.fibers)
      {
        ASSERT_TRUE(sameFiber(f, whole.fibers[next]))
          << what << ": fiber " << next << " of piece " << piece << " of " << pieces
          << " differs from the whole model";
        ++next;
      }
    }
    EXPECT_EQ(next, whole.fibers.size()) << what << ", " << pieces << " pieces";
  }
}
} // namespace

TEST(FiberPieces, RangesAreContiguousAndBalanced)
{
  for (std::size_t total : { 0u, 1u, 7u, 1000u })
  {
    for (int pieces = 1; pieces <= 9; ++pieces)
    {
      std::size_t next = 0;
      for (int p = 0; p < pieces; ++p)
      {
        const FiberRange r = pieceRange(total, p, pieces);
        EXPECT_EQ(r.begin, next);
        EXPECT_LE(r.size(), total / pieces + 1);
        EXPECT_GE(r.size(), total / pieces);
        next = r.end;
      }
      EXPECT_EQ(next, total);
    }
  }
  EXPECT_EQ(pieceRange(10, 3, 3).size(), 0u); // outside [0, pieces)
  EXPECT_EQ(pieceRange(10, -1, 3).size(), 0u);
  EXPECT_EQ(pieceRange(10, 0, 0).size(), 10u); // pieces < 1 counts as 1
}

TEST(FiberPieces, OpenCube)
{
  CubeOptions o;
  o.populations = 2;
  o.numberOfFibers = 23;
  o.seed = 7;
  ASSERT_EQ(validateCubeOptions(o), "");
  expectPiecesMakeTheWhole([&](int p, int n) { return generateCube(o, p, n); }, "open cube");
}

TEST(FiberPieces, PeriodicCubes)
{
  CubeOptions o;
  o.populations = 3;
  o.numberOfFibers = 31;
  o.edgeLength = 30.0;
  o.periodic = true;
  o.seed = 11;
  expectPiecesMakeTheWhole([&](int p, int n) { return generateCube(o, p, n); }, "periodic cube");
  // The count comes from the radii of all fibers: every piece must count the same.
  o.volumeFraction = 0.3;
  o.radiusSpread = 0.3;
  o.radiusDistribution = RadiusDistribution::LogNormal;
  ASSERT_EQ(validateCubeOptions(o), "");
  expectPiecesMakeTheWhole(
    [&](int p, int n) { return generateCube(o, p, n); }, "periodic cube, volume fraction");
  // Lattice sites are shuffled over all fibers of a population: a piece takes the same sites.
  o.radiusSpread = 0.0;
  o.populations = 2;
  o.volumeFraction = 0.4;
  o.seeding = CubeSeeding::Lattice;
  ASSERT_EQ(validateCubeOptions(o), "");
  expectPiecesMakeTheWhole(
    [&](int p, int n) { return generateCube(o, p, n); }, "periodic cube, lattice");
}

TEST(FiberPieces, MorePiecesThanFibers)
{
  CubeOptions o;
  o.numberOfFibers = 3;
  std::size_t fibers = 0;
  for (int p = 0; p < 8; ++p)
  {
    const FiberModel part = generateCube(o, p, 8);
    EXPECT_LE(part.fibers.size(), 1u);
    fibers += part.fibers.size();
  }
  EXPECT_EQ(fibers, 3u);
}

TEST(FiberPieces, Bundles)
{
  std::vector<Vec3> curve;
  for (int i = -10; i <= 10; ++i)
  {
    curve.push_back({ 3.0 * i, 0.05 * i * i, 0.0 });
  }
  for (BundleShape shape : { BundleShape::Cylinder, BundleShape::Trajectory, BundleShape::Crossing,
         BundleShape::YShape, BundleShape::Chiasm })
  {
    BundleOptions o;
    o.shape = shape;
    o.seed = 5;
    o.radiusSpread = 0.2;
    const std::vector<Vec3>* path = shape == BundleShape::Trajectory ? &curve : nullptr;
    ASSERT_EQ(validateBundleOptions(o, path), "");
    expectPiecesMakeTheWhole([&](int p, int n) { return generateBundle(o, path, nullptr, p, n); },
      std::string("bundle ") + bundleShapeName(shape));
  }
  BundleOptions random;
  random.numberOfFibers = 40;
  random.shape = BundleShape::Chiasm;
  expectPiecesMakeTheWhole([&](int p, int n)
    { return generateBundle(random, nullptr, nullptr, p, n); },
    "random-seeded chiasm");
}

TEST(FiberPieces, MemoryGuardChecksOnePiece)
{
  // 100 000 fibers of 501 points: about 3.2 GB with the converted copy. Under a 1 GB budget the
  // whole cube is refused, a quarter fits, a half is refused naming the share.
  const fiberpli::testing::MemoryLimitGuard limit("1G");
  CubeOptions o;
  o.numberOfFibers = 100000;
  o.edgeLength = 1000.0;
  EXPECT_NE(validateCubeOptions(o), "");
  EXPECT_EQ(validateCubeOptions(o, 4), "");
  EXPECT_NE(validateCubeOptions(o, 2).find("a share of 1/2 per piece"), std::string::npos)
    << validateCubeOptions(o, 2);
}
