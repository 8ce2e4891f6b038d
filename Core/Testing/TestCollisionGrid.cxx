// Uniform-grid collision detection (docs/solver.md §3, tests 9–13 of §10) against an
// independent O(N²) reference.
#include "Index/CollisionGrid.h"
#include "Index/PeriodicPairs.h"
#include "Solver/PairBound.h"

#include "BruteForceOverlap.h"
#include "Tissue/CubeGenerator.h"
#include "Util/Random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

using namespace fiberpli;

namespace
{
std::vector<CapsuleLink> linksOf(const FiberModel& m)
{
  std::vector<CapsuleLink> out;
  for (const auto& r : fiberpli_test::refLinks(m))
  {
    CapsuleLink l;
    l.p0 = r.p0;
    l.p1 = r.p1;
    l.rho = r.rho;
    l.fiber = static_cast<std::uint32_t>(r.fiber);
    l.k = static_cast<std::uint32_t>(r.k);
    l.arc0 = r.arc0;
    l.arc1 = r.arc1;
    out.push_back(l);
  }
  return out;
}

std::vector<std::pair<std::size_t, std::size_t>> pairIds(const std::vector<CapsulePair>& pairs)
{
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (const CapsulePair& p : pairs)
    out.emplace_back(p.a, p.b);
  return out;
}

std::vector<std::pair<std::size_t, std::size_t>> gridPairs(
  const FiberModel& m, int threads = 1, double gap = 0.0)
{
  CollisionGrid grid;
  std::vector<CapsulePair> pairs;
  grid.findPairs(linksOf(m), gap, threads, pairs);
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (const CapsulePair& p : pairs)
    out.emplace_back(p.a, p.b);
  return out;
}

Fiber fiber(std::vector<Vec3> pts, double r, std::int64_t id = 0)
{
  Fiber f;
  f.points = std::move(pts);
  f.radii.assign(f.points.size(), r);
  f.id = id;
  return f;
}
} // namespace

TEST(CollisionGrid, TouchingIsNotColliding)
{
  for (double d : { 1.0, 1.0 - 1e-9 })
  {
    FiberModel m;
    m.fibers.push_back(fiber({ { -1, 0, 0 }, { 1, 0, 0 } }, 0.5, 0));
    m.fibers.push_back(fiber({ { 0, -1, d }, { 0, 1, d } }, 0.5, 1));
    EXPECT_EQ(gridPairs(m).size(), d == 1.0 ? 0u : 1u) << d;
  }
}

TEST(CollisionGrid, AdjacentLinksNeverCollide)
{
  FiberModel straight;
  std::vector<Vec3> pts;
  for (int i = 0; i <= 20; ++i)
    pts.push_back({ double(i), 0, 0 });
  straight.fibers.push_back(fiber(pts, 2.0));
  EXPECT_TRUE(gridPairs(straight).empty());

  FiberModel zigzag;
  pts.clear();
  for (int i = 0; i <= 20; ++i)
    pts.push_back({ double((i + 1) / 2), double(i / 2), 0 }); // 90° corners, links of 1
  zigzag.fibers.push_back(fiber(pts, 2.0));
  EXPECT_TRUE(gridPairs(zigzag).empty());
  EXPECT_TRUE(fiberpli_test::refPairs(fiberpli_test::refLinks(zigzag)).empty());
}

TEST(CollisionGrid, HairpinCollidesWithItself)
{
  std::vector<Vec3> pts;
  for (int i = 0; i <= 10; ++i)
    pts.push_back({ double(i), 0, 0 });
  pts.push_back({ 10.5, 0.5, 0 });
  for (int i = 0; i <= 10; ++i)
    pts.push_back({ 10.0 - i, 1, 0 });
  FiberModel m;
  m.fibers.push_back(fiber(pts, 0.6));
  const auto pairs = gridPairs(m);
  EXPECT_GT(pairs.size(), 10u);
  EXPECT_EQ(pairs, fiberpli_test::refPairs(fiberpli_test::refLinks(m)));
}

