// Collision solver (docs/solver.md §4–§6, tests 14–27 of §10). Overlaps are counted by an
// independent brute-force checker (BruteForceOverlap.h), never by the solver's own detection.
#include "Solver/CollisionSolver.h"

#include "BruteForceOverlap.h"
#include "SolverTestModels.h"
#include "Tissue/CubeGenerator.h"
#include "Util/Random.h"

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

using namespace fiberpli;

namespace
{
using fiberpli_test::line;
using fiberpli_test::paperCube;

double minAxisDistance(const Fiber& a, const Fiber& b)
{
  double d = HUGE_VAL;
  for (std::size_t i = 0; i + 1 < a.size(); ++i)
    for (std::size_t j = 0; j + 1 < b.size(); ++j)
      d = std::min(d,
        fiberpli_test::refSegmentDistance(
          a.points[i], a.points[i + 1], b.points[j], b.points[j + 1]));
  return d;
}

bool allFinite(const FiberModel& m)
{
  for (const Fiber& f : m.fibers)
    for (const Vec3& p : f.points)
      if (!isFinite(p))
        return false;
  return true;
}

using fiberpli_test::bitwiseEqual;
} // namespace

TEST(CollisionSolver, CrossingFibersSeparateSymmetrically)
{
  const double d = 0.5;
  FiberModel m;
  m.fibers.push_back(line({ -10, 0, 0 }, { 1, 0, 0 }, 21, 1.0, 0));
  m.fibers.push_back(line({ 0, -10, d }, { 0, 1, 0 }, 21, 1.0, 1));
  CollisionSolverOptions o;
  o.segmentLength = 1.0;
  o.maxSteps = 2000;
  const CollisionSolverResult r = solveCollisions(m, o);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_TRUE(r.solved);
  EXPECT_GT(r.steps, 0);
  EXPECT_EQ(fiberpli_test::refCollisionCount(m), 0u);
  const double dist = minAxisDistance(m.fibers[0], m.fibers[1]);
  EXPECT_GE(dist, 2.0);
  EXPECT_LE(dist, 2.5);
  // (x, y, z) ↦ (y, x, d − z) maps fiber A onto fiber B.
  const Fiber& a = m.fibers[0];
  const Fiber& b = m.fibers[1];
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    EXPECT_NEAR(a.points[i].x, b.points[i].y, 1e-9);
    EXPECT_NEAR(a.points[i].y, b.points[i].x, 1e-9);
    EXPECT_NEAR(a.points[i].z, d - b.points[i].z, 1e-9);
  }
}

TEST(CollisionSolver, ExactIntersectionLowerIdMovesUp)
{
  FiberModel m;
  m.fibers.push_back(line({ -10, 0, 0 }, { 1, 0, 0 }, 21, 1.0, 0));
  m.fibers.push_back(line({ 0, -10, 0 }, { 0, 1, 0 }, 21, 1.0, 1));
  CollisionSolverOptions o;
  o.segmentLength = 1.0;
  o.maxSteps = 2000;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_TRUE(r.solved);
  EXPECT_TRUE(allFinite(m));
  EXPECT_EQ(fiberpli_test::refCollisionCount(m), 0u);
  EXPECT_GT(m.fibers[0].points[10].z, m.fibers[1].points[10].z);
}

TEST(CollisionSolver, ParallelFibersStayPlanar)
{
  FiberModel m;
  m.fibers.push_back(line({ 0, 0, 0 }, { 1, 0, 0 }, 21, 1.0, 0));
  m.fibers.push_back(line({ 0, 0.5, 0 }, { 1, 0, 0 }, 21, 1.0, 1));
  CollisionSolverOptions o;
  o.segmentLength = 1.0;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_TRUE(r.solved);
  EXPECT_GE(minAxisDistance(m.fibers[0], m.fibers[1]), 2.0);
  for (const Fiber& f : m.fibers)
    for (const Vec3& p : f.points)
      EXPECT_EQ(p.z, 0.0);
}

TEST(CollisionSolver, CoincidentFibersSeparateDeterministically)
{
  FiberModel copies;
  copies.fibers.push_back(line({ 0, 0, 0 }, { 1, 0.5, 0 }, 6, 0.5, 0));
  copies.fibers.push_back(copies.fibers[0]);
  copies.fibers[1].id = 1;
  CollisionSolverOptions o;
  o.segmentLength = -1.0;
  o.maxSteps = 2000;
  const CollisionSolverResult r = solveCollisions(copies, o);
  EXPECT_TRUE(r.solved);
  EXPECT_TRUE(allFinite(copies));
  EXPECT_EQ(fiberpli_test::refCollisionCount(copies), 0u);

  FiberModel collinear; // fastPLI's test_fibers case
  collinear.fibers.push_back(line({ 0, 0, 0 }, { 0, 0, 1 }, 2, 0.1, 0));
  collinear.fibers.push_back(line({ 0, 0, 0.1 }, { 0, 0, 1 }, 2, 0.1, 1));
  const CollisionSolverResult rc = solveCollisions(collinear, o);
  EXPECT_TRUE(rc.solved);
  for (const Vec3& p : collinear.fibers[0].points)
  {
    EXPECT_EQ(p.x, 0.0); // §2.4 rule 2: along ±e_y only
    EXPECT_GT(p.y, 0.0);
  }
  for (const Vec3& p : collinear.fibers[1].points)
  {
    EXPECT_EQ(p.x, 0.0);
    EXPECT_LT(p.y, 0.0);
  }
}

