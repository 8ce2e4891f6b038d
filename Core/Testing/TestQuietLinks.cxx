// Quiet links (docs/solver.md §3.4): skipping the pairs of two links that are unchanged and
// collision-free since the last detection gives bit for bit the run that tests every pair, step
// by step, for any thread count, and it does skip: in a model whose colliding part is small most
// links are quiet in the late steps.
#include "Index/CollisionGrid.h"
#include "Index/PeriodicPairs.h"
#include "PeriodicReference.h"
#include "Solver/CollisionSolver.h"
#include "Solver/QuietLinks.h"
#include "Solver/SolverLinks.h"
#include "SolverTestModels.h"
#include "Tissue/CubeGenerator.h"
#include "Util/Fnv1a.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <vector>

using namespace fiberpli;
using fiberpli_test::bitwiseEqual;
using fiberpli_test::line;
using fiberpli_test::paperCube;
using fiberpli_test::periodicCube;

namespace
{
// FNV-1a over every point and radius of the model, to the bit.
std::uint64_t modelHash(const FiberModel& m)
{
  std::uint64_t h = kFnv1aOffset;
  for (const Fiber& f : m.fibers)
  {
    fnv1aAdd(h, f.points.data(), f.points.size() * sizeof(Vec3));
    fnv1aAdd(h, f.radii.data(), f.radii.size() * sizeof(double));
  }
  return h;
}

// One run driven step by step: the model after every step and the links of every detection.
struct Trace
{
  std::vector<std::uint64_t> models; // the model's hash after each step
  std::vector<std::size_t> detected, loud;
  CollisionSolverResult result;
  FiberModel out;
};

Trace trace(const FiberModel& in, CollisionSolverOptions o, bool quiet, int threads)
{
  Trace t;
  t.out = in;
  o.quietLinks = quiet;
  o.numberOfThreads = threads;
  CollisionSolverRun run(
    t.out, o, {}, [&t](int, const FiberModel& m) { t.models.push_back(modelHash(m)); });
  EXPECT_TRUE(run.start());
  while (run.step())
  {
    t.detected.push_back(run.detectedLinks());
    t.loud.push_back(run.loudLinks());
  }
  t.result = run.finish();
  EXPECT_EQ(t.result.error, "");
  return t;
}

// Quiet skipping on (1 and 3 threads) against off: the same model after every step and the same
// result; returns the run with skipping on (1 thread).
Trace expectSameRuns(const FiberModel& in, const CollisionSolverOptions& o)
{
  const Trace off = trace(in, o, false, 1);
  Trace on = trace(in, o, true, 1);
  const Trace on3 = trace(in, o, true, 3);
  for (const Trace* t : std::initializer_list<const Trace*>{ &on, &on3 })
  {
    EXPECT_EQ(t->result.steps, off.result.steps);
    EXPECT_EQ(t->result.collisions, off.result.collisions);
    EXPECT_EQ(t->result.bestCollisions, off.result.bestCollisions);
    EXPECT_EQ(t->result.bestStep, off.result.bestStep);
    EXPECT_EQ(t->result.maxOverlap, off.result.maxOverlap);
    EXPECT_EQ(t->result.minGap, off.result.minGap);
    EXPECT_EQ(t->result.shapeOk, off.result.shapeOk);
    EXPECT_EQ(t->result.sourceIndex, off.result.sourceIndex);
    EXPECT_EQ(t->result.warnings, off.result.warnings);
    EXPECT_EQ(t->result.detectedLinks, off.result.detectedLinks);
    EXPECT_TRUE(bitwiseEqual(t->out, off.out));
    EXPECT_EQ(t->loud, on.loud);      // the skipping does not depend on the thread count
    EXPECT_EQ(t->models, off.models); // the same model after every step
  }
  EXPECT_EQ(off.result.loudLinks, off.result.detectedLinks); // off: every link is tested
  EXPECT_LE(on.result.loudLinks, on.result.detectedLinks);
  return on;
}

// Mean share of loud links over the detections from `from` on.
double loudShare(const Trace& t, std::size_t from)
{
  double loud = 0.0, all = 0.0;
  for (std::size_t i = from; i < t.loud.size(); ++i)
  {
    loud += static_cast<double>(t.loud[i]);
    all += static_cast<double>(t.detected[i]);
  }
  return all > 0.0 ? loud / all : 1.0;
}
} // namespace