TEST(CollisionGrid, RandomCapsulesMatchBruteForce)
{
  FiberModel m;
  RandomStream rng(11, 0, 0);
  for (int i = 0; i < 500; ++i)
  {
    const Vec3 a{ rng.uniform(0, 20), rng.uniform(0, 20), rng.uniform(0, 20) };
    const Vec3 d{ rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2) };
    Fiber f = fiber({ a, a + d }, 0.3, i);
    f.radii[1] = rng.uniform(0.2, 0.8);
    m.fibers.push_back(f);
  }
  // A few oversize links take the grid's fallback path.
  m.fibers.push_back(fiber({ { 0, 0, 0 }, { 20, 20, 20 } }, 0.5, 500));
  m.fibers.push_back(fiber({ { 20, 0, 0 }, { 0, 20, 20 } }, 0.5, 501));
  const auto ref = fiberpli_test::refPairs(fiberpli_test::refLinks(m));
  EXPECT_GT(ref.size(), 50u);
  EXPECT_EQ(gridPairs(m, 1), ref);
  EXPECT_EQ(gridPairs(m, 2), ref);
  const auto refGap = fiberpli_test::refPairs(fiberpli_test::refLinks(m), 0.25);
  EXPECT_GT(refGap.size(), ref.size());
  EXPECT_EQ(gridPairs(m, 2, 0.25), refGap);
}

TEST(CollisionGrid, ManyLocalOversizeLinksMatchBruteForceWithAnyFlags)
{
  // Polydisperse links: one in eighty is thick (radius 2.5 instead of 0.3–0.6), so its box
  // is over twice the median edge (oversize) but spans only a few cells of the 40 µm box: the
  // oversize path must search the cells around it, not the whole grid. Checked against the
  // brute-force pairs, unflagged, with loud flags (pairs with a loud link) and with tested flags
  // under both rules, on 1 and 2 threads.
  FiberModel m;
  RandomStream rng(17, 3, 0);
  for (int i = 0; i < 3000; ++i)
  {
    const Vec3 a{ rng.uniform(0, 40), rng.uniform(0, 40), rng.uniform(0, 40) };
    const Vec3 d{ rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1) };
    const double r = i % 80 == 0 ? 2.5 : rng.uniform(0.3, 0.6);
    m.fibers.push_back(fiber({ a, a + d }, r, i));
  }
  const std::vector<CapsuleLink> links = linksOf(m);
  const auto ref = fiberpli_test::refPairs(fiberpli_test::refLinks(m));
  std::size_t thickPairs = 0;
  for (const auto& p : ref)
    thickPairs += (p.first % 80 == 0) + (p.second % 80 == 0);
  ASSERT_GT(thickPairs, 80u);
  std::vector<char> flags(links.size());
  for (char& c : flags)
    c = rng.uniform(0, 1) < 0.3 ? 1 : 0;
  using Ids = std::vector<std::pair<std::size_t, std::size_t>>;
  Ids withLoud, lowerTested, eitherTested;
  for (const auto& p : ref)
  {
    if (flags[p.first] || flags[p.second])
      withLoud.push_back(p);
    if (flags[p.first])
      lowerTested.push_back(p);
  }
  eitherTested = withLoud;
  ASSERT_LT(withLoud.size(), ref.size());
  for (int threads : { 1, 2 })
  {
    CollisionGrid grid;
    std::vector<CapsulePair> pairs;
    ASSERT_TRUE(grid.findPairs(links, 0.0, threads, pairs));
    EXPECT_EQ(pairIds(pairs), ref);
    ASSERT_TRUE(grid.findPairs(links, 0.0, threads, pairs, static_cast<std::size_t>(-1), nullptr,
      TestedPairs::LowerLink, &flags));
    EXPECT_EQ(pairIds(pairs), withLoud);
    ASSERT_TRUE(grid.findPairs(
      links, 0.0, threads, pairs, static_cast<std::size_t>(-1), &flags, TestedPairs::LowerLink));
    EXPECT_EQ(pairIds(pairs), lowerTested);
    ASSERT_TRUE(grid.findPairs(
      links, 0.0, threads, pairs, static_cast<std::size_t>(-1), &flags, TestedPairs::EitherLink));
    EXPECT_EQ(pairIds(pairs), eitherTested);
  }
}

