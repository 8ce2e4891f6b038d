// The link exchange of the distributed solver (Solver/LinkExchange.h) where the caller hands it
// the boxes of the blocks of links it routes and of whole fibers: the boxes hold their points,
// and the exchange reads them exactly once, when they are marked current, with the same links
// held as when it takes the boxes itself. The solve as a whole is checked against the serial one in
// TestDistributedSolver.
#include "Solver/LinkExchange.h"

#include "SolverTestModels.h"
#include "ThreadComm.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>

using namespace fiberpli;
using fiberpli_test::runRanks;

namespace
{
// A wavy fiber along y, so that consecutive blocks of links have different boxes.
Fiber wave(double x, double z, int n, std::int64_t id)
{
  Fiber f;
  for (int i = 0; i < n; ++i)
  {
    const double t = 0.5 * i;
    f.points.push_back(Vec3{ x + 0.8 * std::sin(0.3 * t), t, z + 0.5 * std::cos(0.2 * t) });
  }
  f.radii.assign(f.points.size(), 0.4);
  f.id = id;
  return f;
}

// A straight fiber along x from x0 to x1 at (y, z), points 0.5 apart.
Fiber alongX(double x0, double x1, double y, double z, std::int64_t id)
{
  Fiber f;
  for (double x = x0; x <= x1; x += 0.5)
    f.points.push_back(Vec3{ x, y, z });
  f.radii.assign(f.points.size(), 0.4);
  f.id = id;
  return f;
}

// The fibers a rank owns (every other one), with their global indices, of a model of 8 × 4 waves
// along y in x and z (each 0.8 to either side), then 3 straight fibers along x across all of them
// above the waves. It is wider in x than long in y and symmetric about x = 24, so two ranks cut
// it across x between the waves at x = 22.4 and 25.6: every wave lies in one tester box, those
// two within reach of the other box along some of their length, and the straight fibers cross
// the cut.
void ownFibers(int rank, int ranks, FiberModel& local, std::vector<std::int64_t>& global)
{
  std::int64_t g = 0;
  const auto add = [&](Fiber f)
  {
    if (g % ranks == rank)
    {
      local.fibers.push_back(std::move(f));
      global.push_back(g);
    }
    ++g;
  };
  for (double x : { 0.0, 8.0, 16.0, 22.4, 25.6, 32.0, 40.0, 48.0 })
    for (int iz = 0; iz < 4; ++iz)
      add(wave(x, 2.5 * iz, 61, g));
  for (int iy = 0; iy < 3; ++iy)
    add(alongX(-0.5, 48.5, 5.0 + 10.0 * iy, 9.5, g));
}

// One rank's share of the model above and its exchange: the links it holds after exchangeLinks
// with the given buffers (null: the call's own).
struct RankExchange
{
  Comm& comm;
  FiberModel local;
  std::vector<std::int64_t> global;
  BoxLayout layout;

  explicit RankExchange(Comm& c, int ranks)
    : comm(c)
  {
    ownFibers(comm.rank(), ranks, local, global);
    layout = BoxLayout::make(local, PeriodicCell{}, comm);
  }
  std::vector<CapsuleLink> held(LinkExchangeBuffers* buffers)
  {
    const double reach = 2.0 * 0.4 + 0.1; // twice the radius, and a gap
    std::vector<CapsuleLink> links;
    HeldLinkInfo info;
    std::vector<int> partners;
    exchangeLinks(
      local, nullptr, nullptr, global, 1.0, layout, reach, comm, links, info, partners, buffers);
    return links;
  }
};

// What shape control hands the exchange: every fiber's block boxes and its whole box.
void takeBoxes(const FiberModel& local, LinkExchangeBuffers& buffers)
{
  buffers.blockBoxes.resize(local.fibers.size());
  buffers.fiberBoxes.resize(local.fibers.size());
  for (std::size_t f = 0; f < local.fibers.size(); ++f)
    buffers.fiberBoxes[f] = linkBlockBoxes(
      local.fibers[f].points.data(), local.fibers[f].size() - 1, buffers.blockBoxes[f]);
  buffers.blockBoxesCurrent = true;
}

bool sameLinks(const std::vector<CapsuleLink>& a, const std::vector<CapsuleLink>& b)
{
  if (a.size() != b.size())
    return false;
  for (std::size_t i = 0; i < a.size(); ++i)
  {
    if (!(a[i].p0 == b[i].p0) || !(a[i].p1 == b[i].p1) || a[i].rho != b[i].rho ||
      a[i].fiber != b[i].fiber || a[i].k != b[i].k)
      return false;
  }
  return true;
}
} // namespace

TEST(LinkExchange, BlockBoxesHoldTheirBlocksPointsAndTouchThemOnEveryFace)
{
  const Fiber f = wave(1.0, 2.0, 38, 0); // 37 links: blocks of 16, 16 and 5
  std::vector<BlockBox> boxes{ BlockBox{}, BlockBox{}, BlockBox{}, BlockBox{}, BlockBox{} };
  linkBlockBoxes(f.points.data(), 37, boxes);
  ASSERT_EQ(boxes.size(), 3u);
  for (std::size_t b = 0; b < boxes.size(); ++b)
  {
    const std::size_t k0 = 16 * b, k1 = std::min<std::size_t>(37, k0 + 16);
    for (int d = 0; d < 3; ++d)
    {
      bool touchesLo = false, touchesHi = false;
      for (std::size_t k = k0; k <= k1; ++k) // the links' points, the last one included
      {
        EXPECT_LE(boxes[b].lo[d], f.points[k][d]);
        EXPECT_GE(boxes[b].hi[d], f.points[k][d]);
        touchesLo = touchesLo || boxes[b].lo[d] == f.points[k][d];
        touchesHi = touchesHi || boxes[b].hi[d] == f.points[k][d];
      }
      EXPECT_TRUE(touchesLo && touchesHi) << "block " << b << " axis " << d;
    }
  }
  linkBlockBoxes(f.points.data(), 16, boxes);
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_EQ(boxes[0].hi[1], f.points[16][1]); // the block's last point bounds it
  linkBlockBoxes(f.points.data(), 0, boxes);
  EXPECT_TRUE(boxes.empty());
}