// The grid's loud flags: a pair is tested when one of its links is loud, so the pairs found are
// exactly those of the full search with a loud link, with the same closest points (open and
// periodic, 1 and 3 threads, loud shares from none to all, and loud links only in one corner of
// the cube, where the grid fills the rows of the few cells around them only). Every search runs
// on a fresh grid, so a row it failed to fill would hold no link, not last call's.
TEST(QuietLinks, GridFindsExactlyThePairsWithALoudLink)
{
  const CubeOptions c = periodicCube(2, 14.0, 0.5, 4);
  const FiberModel m = generateCube(c);
  std::vector<CapsuleLink> links;
  buildLinks(m, nullptr, 1, links, nullptr);
  const PeriodicCell cell = cubeCell(c);
  for (bool periodic : { false, true })
  {
    std::vector<CapsulePair> full;
    if (periodic)
      ASSERT_EQ(PeriodicPairs().findPairs(links, cell, 0.0, 1, full), "");
    else
      ASSERT_TRUE(CollisionGrid().findPairs(links, 0.0, 1, full));
    ASSERT_GT(full.size(), 100u);
    // share < 0: the links whose first point lies in a 3 µm corner of the cube.
    for (double share : { 0.0, 0.01, 0.05, 0.3, 1.0, -1.0 })
    {
      RandomStream rng(7);
      std::vector<char> loud(links.size());
      for (std::size_t i = 0; i < links.size(); ++i)
      {
        const Vec3& p = links[i].p0;
        loud[i] = share < 0.0 ? (p.x < 3.0 && p.y < 3.0 && p.z < 3.0 ? 1 : 0)
                              : (rng.uniform() < share ? 1 : 0);
      }
      std::vector<CapsulePair> expected;
      for (const CapsulePair& p : full)
        if (loud[p.a] || loud[p.b])
          expected.push_back(p);
      if (share != 0.0)
      {
        ASSERT_FALSE(expected.empty()) << share;
      }
      for (int threads : { 1, 3 })
      {
        std::vector<CapsulePair> found;
        if (periodic)
          ASSERT_EQ(PeriodicPairs().findPairs(links, cell, 0.0, threads, found,
                      static_cast<std::size_t>(-1), nullptr, nullptr, &loud),
            "");
        else
          ASSERT_TRUE(CollisionGrid().findPairs(links, 0.0, threads, found,
            static_cast<std::size_t>(-1), nullptr, TestedPairs::LowerLink, &loud));
        ASSERT_EQ(found.size(), expected.size()) << periodic << " " << share;
        for (std::size_t i = 0; i < found.size(); ++i)
        {
          EXPECT_EQ(found[i].a, expected[i].a);
          EXPECT_EQ(found[i].b, expected[i].b);
          EXPECT_EQ(std::memcmp(&found[i].s, &expected[i].s, 3 * sizeof(double)), 0);
          EXPECT_EQ(found[i].direction, expected[i].direction);
        }
      }
    }
  }
}

// The same-fiber rule (§3.1): two links of a hairpin that did not move, whose pair the rule
// skipped because the bend between them was short, become loud once the bend is pulled out far
// enough for the rule to test them (then they collide); links that did not move beside an
// unchanged bend stay quiet. Lengths are integers, so every arc length is exact.
TEST(QuietLinks, LinksWhosePairTheSameFiberRuleNoLongerSkipsAreLoud)
{
  const auto hairpin = [](Vec3 bend)
  {
    Fiber f;
    f.points = { { 0, 0, 0 }, { 10, 0, 0 }, bend, { 10, 8, 0 }, { 0, 8, 0 } };
    f.radii.assign(5, 5.0);
    FiberModel m;
    m.fibers.push_back(f);
    return m;
  };
  // Legs 8 apart (< 2·5: the capsules overlap); the arc between them is 5 + 5 = 10 < 2·(5 + 5)
  // with the bend at (13, 4, 0), 13 + 13 = 26 with it at (22, 4, 3).
  const FiberModel before = hairpin({ 13, 4, 0 });
  for (const Vec3& bend : { Vec3{ 13, 4, 0 }, Vec3{ 22, 4, 3 } })
  {
    const bool pulled = bend.x == 22;
    QuietLinks quiet;
    std::vector<CapsuleLink> links;
    quiet.keep(links);
    buildLinks(before, nullptr, 1, links, nullptr);
    EXPECT_EQ(quiet.mark(links, 1), nullptr); // nothing to compare with: all loud
    CollisionGrid grid;
    std::vector<CapsulePair> pairs;
    ASSERT_TRUE(grid.findPairs(links, 0.0, 1, pairs));
    EXPECT_TRUE(pairs.empty()); // the rule skips the legs
    quiet.remember(links.size(), pairs);
    quiet.keep(links);
    buildLinks(hairpin(bend), nullptr, 1, links, nullptr);
    const std::vector<char>* loud = quiet.mark(links, 1);
    ASSERT_NE(loud, nullptr);
    const std::vector<char> expected =
      pulled ? std::vector<char>{ 1, 1, 1, 1 } : std::vector<char>{ 0, 0, 0, 0 };
    EXPECT_EQ(*loud, expected);
    EXPECT_EQ(quiet.loudLinks(), pulled ? 4u : 0u);
    std::vector<CapsulePair> all, skipping;
    ASSERT_TRUE(grid.findPairs(links, 0.0, 1, all));
    ASSERT_TRUE(grid.findPairs(links, 0.0, 1, skipping, static_cast<std::size_t>(-1), nullptr,
      TestedPairs::LowerLink, loud));
    ASSERT_EQ(all.size(), pulled ? 1u : 0u); // the legs, links 0 and 3
    ASSERT_EQ(skipping.size(), all.size());
    if (pulled)
    {
      EXPECT_EQ(skipping[0].a, 0u);
      EXPECT_EQ(skipping[0].b, 3u);
    }
  }
}