TEST(CollisionGrid, CubeMatchesBruteForceAndIsTranslationInvariant)
{
  CubeOptions o;
  o.numberOfFibers = 200;
  o.populations = 3;
  o.edgeLength = std::sqrt(3.0) * 30.0 * std::sqrt(0.2);
  o.seed = 3;
  FiberModel m = generateCube(o);
  const auto ref = fiberpli_test::refPairs(fiberpli_test::refLinks(m));
  EXPECT_GT(ref.size(), 100u);
  EXPECT_EQ(gridPairs(m, 1), ref);
  EXPECT_EQ(gridPairs(m, 3), ref);
  for (Fiber& f : m.fibers)
    for (Vec3& p : f.points)
      p += Vec3{ 1000, -500, 3 };
  EXPECT_EQ(gridPairs(m, 2), ref);
}

TEST(CollisionGrid, ReusedGridGivesTheSameAnswerAsAFreshOne)
{
  // The grid starts its sort from the previous call's order; the result must not depend on it.
  CubeOptions o;
  o.numberOfFibers = 100;
  o.populations = 2;
  o.edgeLength = std::sqrt(3.0) * 30.0 * std::sqrt(0.1);
  o.seed = 9;
  FiberModel m = generateCube(o);
  CollisionGrid grid;
  std::vector<CapsulePair> pairs;
  RandomStream rng(9, 9, 9);
  for (int round = 0; round < 4; ++round)
  {
    grid.findPairs(linksOf(m), 0.0, 2, pairs);
    std::vector<std::pair<std::size_t, std::size_t>> got;
    for (const CapsulePair& p : pairs)
      got.emplace_back(p.a, p.b);
    EXPECT_EQ(got, fiberpli_test::refPairs(fiberpli_test::refLinks(m))) << round;
    // Small moves (the solver's case), then a full reshuffle of the fibers (same link count).
    for (Fiber& f : m.fibers)
      for (Vec3& p : f.points)
        p += Vec3{ rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2), rng.uniform(-0.2, 0.2) };
    if (round == 2)
      std::reverse(m.fibers.begin(), m.fibers.end());
  }
}

TEST(CollisionGrid, SparseAndDenseGridsGiveTheBruteForcePairs)
{
  // Links sort by cell by counting when the grid has at most 2 cells per link, else by keys
  // (docs/solver.md §3.3). Two clusters 1 mm apart make a grid of ~10^6 cells for 600 links
  // (keys); one cluster alone a dense one (counting). One grid object alternates between them.
  const auto cluster = [](FiberModel& m, const Vec3& at, std::uint64_t seed)
  {
    RandomStream rng(seed, 0, 0);
    for (int i = 0; i < 300; ++i)
    {
      const Vec3 a = at + Vec3{ rng.uniform(0, 15), rng.uniform(0, 15), rng.uniform(0, 15) };
      const Vec3 d{ rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2) };
      m.fibers.push_back(fiber({ a, a + d, a + 2.0 * d }, rng.uniform(0.2, 0.6),
        static_cast<std::int64_t>(m.fibers.size())));
    }
  };
  FiberModel dense, sparse;
  cluster(dense, { 0, 0, 0 }, 5);
  cluster(sparse, { 0, 0, 0 }, 5);
  cluster(sparse, { 1000, 1000, 1000 }, 6);
  CollisionGrid grid;
  for (const FiberModel* m : { &dense, &sparse, &dense, &sparse })
  {
    const auto ref = fiberpli_test::refPairs(fiberpli_test::refLinks(*m));
    ASSERT_GT(ref.size(), 50u);
    for (int threads : { 1, 2 })
    {
      std::vector<CapsulePair> pairs;
      ASSERT_TRUE(grid.findPairs(linksOf(*m), 0.0, threads, pairs));
      EXPECT_EQ(pairIds(pairs), ref) << m->fibers.size() << " fibers, " << threads << " threads";
    }
  }
}