TEST(CollisionSolver, SolvedInputIsReturnedBitIdentical)
{
  FiberModel m;
  m.fibers.push_back(line({ 0, 0, 0 }, { 1.5, 0, 0 }, 8, 0.7, 42));
  m.fibers[0].bundle = 3;
  const FiberModel in = m;
  CollisionSolverOptions o;
  o.segmentLength = 1.5;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_TRUE(bitwiseEqual(m, in));
  EXPECT_EQ(r.steps, 0);
  EXPECT_TRUE(r.solved);
  EXPECT_TRUE(r.shapeOk);
  ASSERT_EQ(r.sourceIndex.size(), 1u);
  for (std::size_t i = 0; i < 8; ++i)
    EXPECT_EQ(r.sourceIndex[0][i], double(i));

  // §10 test 10: a straight fiber and a zig-zag thicker than their links stay untouched.
  FiberModel thick;
  thick.fibers.push_back(line({ 0, 0, 0 }, { 1, 0, 0 }, 21, 2.0, 0));
  std::vector<Vec3> zz;
  for (int i = 0; i <= 20; ++i)
    zz.push_back({ double((i + 1) / 2), double(i / 2), 50.0 });
  Fiber z;
  z.points = zz;
  z.radii.assign(zz.size(), 2.0);
  z.id = 1;
  thick.fibers.push_back(z);
  const FiberModel thickIn = thick;
  o.segmentLength = 1.0;
  const CollisionSolverResult rt = solveCollisions(thick, o);
  EXPECT_TRUE(bitwiseEqual(thick, thickIn));
  EXPECT_EQ(rt.steps, 0);
}

TEST(CollisionSolver, HairpinLegsAreSeparated)
{
  Fiber f;
  for (int i = 0; i <= 10; ++i)
    f.points.push_back({ double(10 - i), 0, 0 });
  f.points.push_back({ -0.5, 0.5, 0 });
  for (int i = 0; i <= 10; ++i)
    f.points.push_back({ double(i), 1, 0 });
  f.radii.assign(f.points.size(), 0.6);
  FiberModel m;
  m.fibers.push_back(f);
  ASSERT_GT(fiberpli_test::refCollisionCount(m), 0u);
  CollisionSolverOptions o;
  o.segmentLength = 1.0;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_TRUE(r.solved);
  EXPECT_EQ(fiberpli_test::refCollisionCount(m), 0u);
}

TEST(ShapeControl, SplitAndMerge)
{
  FiberPointState st;
  auto reset = [&](const Fiber& f)
  {
    st.velocity.assign(f.size(), Vec3{});
    st.source.clear();
    for (std::size_t i = 0; i < f.size(); ++i)
      st.source.push_back(double(i));
  };
  Fiber a;
  a.points = { { 0, 0, 0 }, { 0, 0, 1 } };
  a.radii = { 1.0, 2.0 };
  reset(a);
  EXPECT_TRUE(controlSegmentLength(a, st, 0.5));
  ASSERT_EQ(a.size(), 3u);
  EXPECT_EQ(a.radii[1], 1.5);
  EXPECT_EQ(a.points[1], (Vec3{ 0, 0, 0.5 }));
  EXPECT_EQ(st.source[1], 0.5);

  Fiber b;
  b.points = { { 0, 0, 0 }, { 0, 0, 0.1 }, { 0, 0, 2 } };
  b.radii = { 1, 1, 1 };
  reset(b);
  EXPECT_TRUE(controlSegmentLength(b, st, 2.0));
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b.points[0], (Vec3{ 0, 0, 0 }));
  EXPECT_EQ(b.points[1], (Vec3{ 0, 0, 2 }));
  EXPECT_EQ(st.source[1], 2.0);

  Fiber c;
  c.points = { { 0, 0, 0 }, { 0, 0, 0.3 } };
  c.radii = { 1, 1 };
  reset(c);
  EXPECT_FALSE(controlSegmentLength(c, st, 2.0));
  EXPECT_EQ(c.size(), 2u);
}

TEST(ShapeControl, RanvierNodeSurvivesMergePressure)
{
  const double r = 1.0;
  Fiber f;
  for (int i = 0; i <= 40; ++i)
    f.points.push_back({ 0.5 * i, 0, 0 });
  f.radii.assign(f.points.size(), r);
  f.radii[20] = 0.5 * r; // 10 µm from either end, l_min = 4/3 µm
  FiberPointState st;
  st.velocity.assign(f.size(), Vec3{});
  for (std::size_t i = 0; i < f.size(); ++i)
    st.source.push_back(double(i));
  for (int step = 0; step < 200; ++step)
    controlSegmentLength(f, st, 2.0);
  bool found = false;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (f.radii[i] == 0.5 * r)
    {
      found = true;
      EXPECT_EQ(st.source[i], 20.0);
      EXPECT_EQ(f.points[i], (Vec3{ 10, 0, 0 }));
    }
  EXPECT_TRUE(found);
  for (std::size_t i = 0; i + 1 < f.size(); ++i)
  {
    const double len = distance(f.points[i], f.points[i + 1]);
    EXPECT_GE(len, 2.0 * 2.0 / 3.0);
    EXPECT_LE(len, 2.0 * 4.0 / 3.0);
  }
}