TEST(LinkExchange, BlockBoxesReturnTheBoxOfAllTheirPoints)
{
  const Fiber f = wave(1.0, 2.0, 38, 0);
  std::vector<BlockBox> boxes;
  const BlockBox all = linkBlockBoxes(f.points.data(), 37, boxes);
  for (int d = 0; d < 3; ++d)
  {
    double lo = f.points[0][d], hi = f.points[0][d];
    for (const Vec3& p : f.points)
    {
      lo = std::min(lo, p[d]);
      hi = std::max(hi, p[d]);
    }
    EXPECT_EQ(all.lo[d], lo);
    EXPECT_EQ(all.hi[d], hi);
  }
  const BlockBox first = linkBlockBoxes(f.points.data(), 1, boxes); // one link: its two points
  EXPECT_EQ(first.lo[1], f.points[0][1]);
  EXPECT_EQ(first.hi[1], f.points[1][1]);
}

TEST(LinkExchange, GivenBlockBoxesAreReadOnlyWhenCurrentAndOnlyOnce)
{
  constexpr int kRanks = 2;
  std::array<bool, kRanks> sameWithBoxes{}, flagCleared{}, sameWhenNotCurrent{},
    differentWithWrongFiberBoxes{}, differentWithWrongBoxes{};
  runRanks(kRanks,
    [&](Comm& comm)
    {
      const int r = comm.rank();
      RankExchange rank(comm, kRanks);
      const FiberModel& local = rank.local;
      const auto exchange = [&](LinkExchangeBuffers& buffers) { return rank.held(&buffers); };
      LinkExchangeBuffers own;
      const std::vector<CapsuleLink> reference = exchange(own);

      LinkExchangeBuffers given;
      takeBoxes(local, given);
      sameWithBoxes[r] = sameLinks(exchange(given), reference);
      flagCleared[r] = !given.blockBoxesCurrent;

      // Whole-fiber boxes that do not describe the points (each shrunk to its fiber's first point,
      // inside one tester box): the routing believes every fiber lies there, far from the other.
      takeBoxes(local, given);
      for (std::size_t f = 0; f < local.fibers.size(); ++f)
        given.fiberBoxes[f] = BlockBox{ local.fibers[f].points[0], local.fibers[f].points[0] };
      differentWithWrongFiberBoxes[r] = !sameLinks(exchange(given), reference);

      // The blocks' boxes shrunk so too.
      for (std::size_t f = 0; f < local.fibers.size(); ++f)
        for (BlockBox& b : given.blockBoxes[f])
          b = BlockBox{ local.fibers[f].points[0], local.fibers[f].points[0] };
      sameWhenNotCurrent[r] = sameLinks(exchange(given), reference);
      given.blockBoxesCurrent = true;
      differentWithWrongBoxes[r] = !sameLinks(exchange(given), reference);
    });
  for (int r = 0; r < kRanks; ++r)
  {
    EXPECT_TRUE(sameWithBoxes[r]) << "rank " << r;
    EXPECT_TRUE(flagCleared[r]) << "rank " << r;
    EXPECT_TRUE(sameWhenNotCurrent[r]) << "rank " << r;
  }
  // The wrong boxes send fewer links to the other rank: some rank holds different links, which
  // shows that current boxes are what the routing reads, the fibers' as well as the blocks'.
  EXPECT_TRUE(differentWithWrongFiberBoxes[0] || differentWithWrongFiberBoxes[1]);
  EXPECT_TRUE(differentWithWrongBoxes[0] || differentWithWrongBoxes[1]);
}

// The received runs land in the caller's buffers, which keep their storage: a second exchange of
// the same links needs no new memory (under MPI, megabytes a step that would otherwise be fresh
// pages), and the buffers do not change what is held.
TEST(LinkExchange, ReceivesIntoTheCallersBuffersAndKeepsTheirStorage)
{
  constexpr int kRanks = 2;
  std::array<bool, kRanks> received{}, storageKept{}, sameHeld{};
  runRanks(kRanks,
    [&](Comm& comm)
    {
      const int r = comm.rank();
      RankExchange rank(comm, kRanks);
      const auto exchange = [&](LinkExchangeBuffers* buffers) { return rank.held(buffers); };
      const std::vector<CapsuleLink> reference = exchange(nullptr);
      LinkExchangeBuffers buffers;
      const std::vector<CapsuleLink> first = exchange(&buffers);
      const std::vector<char>& fromOther = buffers.in[static_cast<std::size_t>(1 - r)];
      received[r] = !fromOther.empty();
      const char* storage = fromOther.data();
      const std::vector<CapsuleLink> second = exchange(&buffers);
      storageKept[r] = buffers.in[static_cast<std::size_t>(1 - r)].data() == storage;
      sameHeld[r] = sameLinks(first, reference) && sameLinks(second, reference);
    });
  for (int r = 0; r < kRanks; ++r)
  {
    EXPECT_TRUE(received[r]) << "rank " << r << " got no runs from the other: the test is void";
    EXPECT_TRUE(storageKept[r]) << "rank " << r;
    EXPECT_TRUE(sameHeld[r]) << "rank " << r;
  }
}