TEST(CollisionGrid, StopsExactlyWhenThePairsExceedTheLimit)
{
  // 20 parallel fibers 1 µm apart with radius 0.8: every neighbour pair collides. The reference
  // count is the limit where findPairs switches from "all found" to "refused", for any threads.
  FiberModel m;
  for (int i = 0; i < 20; ++i)
    m.fibers.push_back(
      fiber({ { 0, double(i), 0 }, { 2, double(i), 0 }, { 4, double(i), 0 }, { 6, double(i), 0 } },
        0.8, i));
  const std::vector<CapsuleLink> links = linksOf(m);
  const std::size_t expected = fiberpli_test::refPairs(fiberpli_test::refLinks(m)).size();
  ASSERT_GT(expected, 40u);
  for (int threads : { 1, 2, 3 })
  {
    CollisionGrid grid;
    std::vector<CapsulePair> pairs;
    EXPECT_TRUE(grid.findPairs(links, 0.0, threads, pairs, expected));
    EXPECT_EQ(pairs.size(), expected);
    EXPECT_FALSE(grid.findPairs(links, 0.0, threads, pairs, expected - 1));
    EXPECT_TRUE(pairs.empty());
    EXPECT_TRUE(grid.findPairs(links, 0.0, threads, pairs, expected)); // reusable after a refusal
    EXPECT_EQ(pairs.size(), expected);
  }
}

TEST(CollisionGrid, LowerOnlyFindsExactlyThePairsWhoseLowerLinkIsMarked)
{
  // Random marks; the reference is the brute-force list restricted to marked lower links, in the
  // open space and (against the unrestricted periodic finder) in a cell. The limit counts only
  // the marked pairs.
  FiberModel m;
  RandomStream rng(5, 1, 2);
  for (int i = 0; i < 400; ++i)
  {
    const Vec3 a{ rng.uniform(0, 16), rng.uniform(0, 16), rng.uniform(0, 16) };
    const Vec3 d{ rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2) };
    m.fibers.push_back(fiber({ a, a + d, a + 2.0 * d }, 0.4, i));
  }
  m.fibers.push_back(fiber({ { 0, 0, 0 }, { 16, 16, 16 } }, 0.5, 400)); // oversize path
  const std::vector<CapsuleLink> links = linksOf(m);
  std::vector<char> marked(links.size());
  for (char& c : marked)
    c = rng.uniform(0, 1) < 0.4 ? 1 : 0;
  marked.back() = 1;
  std::vector<std::pair<std::size_t, std::size_t>> expected;
  for (const auto& p : fiberpli_test::refPairs(fiberpli_test::refLinks(m)))
    if (marked[p.first])
      expected.push_back(p);
  ASSERT_GT(expected.size(), 50u);
  for (int threads : { 1, 2 })
  {
    CollisionGrid grid;
    std::vector<CapsulePair> pairs;
    EXPECT_TRUE(grid.findPairs(links, 0.0, threads, pairs, expected.size(), &marked));
    EXPECT_EQ(pairIds(pairs), expected);
    EXPECT_FALSE(grid.findPairs(links, 0.0, threads, pairs, expected.size() - 1, &marked));
  }
  PeriodicCell cell;
  cell.lo = { 0, 0, 0 };
  cell.hi = { 16, 16, 16 };
  std::vector<CapsuleLink> inCell(links.begin(), links.end() - 1); // without the oversize link
  marked.pop_back();
  PeriodicPairs finder;
  std::vector<CapsulePair> all, some;
  ASSERT_EQ(finder.findPairs(inCell, cell, 0.0, 2, all), "");
  ASSERT_EQ(
    finder.findPairs(inCell, cell, 0.0, 2, some, static_cast<std::size_t>(-1), nullptr, &marked),
    "");
  std::vector<std::pair<std::size_t, std::size_t>> restricted;
  for (const auto& p : pairIds(all))
    if (marked[p.first])
      restricted.push_back(p);
  EXPECT_GT(restricted.size(), expected.size()); // pairs across the faces too
  EXPECT_EQ(pairIds(some), restricted);
  for (std::size_t i = 0; i < some.size(); ++i) // the same closest points as unrestricted
  {
    const auto it = std::find_if(all.begin(), all.end(),
      [&](const CapsulePair& p) { return p.a == some[i].a && p.b == some[i].b; });
    ASSERT_NE(it, all.end());
    EXPECT_EQ(it->distance, some[i].distance);
    EXPECT_EQ(it->direction, some[i].direction);
  }
}