// A beaded fiber squeezed (merges) and then stretched (splits): every new point takes its radius
// from the input profile at its source index, so the beads are not averaged away; the mean of the
// two neighbours (no profile) leaves points off the profile.
TEST(ShapeControl, SplitsKeepTheInputRadiusProfile)
{
  for (const bool withProfile : { true, false })
  {
    Fiber f;
    for (int i = 0; i <= 64; ++i)
    {
      f.points.push_back({ 0.5 * i, 0, 0 });
      f.radii.push_back(1.0 + 0.3 * std::sin(2.0 * M_PI * i / 16.0));
    }
    FiberPointState st;
    st.velocity.assign(f.size(), Vec3{});
    for (std::size_t i = 0; i < f.size(); ++i)
      st.source.push_back(double(i));
    if (withProfile)
      st.inputRadii = f.radii;
    const std::vector<double> input = f.radii;
    while (controlSegmentLength(f, st, 2.0)) // links of 0.5 µm merge up to [4/3, 8/3] µm
    {
    }
    ASSERT_LT(f.size(), 40u);
    for (Vec3& p : f.points)
      p = 3.0 * p; // links of 4–8 µm split down again
    while (controlSegmentLength(f, st, 2.0))
    {
    }
    double worst = 0.0;
    for (std::size_t i = 0; i < f.size(); ++i)
      worst = std::max(worst, std::fabs(f.radii[i] - profileRadius(input, st.source[i])));
    if (withProfile)
      EXPECT_LT(worst, 1e-12);
    else
      EXPECT_GT(worst, 0.01);
  }
  EXPECT_DOUBLE_EQ(profileRadius({ 1.0, 3.0, 2.0 }, 0.5), 2.0);
  EXPECT_DOUBLE_EQ(profileRadius({ 1.0, 3.0, 2.0 }, 1.25), 2.75);
  EXPECT_DOUBLE_EQ(profileRadius({ 1.0, 3.0, 2.0 }, 7.0), 2.0);
  EXPECT_DOUBLE_EQ(profileRadius({ 1.0, 3.0, 2.0 }, -1.0), 1.0);
}

TEST(ShapeControl, CurvatureFlattensSharpVertex)
{
  Fiber f;
  f.points = { { 0, 0, 0 }, { 1, 1, 0 }, { 2, 0, 0 } }; // 90° vertex, R = 1
  f.radii = { 1, 1, 1 };
  EXPECT_FALSE(curvatureOk(f, 2.0));
  EXPECT_TRUE(curvatureOk(f, 0.9));
  const Vec3 before = f.points[1];
  EXPECT_TRUE(controlCurvature(f, 2.0, 0.1, EndPointRule::Free));
  EXPECT_NEAR(f.points[1].y, before.y - 0.02, 1e-15); // 0.2·step towards the chord
  EXPECT_NEAR(f.points[0].y, 0.005, 1e-15);           // neighbours 0.05·step away
  Fiber g;
  g.points = { { 0, 0, 0 }, { 1, 1, 0 }, { 2, 0, 0 } };
  g.radii = { 1, 1, 1 };
  controlCurvature(g, 2.0, 0.1, EndPointRule::Fixed);
  EXPECT_EQ(g.points[0], (Vec3{ 0, 0, 0 }));
  EXPECT_EQ(g.points[2], (Vec3{ 2, 0, 0 }));
}

class SolverCube : public ::testing::TestWithParam<int>
{
};

TEST_P(SolverCube, SmallPaperDensityCubeIsSolved)
{
  const int pops = GetParam();
  FiberModel m = paperCube(pops, 40, 42);
  const FiberModel in = m;
  CollisionSolverOptions o;
  o.segmentLength = 2.0;
  o.minCurvatureRadius = 4.0;
  o.maxSteps = 20000;
  o.numberOfThreads = 2;
  ASSERT_GT(fiberpli_test::refCollisionCount(in), 0u);
  const CollisionSolverResult r = solveCollisions(m, o);
  ASSERT_TRUE(r.error.empty());
  EXPECT_TRUE(r.solved);
  EXPECT_TRUE(r.shapeOk);
  EXPECT_EQ(r.collisions, 0u);
  EXPECT_EQ(fiberpli_test::refCollisionCount(m), 0u);
  EXPECT_EQ(countCollisions(m, 0.0, 1), 0u);
  ASSERT_EQ(m.fibers.size(), in.fibers.size());
  ASSERT_EQ(r.sourceIndex.size(), in.fibers.size());
  for (std::size_t f = 0; f < m.fibers.size(); ++f)
  {
    const Fiber& a = m.fibers[f];
    const Fiber& b = in.fibers[f];
    EXPECT_EQ(a.id, b.id);
    EXPECT_EQ(a.bundle, b.bundle);
    ASSERT_EQ(r.sourceIndex[f].size(), a.size());
    EXPECT_EQ(r.sourceIndex[f].front(), 0.0);
    EXPECT_EQ(r.sourceIndex[f].back(), double(b.size() - 1));
    for (std::size_t i = 0; i + 1 < a.size(); ++i)
    {
      EXPECT_LT(r.sourceIndex[f][i], r.sourceIndex[f][i + 1]);
      const double len = distance(a.points[i], a.points[i + 1]);
      EXPECT_GE(len, 4.0 / 3.0);
      EXPECT_LE(len, 8.0 / 3.0);
    }
    for (std::size_t i = 1; i + 1 < a.size(); ++i)
    {
      // Circumradius R = abc / (2|e1 × e2|) >= 4 and vertex angle >= 60°.
      const Vec3 e1 = a.points[i] - a.points[i - 1], e2 = a.points[i + 1] - a.points[i];
      const double la = norm(e1), lb = norm(e2), lc = distance(a.points[i + 1], a.points[i - 1]);
      EXPECT_GE(la * lb * lc, 2.0 * norm(cross(e1, e2)) * 4.0 * (1.0 - 1e-12));
      EXPECT_LE(dot(-e1, e2), 0.5 * la * lb * (1.0 + 1e-12));
    }
    for (double rad : a.radii)
      EXPECT_EQ(rad, 0.8);
  }
}

INSTANTIATE_TEST_SUITE_P(Populations, SolverCube, ::testing::Values(1, 2, 3));

TEST(CollisionSolver, BitIdenticalForAnyThreadCount)
{
  const FiberModel in = paperCube(1, 200, 1);
  CollisionSolverOptions o;
  o.maxSteps = 100;
  o.minCurvatureRadius = 4.0;
  FiberModel reference = in;
  o.numberOfThreads = 1;
  const CollisionSolverResult r1 = solveCollisions(reference, o);
  EXPECT_EQ(r1.steps, 100);
  for (int t : { 1, 2, 3, 4, 7 })
  {
    FiberModel m = in;
    o.numberOfThreads = t;
    const CollisionSolverResult r = solveCollisions(m, o);
    EXPECT_TRUE(bitwiseEqual(m, reference)) << t << " threads";
    EXPECT_EQ(r.collisions, r1.collisions);
    EXPECT_EQ(r.sourceIndex, r1.sourceIndex);
  }
}

