// Periodic cells: the periodic cube generator, minimum-image detection and the solver in a cell.
// The references here (overlap count over all 27 images, volume fraction by Monte Carlo over
// the cell) share no code with the solver: distances come from BruteForceOverlap.h.
#include "BruteForceOverlap.h"
#include "Model/PeriodicCellRule.h"
#include "Model/PeriodicTiling.h"
#include "PeriodicReference.h"
#include "Solver/CollisionSolver.h"
#include "Solver/Decomposition.h"
#include "SolverTestModels.h"
#include "ThreadComm.h"
#include "Tissue/CubeGenerator.h"
#include "Util/Random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace fiberpli;
using fiberpli_test::monteCarloFraction;
using fiberpli_test::periodicCube;
using fiberpli_test::refPeriodicCount;
using fiberpli_test::runRanks;

namespace
{
void expectClosed(const FiberModel& m, double L)
{
  for (const Fiber& f : m.fibers)
  {
    Vec3 shift;
    shift[f.bundle] = L;
    ASSERT_EQ(f.points.back(), f.points.front() + shift) << "fiber " << f.id;
  }
}
} // namespace

TEST(PeriodicCube, FibersSpanOnePeriodAndAreClosed)
{
  for (int pops = 1; pops <= 3; ++pops)
  {
    const CubeOptions o = periodicCube(pops, 16.0, 0.4);
    ASSERT_EQ(validateCubeOptions(o), "");
    const FiberModel m = generateCube(o);
    ASSERT_FALSE(m.fibers.empty());
    expectClosed(m, o.edgeLength);
    for (const Fiber& f : m.fibers)
    {
      ASSERT_EQ(f.size(), 9u); // round(16 / 2) + 1
      // Undisplaced axis coordinates run from -L/2 in steps of L/8; displacement bounds the rest.
      for (std::size_t i = 0; i + 1 < f.size(); ++i)
        EXPECT_NEAR(f.points[i][f.bundle], -8.0 + 2.0 * double(i), o.displacement + 1e-12);
      for (double r : f.radii)
        EXPECT_EQ(r, 0.8);
    }
  }
}

TEST(PeriodicCube, FiberCountMatchesTheVolumeFraction)
{
  for (int pops = 1; pops <= 3; ++pops)
  {
    const CubeOptions o = periodicCube(pops, 20.0, 0.6);
    const FiberModel m = generateCube(o);
    // The smallest N with N π r² L ≥ φ L³: N = ⌈φ L² / (π r²)⌉ = ⌈119.37⌉.
    EXPECT_EQ(m.fibers.size(), 120u);
    int count[3] = { 0, 0, 0 };
    for (const Fiber& f : m.fibers)
      ++count[f.bundle];
    for (int k = 1; k < pops; ++k)
      EXPECT_LE(std::abs(count[k] - count[0]), 1); // populations filled in turn
  }
  // A target that a count meets exactly gets that count, not one more.
  EXPECT_EQ(generateCube(periodicCube(2, 20.0, 100 * M_PI * 0.64 / 400.0)).fibers.size(), 100u);
}

TEST(PeriodicCube, PolydisperseCountIsTheSmallestReachingTheFraction)
{
  for (int pops = 1; pops <= 3; ++pops)
  {
    CubeOptions o = periodicCube(pops, 20.0, 0.5, 7);
    o.radiusDistribution = RadiusDistribution::Gamma;
    o.radiusSpread = 0.5;
    const FiberModel m = generateCube(o);
    const double cell = 20.0 * 20.0 * 20.0;
    double volume = 0.0;
    for (const Fiber& f : m.fibers)
      volume += M_PI * f.radii[0] * f.radii[0] * 20.0;
    EXPECT_GE(volume, 0.5 * cell) << pops;
    // Without the fiber added last (fibers are added to populations 0, 1, 2, 0, …, so it is the
    // last fiber of population (N − 1) mod pops) the target is not reached.
    const std::size_t n = m.fibers.size();
    const int lastPopulation = static_cast<int>((n - 1) % static_cast<std::size_t>(pops));
    const Fiber* last = nullptr;
    for (const Fiber& f : m.fibers)
      if (f.bundle == lastPopulation)
        last = &f;
    ASSERT_NE(last, nullptr);
    EXPECT_LT(volume - M_PI * last->radii[0] * last->radii[0] * 20.0, 0.5 * cell) << pops;
  }
}