TEST(CollisionGrid, PackingBoundAdmitsDenseStartsButNotStacks)
{
  // Random straight fibers at 4× the paper's density: far below the bound. 200 copies of one
  // fiber: every link collides with ~3 links of each copy, above it.
  CubeOptions o;
  o.numberOfFibers = 500;
  o.populations = 3;
  o.edgeLength = std::sqrt(3.0) * 30.0 * std::sqrt(0.5) / 2.0;
  const FiberModel dense = generateCube(o);
  const std::vector<CapsuleLink> denseLinks = linksOf(dense);
  const double denseCount =
    static_cast<double>(fiberpli_test::refPairs(fiberpli_test::refLinks(dense)).size());
  EXPECT_LT(denseCount, 0.5 * packingPairBound(denseLinks, 0.0).pairs);

  FiberModel stack;
  for (int i = 0; i < 200; ++i)
    stack.fibers.push_back(
      fiber({ { 0, 0, 0 }, { 2, 0, 0 }, { 4, 0, 0 }, { 6, 0, 0 }, { 8, 0, 0 } }, 0.8, i));
  const std::vector<CapsuleLink> stackLinks = linksOf(stack);
  const double stackCount =
    static_cast<double>(fiberpli_test::refPairs(fiberpli_test::refLinks(stack)).size());
  EXPECT_GT(stackCount, packingPairBound(stackLinks, 0.0).pairs);
}

// The tested flags (with the box tests of two unflagged links left out) find exactly the
// unrestricted pairs whose lower link is flagged (LowerLink) or that have a flagged link
// (EitherLink), for masks by id, by position and in blocks, on 1 and 2 threads; in a periodic
// cell (LowerLink) likewise, the lower link being the smaller real id.
TEST(CollisionGrid, LowerOnlyEqualsTheFilteredPairs)
{
  CubeOptions o;
  o.numberOfFibers = 300;
  o.populations = 3;
  o.edgeLength = 25.0;
  o.seed = 7;
  const std::vector<CapsuleLink> links = linksOf(generateCube(o));
  PeriodicCell cell;
  cell.lo = { -12.5, -12.5, -12.5 };
  cell.hi = { 12.5, 12.5, 12.5 };
  CollisionGrid grid;
  PeriodicPairs finder;
  std::vector<CapsulePair> all, allPeriodic;
  ASSERT_TRUE(grid.findPairs(links, 0.0, 2, all));
  ASSERT_EQ(finder.findPairs(links, cell, 0.0, 2, allPeriodic), "");
  const auto filtered =
    [](const std::vector<CapsulePair>& pairs, const std::vector<char>& mask, bool either = false)
  {
    std::vector<std::pair<std::size_t, std::size_t>> out;
    for (const auto& p : pairIds(pairs))
      if (mask[std::min(p.first, p.second)] || (either && mask[std::max(p.first, p.second)]))
        out.push_back(p);
    return out;
  };
  for (int pattern = 0; pattern < 4; ++pattern)
  {
    std::vector<char> mask(links.size());
    for (std::size_t i = 0; i < links.size(); ++i)
      mask[i] = pattern == 0 ? (i % 7 == 0)
        : pattern == 1       ? (links[i].p0.x + links[i].p1.x < 0.0)
        : pattern == 2       ? (i % 2)
                             : (i < 40);
    for (int threads : { 1, 2 })
    {
      const std::string what =
        "pattern " + std::to_string(pattern) + " threads " + std::to_string(threads);
      std::vector<CapsulePair> got;
      ASSERT_TRUE(grid.findPairs(links, 0.0, threads, got, static_cast<std::size_t>(-1), &mask));
      const auto expected = filtered(all, mask);
      EXPECT_GT(expected.size(), 0u) << what;
      EXPECT_EQ(pairIds(got), expected) << what;
      ASSERT_TRUE(grid.findPairs(
        links, 0.0, threads, got, static_cast<std::size_t>(-1), &mask, TestedPairs::EitherLink));
      const auto expectedEither = filtered(all, mask, true);
      if (pattern != 3) // the first 40 flagged: a flagged link's partner below it is flagged too
      {
        EXPECT_GT(expectedEither.size(), expected.size()) << what;
      }
      EXPECT_EQ(pairIds(got), expectedEither) << what;
      ASSERT_EQ(finder.findPairs(
                  links, cell, 0.0, threads, got, static_cast<std::size_t>(-1), nullptr, &mask),
        "");
      const auto expectedPeriodic = filtered(allPeriodic, mask);
      EXPECT_GT(expectedPeriodic.size(), expected.size()) << what; // pairs across the faces too
      EXPECT_EQ(pairIds(got), expectedPeriodic) << what;
    }
  }
}