TEST(CollisionSolver, FixedEndsThatCannotMoveStopAtMaxSteps)
{
  FiberModel m;
  m.fibers.push_back(line({ -1, 0, 0 }, { 2, 0, 0 }, 2, 0.5, 0));
  m.fibers.push_back(line({ 0, -1, 0 }, { 0, 2, 0 }, 2, 0.5, 1));
  const FiberModel in = m;
  CollisionSolverOptions o;
  o.endPoints = EndPointRule::Fixed;
  o.segmentLength = -1.0;
  o.maxSteps = 50;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_EQ(r.steps, 50);
  EXPECT_FALSE(r.solved);
  EXPECT_EQ(r.collisions, 1u);
  EXPECT_EQ(fiberpli_test::refCollisionCount(m), 1u);
  EXPECT_NEAR(r.maxOverlap, 1.0, 1e-15);
  EXPECT_FALSE(r.warnings.empty());
  EXPECT_TRUE(bitwiseEqual(m, in)); // end points bitwise unchanged
}

TEST(CollisionSolver, ProgressFalseAborts)
{
  FiberModel m = paperCube(2, 60, 5);
  CollisionSolverOptions o;
  int calls = 0;
  const CollisionSolverResult r = solveCollisions(m, o,
    [&](double f)
    {
      EXPECT_GT(f, 0.0);
      EXPECT_LE(f, 1.0);
      return ++calls < 3;
    });
  EXPECT_TRUE(r.aborted);
  EXPECT_EQ(r.steps, 3);
  EXPECT_EQ(calls, 3);
  EXPECT_FALSE(r.solved);
  EXPECT_EQ(r.collisions, fiberpli_test::refCollisionCount(m));
  EXPECT_EQ(r.collisions, countCollisions(m));
}

TEST(CollisionSolver, ObserverSeesEveryStep)
{
  FiberModel m = paperCube(1, 30, 8);
  CollisionSolverOptions o;
  o.maxSteps = 20;
  int last = 0;
  const CollisionSolverResult r = solveCollisions(m, o, {},
    [&](int step, const FiberModel& cur)
    {
      EXPECT_EQ(step, last + 1);
      EXPECT_EQ(cur.fibers.size(), 30u);
      last = step;
    });
  EXPECT_EQ(last, r.steps);
}

TEST(CollisionSolver, EndPointsMovePerpendicular)
{
  // §10 test 22: every move of an end point is perpendicular to its end link at that moment
  // (shape control off, so consecutive observer snapshots are exactly one move phase apart).
  FiberModel m = paperCube(2, 30, 4);
  CollisionSolverOptions o;
  o.segmentLength = -1.0;
  o.maxSteps = 30;
  FiberModel prev = m;
  int checked = 0;
  solveCollisions(m, o, {},
    [&](int, const FiberModel& cur)
    {
      for (std::size_t f = 0; f < cur.fibers.size(); ++f)
      {
        const Fiber& a = prev.fibers[f];
        const Fiber& b = cur.fibers[f];
        const std::size_t n = a.size();
        const Vec3 t0 = normalized(a.points[1] - a.points[0]);
        const Vec3 t1 = normalized(a.points[n - 1] - a.points[n - 2]);
        const Vec3 d0 = b.points[0] - a.points[0];
        const Vec3 d1 = b.points[n - 1] - a.points[n - 1];
        EXPECT_LE(std::fabs(dot(d0, t0)), 1e-12 * (norm(d0) + 1e-300) + 1e-15);
        EXPECT_LE(std::fabs(dot(d1, t1)), 1e-12 * (norm(d1) + 1e-300) + 1e-15);
        checked += norm(d0) > 0.0 ? 1 : 0;
      }
      prev = cur;
    });
  EXPECT_GT(checked, 0);
}