TEST(PeriodicCube, SeedsAreUniformOverTheCrossSection)
{
  CubeOptions o = periodicCube(1, 20.0, 0.0);
  o.numberOfFibers = 4000;
  o.displacement = 0.0;
  const FiberModel m = generateCube(o);
  // Quadrant counts of the (y, z) seeds: each 1000 ± 4σ (σ = √(4000·¼·¾) ≈ 27).
  int quadrant[4] = { 0, 0, 0, 0 };
  for (const Fiber& f : m.fibers)
  {
    ASSERT_GE(f.points[0].y, -10.0);
    ASSERT_LT(f.points[0].y, 10.0);
    ++quadrant[(f.points[0].y > 0 ? 1 : 0) + (f.points[0].z > 0 ? 2 : 0)];
  }
  for (int q : quadrant)
    EXPECT_NEAR(q, 1000, 110);
}

TEST(PeriodicCube, BadInputIsRejectedNamingTheProperty)
{
  CubeOptions o = periodicCube(1, 20.0, 0.5);
  o.volumeFraction = -0.1;
  EXPECT_NE(validateCubeOptions(o).find("VolumeFraction"), std::string::npos);
  o.volumeFraction = 1.0;
  EXPECT_NE(validateCubeOptions(o).find("VolumeFraction"), std::string::npos);
  o.volumeFraction = std::nan("");
  EXPECT_NE(validateCubeOptions(o).find("VolumeFraction"), std::string::npos);
  o.volumeFraction = 0.5;
  o.edgeLength = 3.1; // < two fiber diameters (3.2)
  EXPECT_NE(validateCubeOptions(o).find("EdgeLength"), std::string::npos);
  o.periodic = false; // an open cube only needs one diameter
  EXPECT_EQ(validateCubeOptions(o), "");
  o.periodic = true;
  o.edgeLength = 20.0;
  o.radiusSpread = 0.5;
  o.radiusDistribution = RadiusDistribution::Uniform;
  EXPECT_EQ(validateCubeOptions(o), "");
  o.radiusSpread = 1.0;
  EXPECT_NE(validateCubeOptions(o).find("RadiusSpread"), std::string::npos);
}

TEST(PeriodicCube, OpenCubeDrawsAreUnchanged)
{
  // Periodic off, constant radius: the draws of docs/tissue-models.md §6.1 (position, then the
  // displacements), so existing cubes keep their bytes.
  CubeOptions o;
  o.numberOfFibers = 3;
  o.edgeLength = 10.0;
  const FiberModel m = generateCube(o);
  RandomStream rng(o.seed, 0, 1);
  const double t1 = rng.uniform(-5.0, 5.0);
  const double t2 = rng.uniform(-5.0, 5.0);
  const double dx = rng.uniform(-0.5, 0.5);
  const double dy = rng.uniform(-0.5, 0.5);
  EXPECT_EQ(m.fibers[1].points[0].x, -5.0 + dx);
  EXPECT_EQ(m.fibers[1].points[0].y, t1 + dy);
  EXPECT_EQ(m.fibers[1].size(), 6u);
  (void)t2;
}

TEST(PeriodicDetection, MatchesTheBruteForceOverAllImages)
{
  for (int pops = 1; pops <= 3; ++pops)
  {
    // Unsolved: many overlaps, also across the faces.
    const CubeOptions o = periodicCube(pops, 14.0, 0.5, 10 + pops);
    const FiberModel m = generateCube(o);
    const std::size_t expected = refPeriodicCount(m, o.edgeLength);
    EXPECT_GT(expected, 20u);
    for (int threads : { 1, 2 })
      EXPECT_EQ(countCollisions(m, 0.0, threads, cubeCell(o)), expected) << pops << " populations";
  }
}

