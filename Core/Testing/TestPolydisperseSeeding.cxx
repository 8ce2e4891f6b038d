// Lattice seeding with polydisperse radii (CubeGenerator + Tissue/DiskPacking,
// docs/periodic-cells.md "Polydisperse seeding"): the seeded cross-section checked by brute force
// over the periodic images, the radii and draws kept, the same model for any piece count, constant
// radii on today's lattice, and a dense Gamma cell solved to zero overlaps (independent counter of
// PeriodicReference.h).
#include "PeriodicReference.h"
#include "Solver/CollisionSolver.h"
#include "Tissue/CubeGenerator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

using namespace fiberpli;

namespace
{
// Gamma radii, mean 1 µm, spread 0.5 (MEDUSA's α 4, β 0.25 µm), seeded on the lattice.
CubeOptions gammaCube(int populations, double edge, double phi, std::uint64_t seed)
{
  CubeOptions o = fiberpli_test::periodicCube(populations, edge, phi, seed);
  o.seeding = CubeSeeding::Lattice;
  o.fiberRadius = 1.0;
  o.radiusSpread = 0.5;
  o.radiusDistribution = RadiusDistribution::Gamma;
  return o;
}

double wrap(double d, double L)
{
  return std::fabs(d - L * std::round(d / L));
}

// Smallest surface gap between two straight fibers of the model over all images: parallel fibers
// by the minimum image of their axes in the cross-section, perpendicular ones by the one
// coordinate they share (every x-fiber crosses every y-fiber of a periodic cell).
double smallestStraightGap(const FiberModel& m, double L)
{
  double gap = HUGE_VAL;
  for (std::size_t a = 0; a < m.fibers.size(); ++a)
  {
    const Fiber& fa = m.fibers[a];
    for (std::size_t b = a + 1; b < m.fibers.size(); ++b)
    {
      const Fiber& fb = m.fibers[b];
      const Vec3& p = fa.points.front();
      const Vec3& q = fb.points.front();
      const int ka = fa.bundle, kb = fb.bundle;
      double distance = 0.0;
      if (ka == kb)
        distance = std::hypot(
          wrap(p[(ka + 1) % 3] - q[(ka + 1) % 3], L), wrap(p[(ka + 2) % 3] - q[(ka + 2) % 3], L));
      else
      {
        const int shared = 3 - ka - kb;
        distance = wrap(p[shared] - q[shared], L);
      }
      gap = std::min(gap, distance - fa.radii.front() - fb.radii.front());
    }
  }
  return gap;
}
} // namespace

TEST(PolydisperseSeeding, StraightFibersOfTheSeededCellDoNotOverlapAndKeepTheirRadii)
{
  // 0.85 / 0.72 straight: the lattice spaced for the mean cross-section overlaps there.
  for (const int pops : { 1, 2 })
  {
    CubeOptions o = gammaCube(pops, 16.0, pops == 1 ? 0.85 : 0.72, 5);
    o.displacement = 0.0;
    const FiberModel seeded = generateCube(o);
    EXPECT_GT(smallestStraightGap(seeded, o.edgeLength), 0.0) << pops << " populations";
    // Same fibers as with random seeds, moved across only: radius, population, along-axis points.
    CubeOptions random = o;
    random.seeding = CubeSeeding::Random;
    const FiberModel drawn = generateCube(random);
    ASSERT_EQ(seeded.fibers.size(), drawn.fibers.size());
    for (std::size_t f = 0; f < seeded.fibers.size(); ++f)
    {
      EXPECT_EQ(seeded.fibers[f].radii, drawn.fibers[f].radii) << f;
      EXPECT_EQ(seeded.fibers[f].bundle, drawn.fibers[f].bundle) << f;
      const int axis = seeded.fibers[f].bundle;
      for (std::size_t i = 0; i < seeded.fibers[f].points.size(); ++i)
        EXPECT_EQ(seeded.fibers[f].points[i][axis], drawn.fibers[f].points[i][axis]);
    }
    // The lattice of the same fiber counts (today's seeding of constant radii), for contrast,
    // does not fit these radii.
    CubeOptions constant = o;
    constant.radiusDistribution = RadiusDistribution::Constant;
    constant.volumeFraction = 0.0;
    constant.numberOfFibers = static_cast<int>(drawn.fibers.size());
    const FiberModel lattice = generateCube(constant);
    ASSERT_EQ(lattice.fibers.size(), drawn.fibers.size());
    FiberModel onLattice = drawn;
    for (std::size_t f = 0; f < onLattice.fibers.size(); ++f)
    {
      ASSERT_EQ(lattice.fibers[f].bundle, drawn.fibers[f].bundle);
      onLattice.fibers[f].points = lattice.fibers[f].points;
    }
    EXPECT_LT(smallestStraightGap(onLattice, o.edgeLength), 0.0) << pops << " populations";
  }
}