TEST(CollisionSolver, BadInputGivesClearErrors)
{
  CollisionSolverOptions o;
  FiberModel m;
  m.fibers.push_back(line({ 0, 0, 0 }, { 1, 0, 0 }, 3, 1.0, 7));
  FiberModel noRadius = m;
  noRadius.fibers[0].radii.clear();
  CollisionSolverResult r = solveCollisions(noRadius, o);
  EXPECT_NE(r.error.find("radii"), std::string::npos) << r.error;

  FiberModel nan = m;
  nan.fibers[0].points[2].y = std::numeric_limits<double>::quiet_NaN();
  r = solveCollisions(nan, o);
  EXPECT_NE(r.error.find("point 2"), std::string::npos) << r.error;

  FiberModel zero = m;
  zero.fibers[0].radii[1] = 0.0;
  r = solveCollisions(zero, o);
  EXPECT_NE(r.error.find("radius"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("fiber 0"), std::string::npos) << r.error;

  o.maxSteps = -1;
  r = solveCollisions(m, o);
  EXPECT_NE(r.error.find("MaxSteps"), std::string::npos) << r.error;

  FiberModel empty;
  r = solveCollisions(empty, CollisionSolverOptions{});
  EXPECT_TRUE(r.error.empty());
  EXPECT_EQ(r.steps, 0);
  EXPECT_EQ(r.collisions, 0u);
  EXPECT_TRUE(r.solved);
}

TEST(CollisionSolver, ShortFibersAreCopiedThrough)
{
  FiberModel m;
  m.fibers.push_back(line({ 0, 0, 0 }, { 1, 0, 0 }, 3, 0.5, 0));
  Fiber single;
  single.points = { { 0.5, 0, 0 } };
  single.radii = { 0.5 };
  m.fibers.push_back(single);
  Fiber dup = line({ 0.5, 0, 0 }, { 0, 0, 0 }, 3, 0.5, 2);
  m.fibers.push_back(dup);
  CollisionSolverOptions o;
  o.segmentLength = -1.0;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_TRUE(r.error.empty());
  EXPECT_TRUE(r.solved);
  EXPECT_EQ(m.fibers[1].points, single.points);
  EXPECT_EQ(m.fibers[2].points, dup.points);
  EXPECT_FALSE(r.warnings.empty());
}

TEST(CollisionSolver, MinimumGapIsKept)
{
  FiberModel m;
  m.fibers.push_back(line({ 0, 0, 0 }, { 1, 0, 0 }, 11, 1.0, 0));
  m.fibers.push_back(line({ 0, 1.5, 0 }, { 1, 0, 0 }, 11, 1.0, 1));
  CollisionSolverOptions o;
  o.segmentLength = 1.0;
  o.minimumGap = 0.5;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_TRUE(r.solved);
  EXPECT_GE(minAxisDistance(m.fibers[0], m.fibers[1]), 2.5);
  EXPECT_EQ(fiberpli_test::refCollisionCount(m, 0.5), 0u);
  EXPECT_EQ(countCollisions(m, 0.5, 1), 0u);
}

TEST(CollisionSolver, StallStepsStopsEarly)
{
  FiberModel m; // cannot move: fixed ends, no split
  m.fibers.push_back(line({ -1, 0, 0 }, { 2, 0, 0 }, 2, 0.5, 0));
  m.fibers.push_back(line({ 0, -1, 0 }, { 0, 2, 0 }, 2, 0.5, 1));
  CollisionSolverOptions o;
  o.endPoints = EndPointRule::Fixed;
  o.segmentLength = -1.0;
  o.maxSteps = 1000;
  o.stallSteps = 5;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_EQ(r.steps, 5);
  EXPECT_FALSE(r.solved);
  EXPECT_EQ(r.bestCollisions, 1u);
  EXPECT_EQ(r.bestStep, 0);
}

TEST(CollisionSolver, DragKeepsVelocityAndStillSolves)
{
  FiberModel a = paperCube(2, 40, 6);
  FiberModel b = a;
  CollisionSolverOptions o;
  o.minCurvatureRadius = 4.0;
  o.drag = 0.5;
  o.numberOfThreads = 1;
  const CollisionSolverResult ra = solveCollisions(a, o);
  o.numberOfThreads = 2;
  const CollisionSolverResult rb = solveCollisions(b, o);
  EXPECT_TRUE(ra.solved);
  EXPECT_TRUE(allFinite(a));
  EXPECT_EQ(fiberpli_test::refCollisionCount(a), 0u);
  EXPECT_EQ(ra.steps, rb.steps);
  EXPECT_TRUE(bitwiseEqual(a, b));
}

// DragSteps N: the first N moves keep momentum, the rest have none. So the run equals one with
// momentum stopped after N steps and resumed (model and state, velocities included) by a run
// without momentum, bit for bit; and it differs from momentum to the end.
TEST(CollisionSolver, DragStepsEndsMomentumAfterThatManyMoves)
{
  const FiberModel in = paperCube(2, 80, 3);
  CollisionSolverOptions o;
  o.minCurvatureRadius = 4.0;
  o.drag = 0.6;
  FiberModel always = in;
  const CollisionSolverResult rAlways = solveCollisions(always, o);
  ASSERT_TRUE(rAlways.solved);
  const int n = 15;
  ASSERT_GT(rAlways.steps, n + 5);
  o.dragSteps = n;
  FiberModel limited = in;
  const CollisionSolverResult rLimited = solveCollisions(limited, o);
  ASSERT_TRUE(rLimited.solved) << rLimited.error;
  EXPECT_EQ(fiberpli_test::refCollisionCount(limited), 0u);
  EXPECT_FALSE(rLimited.steps == rAlways.steps && bitwiseEqual(limited, always));

  o.dragSteps = 0;
  FiberModel m = in;
  CollisionSolverState saved;
  {
    CollisionSolverRun run(m, o);
    ASSERT_TRUE(run.start());
    while (run.state().steps < n && run.step())
    {
    }
    ASSERT_EQ(run.state().steps, n);
    saved = run.state();
  }
  o.drag = 0.0;
  CollisionSolverRun plain(m, o);
  ASSERT_EQ(plain.resume(saved), "");
  while (plain.step())
  {
  }
  const CollisionSolverResult rPlain = plain.finish();
  EXPECT_EQ(rPlain.steps, rLimited.steps);
  EXPECT_TRUE(bitwiseEqual(m, limited));
}

TEST(CollisionSolver, SourceIndexLocatesSplitPoints)
{
  // One 2-point fiber of length 10 with radii 1 → 2, L̄ = 2 (l_max 8/3): halved twice into links
  // of 2.5; every new
  // point's source index is its fraction along the input link, and its radius the interpolation.
  FiberModel m;
  Fiber f;
  f.points = { { 0, 0, 0 }, { 10, 0, 0 } };
  f.radii = { 1.0, 2.0 };
  m.fibers.push_back(f);
  CollisionSolverOptions o;
  o.segmentLength = 2.0;
  const CollisionSolverResult r = solveCollisions(m, o);
  ASSERT_TRUE(r.solved);
  const Fiber& out = m.fibers[0];
  ASSERT_EQ(out.size(), 5u);
  ASSERT_EQ(r.sourceIndex[0].size(), 5u);
  for (std::size_t i = 0; i < out.size(); ++i)
  {
    const double u = r.sourceIndex[0][i];
    EXPECT_DOUBLE_EQ(u, double(i) / 4.0);
    EXPECT_DOUBLE_EQ(out.points[i].x, 10.0 * u);
    EXPECT_DOUBLE_EQ(out.radii[i], 1.0 + u);
    EXPECT_GE(out.radii[i], 1.0); // radii stay within the input fiber's range (§10 test 21)
    EXPECT_LE(out.radii[i], 2.0);
  }
}

TEST(CollisionSolver, AbsurdSegmentLengthIsRefusedBeforeAllocating)
{
  FiberModel m;
  m.fibers.push_back(line({ 0, 0, 0 }, { 1e6, 0, 0 }, 3, 1.0, 0)); // 2 m of fiber
  const FiberModel in = m;
  CollisionSolverOptions o;
  o.segmentLength = 1e-3;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_NE(r.error.find("SegmentLength"), std::string::npos) << r.error;
  EXPECT_TRUE(bitwiseEqual(m, in));
}

TEST(CollisionSolver, ThinFibersAmongThickOnesWarnOfTheSlowStepCap)
{
  // The step cap is MaxDisplacement x the smallest radius: one 0.2 µm fiber beside 1 µm ones slows
  // every fiber, and the warning names the option and the resulting step; equal radii do not warn.
  const auto solveWithRadii = [](double thin, double maxDisplacement = 0.125)
  {
    FiberModel m;
    for (int i = 0; i < 4; ++i)
      m.fibers.push_back(line({ -5, 3.0 * i, 0 }, { 1, 0, 0 }, 11, i == 0 ? thin : 1.0, i));
    CollisionSolverOptions o;
    o.segmentLength = 1.0;
    o.maxDisplacement = maxDisplacement;
    return solveCollisions(m, o);
  };
  const auto mentions = [](const CollisionSolverResult& r, const std::string& text)
  {
    for (const std::string& w : r.warnings)
      if (w.find(text) != std::string::npos)
        return true;
    return false;
  };
  const CollisionSolverResult thin = solveWithRadii(0.2);
  EXPECT_TRUE(mentions(thin, "MaxDisplacement 0.125")) << ::testing::PrintToString(thin.warnings);
  EXPECT_TRUE(mentions(thin, "= 0.025")) << ::testing::PrintToString(thin.warnings);
  EXPECT_FALSE(mentions(solveWithRadii(1.0), "MaxDisplacement"));
  // Already at the advised cap: no advice; above 1 (a step beyond the thinnest radius): a warning.
  EXPECT_FALSE(mentions(solveWithRadii(0.2, 0.4), "MaxDisplacement"));
  EXPECT_TRUE(mentions(solveWithRadii(1.0, 1.5), "MaxDisplacement 1.5"));
}

TEST(CollisionSolver, MixedRadiiWithOneThickFiber)
{
  // Random directions and radii 0.4–1.2 µm plus one 4 µm fiber (boxes 4× the median: the grid's
  // cell size follows the largest box): solved, checked by the independent counter.
  FiberModel m;
  RandomStream rng(77, 0, 0);
  for (int i = 0; i < 30; ++i)
  {
    const Vec3 c{ rng.uniform(-6, 6), rng.uniform(-6, 6), rng.uniform(-6, 6) };
    const Vec3 d = normalized(Vec3{ rng.normal(), rng.normal(), rng.normal() });
    Fiber f = line(c - 8.0 * d, 1.0 * d, 17, rng.uniform(0.4, 1.2), i);
    m.fibers.push_back(f);
  }
  m.fibers.push_back(line({ -10, 0, 0 }, { 2, 0, 0 }, 11, 4.0, 30));
  ASSERT_GT(fiberpli_test::refCollisionCount(m), 0u);
  CollisionSolverOptions o;
  o.segmentLength = 1.0;
  o.maxSteps = 20000;
  o.numberOfThreads = 2;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_TRUE(r.solved) << r.collisions;
  EXPECT_EQ(fiberpli_test::refCollisionCount(m), 0u);
  EXPECT_TRUE(allFinite(m));
}

namespace
{
// Peak resident set of this process in bytes (Linux reports KiB).
double peakRssBytes()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return 1024.0 * static_cast<double>(u.ru_maxrss);
}

// Copies of one fiber are refused above 16; 4 are separated like any overlap.
FiberModel copiesOfOneFiber(int copies)
{
  FiberModel m;
  for (int i = 0; i < copies; ++i)
    m.fibers.push_back(line({ 0, 0, 0 }, { 2, 0.1, 0 }, 10, 0.8, i));
  return m;
}
} // namespace