TEST(PeriodicDetection, LatticeTranslatesGiveTheSamePairs)
{
  const CubeOptions o = periodicCube(2, 14.0, 0.5, 5);
  const FiberModel m = generateCube(o);
  const std::size_t before = countCollisions(m, 0.0, 1, cubeCell(o));
  ASSERT_GT(before, 0u);
  for (const Vec3 t : { Vec3{ 14, 0, 0 }, Vec3{ 0, -14, 28 }, Vec3{ 14, 14, -14 } })
  {
    FiberModel moved = m;
    for (std::size_t f = 0; f < moved.fibers.size(); f += 3) // every third fiber
      for (Vec3& p : moved.fibers[f].points)
        p += t;
    EXPECT_EQ(countCollisions(moved, 0.0, 1, cubeCell(o)), before);
    // Without the cell the moved fibers would be far away.
    EXPECT_LT(countCollisions(moved, 0.0, 1), before);
  }
}

TEST(PeriodicSolver, SmallCellsSolveToZeroOverlapsKeepingClosureRadiiAndFraction)
{
  const double targets[3] = { 0.6, 0.45, 0.35 };
  for (int pops = 1; pops <= 3; ++pops)
  {
    const CubeOptions c = periodicCube(pops, 14.0, targets[pops - 1], 20 + pops);
    FiberModel m = generateCube(c);
    CollisionSolverOptions o;
    o.periodicCell = cubeCell(c);
    o.maxSteps = 6000;
    const CollisionSolverResult r = solveCollisions(m, o);
    ASSERT_EQ(r.error, "");
    EXPECT_TRUE(r.solved) << pops << " populations: " << r.collisions << " left";
    EXPECT_EQ(refPeriodicCount(m, c.edgeLength), 0u);
    expectClosed(m, c.edgeLength);
    for (const Fiber& f : m.fibers)
      for (double x : f.radii)
        EXPECT_EQ(x, 0.8);
    // generateCube adds fibers until their straight volume reaches the target, and the solver
    // only lengthens closed fibers (each at least one period L long): the fraction is at least
    // the target.
    EXPECT_GE(r.volumeFraction, targets[pops - 1]);
    const double mc = monteCarloFraction(m, c.edgeLength, 20000);
    EXPECT_NEAR(mc, r.volumeFraction, 4.0 * std::sqrt(mc * (1 - mc) / 20000) + 0.005);
    EXPECT_GE(r.minGap, 0.0);
  }
}

TEST(PeriodicSolver, BitIdenticalForAnyThreadCount)
{
  const CubeOptions c = periodicCube(2, 14.0, 0.45, 8);
  CollisionSolverOptions o;
  o.periodicCell = cubeCell(c);
  o.maxSteps = 60;
  o.minCurvatureRadius = 4.0;
  FiberModel reference = generateCube(c);
  o.numberOfThreads = 1;
  const CollisionSolverResult r1 = solveCollisions(reference, o);
  for (int t : { 2, 3 })
  {
    FiberModel m = generateCube(c);
    o.numberOfThreads = t;
    const CollisionSolverResult r = solveCollisions(m, o);
    EXPECT_EQ(r.steps, r1.steps);
    EXPECT_EQ(r.collisions, r1.collisions);
    ASSERT_EQ(m.fibers.size(), reference.fibers.size());
    for (std::size_t f = 0; f < m.fibers.size(); ++f)
      EXPECT_TRUE(m.fibers[f].points == reference.fibers[f].points) << t << " threads, fiber " << f;
  }
}