// (a) A two-population cube at the paper's density, with curvature control (split, merge and the
// curvature moves renumber and move links between detections).
TEST(QuietLinks, TwoPopulationCubeIsSolvedBitForBitAsWithoutSkipping)
{
  CollisionSolverOptions o;
  o.minCurvatureRadius = 4.0;
  o.maxSteps = 400;
  const Trace on = expectSameRuns(paperCube(2, 100, 5), o);
  ASSERT_GT(on.result.steps, 20);
  EXPECT_LT(on.result.loudLinks, on.result.detectedLinks);
}

// (b) A periodic cell: closed fibers, ghost images across the faces.
TEST(QuietLinks, PeriodicCellIsSolvedBitForBitAsWithoutSkipping)
{
  const CubeOptions c = periodicCube(2, 14.0, 0.45, 8);
  CollisionSolverOptions o;
  o.periodicCell = cubeCell(c);
  o.maxSteps = 300;
  o.minCurvatureRadius = 4.0;
  const Trace on = expectSameRuns(generateCube(c), o);
  ASSERT_GT(on.result.steps, 20);
  EXPECT_LT(on.result.loudLinks, on.result.detectedLinks);
}

// (c) A dense strip of overlapping fibers beside a sparse region that is solved from the start:
// the strip pushes into its neighbours for many steps. Late in the run only the strip and the
// links it reaches are loud.
TEST(QuietLinks, QuietRegionBesideACollidingStripSkipsMostLinks)
{
  FiberModel m;
  std::int64_t id = 0;
  for (int layer = -1; layer <= 1; ++layer) // sparse: 3 µm apart, r = 1, no overlap
    for (int j = 0; j < 60; ++j)
      m.fibers.push_back(line({ 0, 3.0 * j, 3.0 * layer }, { 2, 0, 0 }, 21, 1.0, id++));
  for (int j = 0; j < 8; ++j) // dense: 1 µm apart, overlapping
    for (int l = 0; l < 3; ++l)
      m.fibers.push_back(
        line({ 0.5, 181.0 + 1.0 * j, 1.0 * l - 1.0 + 0.1 * (j % 2) }, { 2, 0, 0 }, 21, 1.0, id++));
  CollisionSolverOptions o;
  o.maxSteps = 3000;
  const Trace on = expectSameRuns(m, o);
  EXPECT_TRUE(on.result.solved);
  ASSERT_GT(on.result.steps, 100);
  ASSERT_EQ(on.loud.size(), static_cast<std::size_t>(on.result.steps));
  // The start's detection tests every link and finds pairs in the strip only: at the first step
  // the strip's 24 fibers of 20 links are loud, the sparse region is quiet.
  EXPECT_EQ(on.loud.front(), 24u * 20u);
  EXPECT_EQ(on.detected.front(), 204u * 20u);
  EXPECT_LT(loudShare(on, on.loud.size() / 2), 0.2);
  EXPECT_LT(on.loud.back(), on.detected.back() / 5);
}