TEST(PolydisperseSeeding, SameModelForAnyPieceCount)
{
  const CubeOptions o = gammaCube(2, 14.0, 0.7, 8);
  const FiberModel whole = generateCube(o);
  for (const int pieces : { 2, 3 })
  {
    std::vector<Fiber> joined;
    for (int piece = 0; piece < pieces; ++piece)
      for (const Fiber& f : generateCube(o, piece, pieces).fibers)
        joined.push_back(f);
    ASSERT_EQ(joined.size(), whole.fibers.size()) << pieces;
    for (std::size_t f = 0; f < joined.size(); ++f)
    {
      EXPECT_EQ(joined[f].id, whole.fibers[f].id);
      EXPECT_TRUE(joined[f].points == whole.fibers[f].points) << pieces << " pieces, fiber " << f;
    }
  }
}

TEST(PolydisperseSeeding, ConstantRadiiKeepTheLattice)
{
  // A spread with the Constant distribution draws nothing: today's lattice model, bit for bit.
  for (const int pops : { 1, 2 })
  {
    CubeOptions spread = gammaCube(pops, 14.0, 0.7, 2);
    spread.radiusDistribution = RadiusDistribution::Constant;
    CubeOptions none = spread;
    none.radiusSpread = 0.0;
    const FiberModel a = generateCube(spread), b = generateCube(none);
    ASSERT_EQ(a.fibers.size(), b.fibers.size());
    for (std::size_t f = 0; f < a.fibers.size(); ++f)
      EXPECT_TRUE(a.fibers[f].points == b.fibers[f].points) << f;
  }
}

TEST(PolydisperseSeeding, DenseGammaCellsSolveToZeroOverlaps)
{
  // One population at 0.85 in a (20 µm)³ cell and two at 0.72 in (16 µm)³ with Gamma radii; on
  // the lattice of the mean cross-section the (30 µm)³ cells of bench/README.md ("Polydisperse
  // seeding") still had 7 625 (one population) and 2 331 (two) overlapping pairs after 3 000 steps.
  // The step cap is 0.4 × the smallest radius (0.25 µm here): the default 0.125 moves a point 0.03
  // µm per step, too little to iron out the displacements of a cell at 0.85.
  struct Case
  {
    int pops;
    double edge, phi;
    std::uint64_t seed;
  };
  for (const Case c : { Case{ 1, 20.0, 0.85, 11 }, Case{ 2, 16.0, 0.72, 42 } })
  {
    CubeOptions cube = gammaCube(c.pops, c.edge, c.phi, c.seed);
    cube.displacement = 0.5; // the bench's cells
    std::string warning = "unset";
    FiberModel m = generateCube(cube, 0, 1, &warning);
    EXPECT_EQ(warning, "") << "the packing separates the disks";
    CollisionSolverOptions o;
    o.periodicCell = cubeCell(cube);
    o.minCurvatureRadius = 4.0;
    o.maxDisplacement = 0.4;
    o.maxSteps = 3000;
    const CollisionSolverResult r = solveCollisions(m, o);
    ASSERT_EQ(r.error, "");
    EXPECT_TRUE(r.solved) << c.pops << " populations: " << r.collisions << " left";
    EXPECT_EQ(fiberpli_test::refPeriodicCount(m, c.edge), 0u) << c.pops;
    const double mc = fiberpli_test::monteCarloFraction(m, c.edge, 10000);
    EXPECT_GE(mc + 4.0 * std::sqrt(mc * (1 - mc) / 10000), c.phi) << c.pops << " populations";
  }
}