TEST(PeriodicSolver, InfeasibleTargetStopsBoundedWithAWarning)
{
  // 95 % of one population is above the hexagonal limit of straight fibers (90.7 %).
  const CubeOptions c = periodicCube(1, 10.0, 0.95, 4);
  FiberModel m = generateCube(c);
  CollisionSolverOptions o;
  o.periodicCell = cubeCell(c);
  o.maxSteps = 50;
  const CollisionSolverResult r = solveCollisions(m, o);
  ASSERT_EQ(r.error, "");
  EXPECT_FALSE(r.solved);
  EXPECT_EQ(r.steps, 50);
  EXPECT_GT(r.collisions, 0u);
  ASSERT_FALSE(r.warnings.empty());
  EXPECT_NE(r.warnings.back().find("still overlap"), std::string::npos) << r.warnings.back();
  EXPECT_NE(r.warnings.back().find("overlap-free at"), std::string::npos) << r.warnings.back();
  expectClosed(m, c.edgeLength);
}

TEST(PeriodicSolver, RadiusGrowthEndsAtFullRadiiOrSaysHowFarItGot)
{
  // Feasible: growth from 70 % ends at full size without overlaps, radii untouched.
  const CubeOptions c = periodicCube(1, 14.0, 0.4, 6);
  FiberModel m = generateCube(c);
  CollisionSolverOptions o;
  o.periodicCell = cubeCell(c);
  o.initialRadiusScale = 0.7;
  o.maxSteps = 3000;
  CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_TRUE(r.solved);
  EXPECT_EQ(r.radiusScale, 1.0);
  EXPECT_EQ(refPeriodicCount(m, c.edgeLength), 0u);
  for (const Fiber& f : m.fibers)
    for (double x : f.radii)
      EXPECT_EQ(x, 0.8);
  // Infeasible: stops at MaxSteps below full size and reports the fraction reached.
  const CubeOptions d = periodicCube(1, 10.0, 0.95, 6);
  m = generateCube(d);
  o.periodicCell = cubeCell(d);
  o.maxSteps = 40;
  r = solveCollisions(m, o);
  EXPECT_FALSE(r.solved);
  EXPECT_LT(r.radiusScale, 1.0);
  EXPECT_EQ(r.steps, 40);
  bool said = false;
  for (const std::string& w : r.warnings)
    said = said || w.find("radius growth stalled at") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(PeriodicSolver, CellTooSmallForTheLinksIsAnErrorAndLeavesTheModel)
{
  CubeOptions c = periodicCube(1, 6.0, 0.3, 4);
  FiberModel m = generateCube(c);
  const FiberModel in = m;
  CollisionSolverOptions o;
  o.periodicCell = cubeCell(c);
  o.segmentLength = 3.0; // links up to 4 µm + 2 radii: more than half the 6 µm cell
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_NE(r.error.find("periodic cell"), std::string::npos) << r.error;
  ASSERT_EQ(m.fibers.size(), in.fibers.size());
  for (std::size_t f = 0; f < m.fibers.size(); ++f)
    EXPECT_TRUE(m.fibers[f].points == in.fibers[f].points);
}

TEST(PeriodicCell, BoundsFieldIsValidated)
{
  PeriodicCell cell;
  const double good[6] = { -1, 1, -2, 2, -3, 3 };
  EXPECT_EQ(periodicCellFromBounds(good, 6, cell), "");
  EXPECT_EQ(cell.edge().z, 6.0);
  EXPECT_NE(periodicCellFromBounds(good, 5, cell).find("6"), std::string::npos);
  const double flat[6] = { -1, 1, 2, 2, -3, 3 };
  EXPECT_NE(periodicCellFromBounds(flat, 6, cell), "");
  const double nan[6] = { -1, 1, -2, std::nan(""), -3, 3 };
  EXPECT_NE(periodicCellFromBounds(nan, 6, cell), "");
}

TEST(PeriodicCell, EdgeThatOverflowsIsRefusedEverywhere)
{
  // Finite bounds whose edge overflows (1e308 − (−1e308) = inf), a huge edge, and an edge too fine
  // for its bounds' magnitude: refused by the one rule, in short number form, by the field reader
  // and by the solver's options alike (the solver used to die on std::length_error).
  PeriodicCell cell;
  const double overflow[6] = { -1e308, 1e308, -5, 5, -5, 5 };
  const std::string e = periodicCellFromBounds(overflow, 6, cell);
  EXPECT_NE(e.find("periodic_cell axis x is [-1e+308, 1e+308]"), std::string::npos) << e;
  EXPECT_NE(e.find("edge inf"), std::string::npos) << e;
  EXPECT_FALSE(cell.enabled()) << "a refused cell must not be filled in";
  const double huge[6] = { -5, 5, 0, 2e9, -5, 5 };
  EXPECT_NE(periodicCellFromBounds(huge, 6, cell).find("axis y"), std::string::npos);
  const double fine[6] = { -5, 5, -5, 5, 1e15, 1e15 + 0.5 };
  EXPECT_NE(periodicCellFromBounds(fine, 6, cell).find("axis z"), std::string::npos);

  FiberModel m;
  Fiber f;
  f.points = { { -4, 0, 0 }, { 0, 0, 0 }, { 4, 0, 0 } };
  f.radii = { 1, 1, 1 };
  m.fibers = { f };
  const FiberModel in = m;
  CollisionSolverOptions o;
  o.periodicCell.lo = { -1e308, -5, -5 };
  o.periodicCell.hi = { 1e308, 5, 5 };
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_NE(r.error.find("periodic_cell axis x"), std::string::npos) << r.error;
  EXPECT_TRUE(m.fibers[0].points == in.fibers[0].points);
}

TEST(PeriodicTiling, CopiesExactlyTheTranslatesThatReachTheBox)
{
  // One closed fiber along x through (0, 0, 0), radius 0.5, in the cell [-5, 5]³; it spans
  // x in [-5.5, 5.5] with its radius, so a box [-15, 15] x [-5, 5]² needs the translates
  // i = -2 … 2 along x (|i|·10 − 5.5 < 15) and none across.
  FiberModel m;
  Fiber f;
  f.points = { { -5, 0, 0 }, { 0, 0.2, 0 }, { 5, 0, 0 } };
  f.radii = { 0.5, 0.5, 0.5 };
  f.id = 7;
  f.bundle = 1;
  m.fibers.push_back(f);
  const PeriodicCell cell{ { -5, -5, -5 }, { 5, 5, 5 } };
  const double box[6] = { -15, 15, -5, 5, -5, 5 };
  ASSERT_EQ(tileModel(m, cell, box), "");
  ASSERT_EQ(m.fibers.size(), 5u);
  std::vector<std::int64_t> ids;
  for (std::size_t c = 0; c < 5; ++c)
  {
    EXPECT_EQ(m.fibers[c].points[1].x, -20.0 + 10.0 * double(c));
    EXPECT_EQ(m.fibers[c].points[1].y, 0.2);
    EXPECT_EQ(m.fibers[c].bundle, 1);
    ids.push_back(m.fibers[c].id);
  }
  EXPECT_EQ(m.fibers[2].id, 7); // the cell's own copy
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(std::unique(ids.begin(), ids.end()), ids.end());
  // The same fiber near the top face (y in [4.3, 5.5] with its radius) and a box reaching 0.2
  // beyond the y faces: the translate one period down (y in [-5.7, -4.5]) reaches in, the one
  // above does not: 5 × 2.
  FiberModel n;
  n.fibers.push_back(f);
  for (Vec3& p : n.fibers[0].points)
    p.y += 4.8;
  const double taller[6] = { -15, 15, -5.2, 5.2, -1, 1 };
  ASSERT_EQ(tileModel(n, cell, taller), "");
  EXPECT_EQ(n.fibers.size(), 10u);
}

TEST(PeriodicDetection, ACellTooSmallForItsLinksIsNeverCountedAsOverlapFree)
{
  // Two crossing straight fibers whose 4 µm links reach further than half the 5 µm cell: the
  // minimum image is ambiguous, so no count is possible — and 0 ("no overlaps") would be a lie.
  FiberModel m;
  Fiber a;
  a.points = { Vec3{ -2, 0, 0 }, Vec3{ 2, 0, 0 } };
  a.radii = { 0.8, 0.8 };
  a.id = 0;
  Fiber b = a;
  b.points = { Vec3{ 0, -2, 0 }, Vec3{ 0, 2, 0 } };
  b.id = 1;
  m.fibers = { a, b };
  PeriodicCell cell;
  cell.lo = Vec3{ -2.5, -2.5, -2.5 };
  cell.hi = Vec3{ 2.5, 2.5, 2.5 };
  EXPECT_EQ(countCollisions(m, 0.0, 1), 1u); // open space: they cross
  EXPECT_EQ(countCollisions(m, 0.0, 1, cell), std::numeric_limits<std::size_t>::max());
}

// One wrap rule: the cell's wrap brings any point into [lo, hi) by whole edges, and the
// distributed solver's boxes shift a point by exactly the same bits, so that a link's tester box
// and the pair finder's image of it agree.
TEST(PeriodicCell, WrapShiftIsOneRuleForTheCellAndTheBoxes)
{
  PeriodicCell cell;
  cell.lo = { -5.0, 0.25, 10.0 };
  cell.hi = { 7.0, 3.25, 10.5 }; // edges 12, 3, 0.5
  FiberModel model;
  model.fibers.push_back(fiberpli_test::line({ -5, 0.25, 10.2 }, { 4, 1, 0 }, 4, 0.1, 0));
  runRanks(2,
    [&](Comm& comm)
    {
      const BoxLayout layout = BoxLayout::make(model, cell, comm);
      for (const Vec3 p : { Vec3{ -5, 0.25, 10 }, Vec3{ 7, 3.25, 10.5 }, Vec3{ -41.5, 100.1, -3.3 },
             Vec3{ 1e3, -1e-9, 10.49 } })
      {
        const Vec3 t = cell.wrapShift(p);
        for (int d = 0; d < 3; ++d)
        {
          const double e = cell.hi[d] - cell.lo[d];
          EXPECT_EQ(t[d] / e, std::nearbyint(t[d] / e)) << "whole edges, axis " << d;
          EXPECT_GE(p[d] + t[d], cell.lo[d]) << "axis " << d;
          EXPECT_LT(p[d] + t[d], cell.hi[d] + 1e-12 * std::fabs(p[d]))
            << "axis " << d; // up to rounding
        }
        const Vec3 b = layout.wrapShift(p);
        EXPECT_TRUE(b.x == t.x && b.y == t.y && b.z == t.z);
      }
    });
}

TEST(PeriodicCube, AnEdgeTheSourceAcceptsTheSolverAccepts)
{
  // EdgeLength 8 with SegmentLength 2, Displacement 0.3 and FiberRadius 0.8 passed the source (>= 4
  // radii) although the solver's links may reach 2 + 0.6 + 1.6 um, more than half the cell. The
  // source now applies the solver's rule to the longest links the solver can meet: it refuses
  // such an edge naming EdgeLength, and what it accepts the solver solves without that error.
  CubeOptions c;
  c.populations = 1;
  c.periodic = true;
  c.numberOfFibers = 2;
  c.fiberRadius = 0.8;
  c.segmentLength = 2.0;
  c.displacement = 0.3;
  c.edgeLength = 8.0;
  const std::string e = validateCubeOptions(c);
  EXPECT_NE(
    e.find("EdgeLength is 8, too small for SegmentLength 2, Displacement 0.3 and FiberRadius 0.8"),
    std::string::npos)
    << e;
  EXPECT_NE(e.find("twice the largest link reach"), std::string::npos) << e;
  for (double edge : { 8.6, 9.0, 12.0 })
  {
    c.edgeLength = edge;
    ASSERT_EQ(validateCubeOptions(c), "") << edge;
    FiberModel m = generateCube(c);
    CollisionSolverOptions o;
    o.periodicCell = cubeCell(c);
    o.segmentLength = c.segmentLength;
    o.maxSteps = 50;
    o.numberOfThreads = 1;
    const CollisionSolverResult r = solveCollisions(m, o);
    EXPECT_EQ(r.error.find("link reach"), std::string::npos) << edge << ": " << r.error;
  }
}