// (d) A hairpin: its legs are one fiber, the same-fiber rule (§3.1) decides by the arc length
// between them, which changes as the bend moves; with Fixed ends some colliding links never move.
TEST(QuietLinks, HairpinIsSolvedBitForBitAsWithoutSkipping)
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
  m.fibers.push_back(line({ -3, 0.5, 3 }, { 1, 0, 0 }, 18, 0.6, 1)); // solved neighbour
  CollisionSolverOptions o;
  o.segmentLength = 1.0;
  o.maxSteps = 2000;
  const Trace on = expectSameRuns(m, o);
  EXPECT_TRUE(on.result.solved);
  EXPECT_LT(on.result.loudLinks, on.result.detectedLinks);
  o.endPoints = EndPointRule::Fixed;
  o.minCurvatureRadius = 1.0;
  o.maxSteps = 300;
  expectSameRuns(m, o);
}

// Radius growth changes every capsule between detections; a resumed run starts loud.
TEST(QuietLinks, RadiusGrowthAndResumeAreBitForBitAsWithoutSkipping)
{
  const CubeOptions c = periodicCube(1, 14.0, 0.5, 11);
  CollisionSolverOptions o;
  o.periodicCell = cubeCell(c);
  o.initialRadiusScale = 0.9;
  o.maxSteps = 200;
  expectSameRuns(generateCube(c), o);

  CollisionSolverOptions p;
  p.maxSteps = 120;
  p.drag = 0.3;
  const FiberModel in = paperCube(2, 60, 9);
  FiberModel reference = in;
  p.quietLinks = false;
  const CollisionSolverResult r1 = solveCollisions(reference, p);
  p.quietLinks = true;
  FiberModel m = in;
  CollisionSolverState saved;
  {
    CollisionSolverRun run(m, p);
    ASSERT_TRUE(run.start());
    while (run.state().steps < 50 && run.step())
    {
    }
    saved = run.state();
  }
  CollisionSolverRun resumed(m, p);
  ASSERT_EQ(resumed.resume(saved), "");
  ASSERT_TRUE(resumed.step());
  EXPECT_EQ(resumed.loudLinks(), resumed.detectedLinks()); // no last detection: all loud
  while (resumed.step())
  {
  }
  const CollisionSolverResult r2 = resumed.finish();
  EXPECT_TRUE(bitwiseEqual(m, reference));
  EXPECT_EQ(r2.steps, r1.steps);
  EXPECT_EQ(r2.collisions, r1.collisions);
}

// The runs of each fiber's links as the link builder hands them to mark() give the flags that
// mark() finds by itself: an unchanged fiber is quiet, a moved point makes its two links loud, a
// fiber that gained a link keeps its unchanged links quiet, and a fiber with no links then is loud.
TEST(QuietLinks, TheBuildersFiberRunsGiveTheFlagsOfAPassOverTheLinks)
{
  const auto straight = [](double y, int points)
  {
    Fiber f;
    for (int i = 0; i < points; ++i)
    {
      f.points.push_back({ 2.0 * i, y, 0.0 });
      f.radii.push_back(0.5);
    }
    return f;
  };
  FiberModel before;
  before.fibers = { straight(0.0, 6), straight(5.0, 6), straight(10.0, 6), straight(15.0, 1) };
  FiberModel after = before;
  after.fibers[1].points[3].z = 0.25;                    // links 2 and 3 of fiber 1
  after.fibers[2].points.push_back({ 12.0, 10.0, 0.0 }); // fiber 2 gains link 5
  after.fibers[2].radii.push_back(0.5);
  after.fibers[3] = straight(15.0, 3); // fiber 3 had no link
  const std::vector<char> expected{ 0, 0, 0, 0, 0, /**/ 0, 0, 1, 1, 0, /**/ 0, 0, 0, 0, 0, 1,
    /**/ 1, 1 };
  for (bool given : { true, false })
  {
    QuietLinks quiet;
    std::vector<CapsuleLink> links;
    std::vector<std::size_t> runs;
    buildLinks(before, nullptr, 1, links, nullptr, nullptr, 1.0, &runs);
    EXPECT_EQ(runs, (std::vector<std::size_t>{ 0, 5, 10, 15 }));
    quiet.keep(links);
    quiet.mark(links, 1, given ? &runs : nullptr);
    quiet.remember(links.size(), {}); // no pair collided
    quiet.keep(links);
    buildLinks(after, nullptr, 1, links, nullptr, nullptr, 1.0, &runs);
    EXPECT_EQ(runs, (std::vector<std::size_t>{ 0, 5, 10, 16, 18 }));
    const std::vector<char>* loud = quiet.mark(links, 1, given ? &runs : nullptr);
    ASSERT_NE(loud, nullptr);
    EXPECT_EQ(*loud, expected) << (given ? "runs given" : "runs found");
    EXPECT_EQ(quiet.loudLinks(), 5u);
  }
}