TEST(PolydisperseSeeding, InfeasibleTargetKeepsEveryFiberWithItsRadius)
{
  // 0.93 is beyond what the packing reaches for these disks: the arrangement with the largest
  // scale is used, nothing is dropped or shrunk, the straight fibers overlap and the generator
  // says so (the solver then reports how far it got,
  // PeriodicSolver.InfeasibleTargetStopsBoundedWithAWarning).
  CubeOptions o = gammaCube(1, 14.0, 0.93, 3);
  o.displacement = 0.0;
  std::string warning;
  const FiberModel seeded = generateCube(o, 0, 1, &warning);
  EXPECT_NE(warning.find("Seeding Lattice: the radii could not be separated in the cross-section"),
    std::string::npos)
    << warning;
  EXPECT_NE(warning.find("VolumeFraction 0.93"), std::string::npos) << warning;
  CubeOptions random = o;
  random.seeding = CubeSeeding::Random;
  const FiberModel drawn = generateCube(random);
  ASSERT_EQ(seeded.fibers.size(), drawn.fibers.size());
  double area = 0.0;
  for (std::size_t f = 0; f < seeded.fibers.size(); ++f)
  {
    EXPECT_EQ(seeded.fibers[f].radii, drawn.fibers[f].radii) << f;
    area += M_PI * seeded.fibers[f].radii.front() * seeded.fibers[f].radii.front();
  }
  EXPECT_GE(area, 0.93 * 14.0 * 14.0);
  EXPECT_LT(smallestStraightGap(seeded, o.edgeLength), 0.0);
}

TEST(PolydisperseSeeding, TwoPopulationSlabThinnerThanAFiberWarns)
{
  // A (4 µm)³ cell with two Gamma populations: the slabs are about 2 µm thick, thinner than the
  // diameter of any fiber of radius > 1 µm, so such a fiber cannot lie in its slab.
  const CubeOptions o = gammaCube(2, 4.0, 0.5, 5);
  std::string warning;
  const FiberModel m = generateCube(o, 0, 1, &warning);
  double area[2] = { 0.0, 0.0 }, widest[2] = { 0.0, 0.0 };
  for (const Fiber& f : m.fibers)
  {
    const double r = f.radii.front();
    area[f.bundle] += r * r;
    widest[f.bundle] = std::max(widest[f.bundle], 2.0 * r);
  }
  const double h0 = 4.0 * area[0] / (area[0] + area[1]);
  ASSERT_TRUE(widest[0] > h0 || widest[1] > 4.0 - h0) << "the case this test is about";
  EXPECT_NE(warning.find("thinner than its largest fiber's diameter"), std::string::npos)
    << warning;
  EXPECT_NE(warning.find("EdgeLength 4"), std::string::npos) << warning;
}

TEST(PolydisperseSeeding, ThePackingsMemoryIsCheckedOnEveryPiece)
{
  // 10⁶ fibers of 4 points in 8 pieces: a piece's share of the model fits 200 MB, the packing of
  // all 10⁶ disks, which every piece computes, does not (diskPackingBytes).
  CubeOptions o = gammaCube(1, 2000.0, 0.0, 1);
  o.volumeFraction = 0.0;
  o.numberOfFibers = 1000000;
  o.segmentLength =
    700.0; // 4 points per fiber (3 would span half the cell: the solver refuses that)
  setenv("FIBERPLI_MEMORY_LIMIT", "200M", 1);
  const std::string e = validateCubeOptions(o, 8);
  o.seeding = CubeSeeding::Random;
  const std::string random = validateCubeOptions(o, 8);
  unsetenv("FIBERPLI_MEMORY_LIMIT");
  EXPECT_NE(e.find("Seeding Lattice with RadiusSpread 0.5"), std::string::npos) << e;
  EXPECT_NE(e.find("NumberOfFibers 1000000 with EdgeLength 2000"), std::string::npos) << e;
  EXPECT_NE(e.find("memory budget"), std::string::npos) << e;
  EXPECT_EQ(random, "") << "the model alone fits";
}

TEST(PolydisperseSeeding, AStopDuringThePackingGivesAnEmptyModel)
{
  for (const int pops : { 1, 2 })
  {
    const CubeOptions o = gammaCube(pops, 14.0, 0.7, 8);
    int calls = 0;
    const FiberModel m = generateCube(o, 0, 1, nullptr, [&](double) { return ++calls < 2; });
    EXPECT_EQ(calls, 2) << pops;
    EXPECT_TRUE(m.fibers.empty()) << pops;
    const FiberModel full = generateCube(o, 0, 1, nullptr, [](double) { return true; });
    EXPECT_FALSE(full.fibers.empty()) << pops;
    const FiberModel plain = generateCube(o);
    ASSERT_EQ(full.fibers.size(), plain.fibers.size()) << pops;
    for (std::size_t f = 0; f < full.fibers.size(); ++f)
      EXPECT_TRUE(full.fibers[f].points == plain.fibers[f].points) << pops << " " << f;
  }
}