TEST(CollisionSolver, StacksOfIdenticalFibersAreRefusedInBoundedMemory)
{
  // Tractography output often repeats a streamline: 1000 and 3000 copies of one 10-point fiber
  // make 12 M / 110 M colliding pairs (GBs). Refused before any pair is stored, model unchanged,
  // naming the copies.
  for (int copies : { 1000, 3000 })
  {
    FiberModel m = copiesOfOneFiber(copies);
    const FiberModel in = m;
    CollisionSolverOptions o;
    o.numberOfThreads = 2;
    const CollisionSolverResult r = solveCollisions(m, o);
    EXPECT_NE(r.error.find("fiber id 0 has " + std::to_string(copies - 1) + " exact copies"),
      std::string::npos)
      << r.error;
    EXPECT_EQ(r.steps, 0);
    EXPECT_TRUE(bitwiseEqual(m, in));
  }
  EXPECT_LT(peakRssBytes(), 50e6);
}

TEST(CollisionSolver, NearlyIdenticalFibersAreRefusedByThePairLimit)
{
  // 1000 copies 1 nm apart are no exact copies, but still 12 M colliding pairs: the pair limit
  // (packingPairBound, ~1.4 M here) refuses them with bounded memory.
  FiberModel m;
  for (int i = 0; i < 1000; ++i)
    m.fibers.push_back(line({ 0, 1e-3 * i, 0 }, { 2, 0.1, 0 }, 10, 0.8, i));
  const FiberModel in = m;
  CollisionSolverOptions o;
  o.numberOfThreads = 2;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_NE(r.error.find("more than any packing"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("on top of each other"), std::string::npos) << r.error;
  EXPECT_TRUE(bitwiseEqual(m, in));
  // Counting stops above the limit as well (the true count is 12 M).
  EXPECT_GT(countCollisions(m), 1000000u);
  EXPECT_LT(peakRssBytes(), 300e6);
}

TEST(CollisionSolver, AFewCopiesOfAFiberAreStillSeparated)
{
  FiberModel m = copiesOfOneFiber(4);
  CollisionSolverOptions o;
  o.maxSteps = 4000;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_TRUE(r.error.empty()) << r.error;
  EXPECT_TRUE(r.solved);
  EXPECT_EQ(fiberpli_test::refCollisionCount(m), 0u);
}

TEST(CollisionSolver, HugeMinimumGapIsRefused)
{
  // 100 fibers of 28 links 20 µm apart; MinimumGap 1e6 µm makes all 3.8 M link pairs collide.
  FiberModel m;
  for (int i = 0; i < 100; ++i)
    m.fibers.push_back(line({ 0, 20.0 * (i % 10), 20.0 * (i / 10) }, { 2, 0, 0 }, 29, 0.8, i));
  const FiberModel in = m;
  CollisionSolverOptions o;
  o.minimumGap = 1e6;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_NE(r.error.find("MinimumGap is 1e+06, more than 10 x the largest fiber radius 0.8"),
    std::string::npos)
    << r.error;
  EXPECT_TRUE(bitwiseEqual(m, in));
  EXPECT_LT(peakRssBytes(), 100e6);
}

TEST(CollisionSolver, SmallSegmentLengthIsCheckedAgainstTheMemoryBudget)
{
  // 300 fibers of 52 µm: SegmentLength 0.01 makes up to 2.4 M points, and each link collides with
  // hundreds of short links: GBs of solver state, refused under a 200 MiB budget; SegmentLength 2
  // is accepted.
  setenv("FIBERPLI_MEMORY_LIMIT", "200M", 1);
  FiberModel m = paperCube(1, 300, 3);
  const FiberModel in = m;
  CollisionSolverOptions o;
  o.segmentLength = 0.01;
  o.maxSteps = 1;
  CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_NE(r.error.find("SegmentLength 0.01"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("memory budget"), std::string::npos) << r.error;
  EXPECT_TRUE(bitwiseEqual(m, in));
  o.segmentLength = 2.0;
  r = solveCollisions(m, o);
  EXPECT_TRUE(r.error.empty()) << r.error;
  unsetenv("FIBERPLI_MEMORY_LIMIT");
  EXPECT_LT(peakRssBytes(), 200e6);
}

// A run driven step by step, saved after 40 steps (model + state, as a checkpoint) and resumed
// by a fresh run object, ends exactly where the uninterrupted solveCollisions ends.
TEST(CollisionSolver, ResumedRunEqualsUninterruptedRun)
{
  const FiberModel in = paperCube(2, 80, 3);
  CollisionSolverOptions o;
  o.maxSteps = 70;
  o.minCurvatureRadius = 4.0;
  o.drag = 0.3; // velocities are part of the state
  FiberModel reference = in;
  const CollisionSolverResult r1 = solveCollisions(reference, o);
  ASSERT_TRUE(r1.error.empty()) << r1.error;
  ASSERT_GT(r1.steps, 40);

  FiberModel m = in;
  CollisionSolverState saved;
  FiberModel savedModel;
  {
    CollisionSolverRun run(m, o);
    ASSERT_TRUE(run.start());
    while (run.state().steps < 40 && run.step())
    {
    }
    ASSERT_EQ(run.state().steps, 40);
    saved = run.state();
    savedModel = m;
  } // the first run is gone: nothing but model and state carries over
  CollisionSolverRun resumed(savedModel, o);
  ASSERT_EQ(resumed.resume(saved), "");
  while (resumed.step())
  {
  }
  const CollisionSolverResult r2 = resumed.finish();
  EXPECT_TRUE(bitwiseEqual(savedModel, reference));
  EXPECT_EQ(r2.steps, r1.steps);
  EXPECT_EQ(r2.collisions, r1.collisions);
  EXPECT_EQ(r2.bestCollisions, r1.bestCollisions);
  EXPECT_EQ(r2.bestStep, r1.bestStep);
  EXPECT_EQ(r2.sourceIndex, r1.sourceIndex);
  EXPECT_EQ(r2.warnings, r1.warnings);

  // A state that does not belong to the model is refused by name.
  FiberModel other = paperCube(1, 10, 4);
  CollisionSolverRun wrong(other, o);
  EXPECT_NE(wrong.resume(saved).find("fibers"), std::string::npos);
  EXPECT_FALSE(wrong.step());
  EXPECT_FALSE(wrong.finish().error.empty());
}

// PushBoost (docs/solver.md §4.1, default 3): input at the paper's density (4–5 colliding pairs
// per link at the first detection) is solved exactly as without the boost (1 = off).
TEST(CollisionSolver, PushBoostLeavesPaperDensityInputUnchanged)
{
  const FiberModel input = paperCube(2, 60, 7);
  FiberModel plain = input;
  FiberModel boosted = input;
  CollisionSolverOptions o;
  o.segmentLength = 2.0;
  o.minCurvatureRadius = 4.0;
  o.maxSteps = 60;
  o.numberOfThreads = 1;
  o.pushBoost = 1.0;
  const CollisionSolverResult a = solveCollisions(plain, o);
  o.pushBoost = 3.0;
  CollisionSolverRun run(boosted, o);
  ASSERT_TRUE(run.start());
  while (run.step())
  {
  }
  EXPECT_EQ(run.state().pushScale, 1.0);
  const CollisionSolverResult b = run.finish();
  ASSERT_TRUE(a.error.empty() && b.error.empty()) << a.error << b.error;
  EXPECT_GT(a.steps, 0);
  EXPECT_EQ(a.steps, b.steps);
  EXPECT_TRUE(bitwiseEqual(plain, boosted));
}

// A bundle of 9 fibers almost on top of each other (every link collides with ~5 links of each of
// the 8 others: far above 9 pairs per link) gets the full boost: pushes × PushBoost (far below
// half their overlaps of almost two radii) and the move cap × (1 + 0.6·(PushBoost − 1)). The outer
// fibers are pushed far beyond the cap, so the largest move of the first step is exactly the
// (boosted) cap.
TEST(CollisionSolver, PushBoostRaisesPushAndCapOnCrowdedInput)
{
  FiberModel input;
  for (int i = 0; i < 9; ++i)
  {
    input.fibers.push_back(
      line({ -10.0, 0.05 * (i % 3), 0.05 * (i / 3) }, { 1, 0, 0 }, 21, 1.0, i));
  }
  const auto firstMove = [&](double boost, double& scale)
  {
    FiberModel m = input;
    CollisionSolverOptions o;
    o.segmentLength = 1.0;
    o.pushBoost = boost;
    o.numberOfThreads = 1;
    CollisionSolverRun run(m, o);
    EXPECT_TRUE(run.start());
    EXPECT_TRUE(run.step());
    scale = run.state().pushScale;
    double largest = 0.0;
    for (std::size_t f = 0; f < m.fibers.size(); ++f)
      for (std::size_t i = 0; i < m.fibers[f].size(); ++i)
        largest = std::max(largest, distance(m.fibers[f].points[i], input.fibers[f].points[i]));
    return largest;
  };
  double plainScale = 0.0, boostedScale = 0.0;
  const double plain = firstMove(1.0, plainScale);
  const double boosted = firstMove(2.5, boostedScale);
  EXPECT_EQ(plainScale, 1.0);
  EXPECT_EQ(boostedScale, 2.5);
  const double cap = CollisionSolverOptions{}.maxDisplacement * 1.0; // × the smallest radius
  EXPECT_NEAR(plain, cap, 1e-12);
  EXPECT_NEAR(boosted, cap * (1.0 + 0.6 * 1.5), 1e-12);
}

TEST(CollisionSolver, PushBoostOutOfRangeIsRefused)
{
  for (double bad : { 0.5, 4.5, std::numeric_limits<double>::quiet_NaN() })
  {
    CollisionSolverOptions o;
    o.pushBoost = bad;
    EXPECT_NE(validateCollisionSolverOptions(o).find("PushBoost"), std::string::npos) << bad;
  }
}

TEST(CollisionSolver, NegativeDragStepsAreRefused)
{
  CollisionSolverOptions o;
  o.drag = 0.5;
  o.dragSteps = -1;
  const std::string error = validateCollisionSolverOptions(o);
  EXPECT_NE(error.find("DragSteps"), std::string::npos) << error;
  EXPECT_NE(error.find("-1"), std::string::npos) << error;
}

// min_gap (§9) is the smallest surface gap of any two capsules, looked for up to one median
// radius (0.8 µm here): parallel straight fibers of radius 0.8 whose axes are 1.6 + g apart, with
// the smallest g at each stage of the widening search (0.05, 0.2, 0.8 µm) and beyond the probe.
TEST(CollisionSolver, MinGapIsTheSmallestSurfaceGapUpToTheProbe)
{
  for (const std::vector<double>& gaps :
    { std::vector<double>{ 0.5, 0.03, 0.7 }, std::vector<double>{ 0.5, 0.1 },
      std::vector<double>{ 0.6, 0.5 }, std::vector<double>{ 1.0, 2.0 } })
  {
    FiberModel m;
    double y = 0.0;
    m.fibers.push_back(line({ 0, y, 0 }, { 2, 0, 0 }, 8, 0.8, 0));
    for (double g : gaps)
    {
      y += 1.6 + g;
      m.fibers.push_back(
        line({ 0, y, 0 }, { 2, 0, 0 }, 8, 0.8, static_cast<std::int64_t>(m.fibers.size())));
    }
    CollisionSolverOptions o;
    o.maxSteps = 0;
    const CollisionSolverResult r = solveCollisions(m, o);
    ASSERT_EQ(r.error, "");
    EXPECT_EQ(r.minGapProbe, 0.8);
    const double smallest = *std::min_element(gaps.begin(), gaps.end());
    EXPECT_NEAR(r.minGap, std::min(smallest, 0.8), 1e-12) << "smallest gap " << smallest;
  }
}

// The same in a periodic cell, the smallest gap g being across the y faces: six fibers 1 µm
// apart (beyond the probe) and a period of 5 × 2.6 + 1.6 + g, so that the last fiber's image
// lies 1.6 + g from the first one; g at each stage of the widening search and beyond the probe.
TEST(CollisionSolver, MinGapInAPeriodicCellIsTheSmallestGapAcrossTheFaces)
{
  for (double g : { 0.03, 0.1, 0.5, 1.5 })
  {
    FiberModel m;
    for (int i = 0; i < 6; ++i)
      m.fibers.push_back(line({ 0, 2.6 * i, 0 }, { 2, 0, 0 }, 8, 0.8, i));
    CollisionSolverOptions o;
    o.maxSteps = 0;
    const double period = 5 * 2.6 + 1.6 + g;
    o.periodicCell.lo = { -20, -0.8 - 0.5 * g, -8 };
    o.periodicCell.hi = { 40, period - 0.8 - 0.5 * g, 8 };
    const CollisionSolverResult r = solveCollisions(m, o);
    ASSERT_EQ(r.error, "");
    EXPECT_EQ(r.minGapProbe, 0.8);
    EXPECT_NEAR(r.minGap, std::min(g, 0.8), 1e-12) << "gap across the faces " << g;
  }
}
