/// LinkExchange: the pair work of the distributed collision solver, by tester box (docs/solver.md
/// §13). Fibers stay owned whole (Solver/Decomposition.h), but pairs are found among links: every
/// step each owner sends each of its links to every rank whose tester box, grown by how far any
/// link reaches out of its own, comes within reach of it. A pair is tested by exactly one rank
/// (testedPairs): without a cell the lower of its two links' tester boxes (BoxLayout::testerOf:
/// the box holding the link's centre; lower in rank order), so a rank needs the links of higher
/// boxes only; in a periodic cell the box of its lower link (in global link order). That rank
/// holds every partner of its links. It sends the pair's pushes back to the owners of the two
/// links, and they add them in pair order, as the serial solver does (§4.4). A rank holds its
/// owned fibers and the links near its box, a shell, not whole fibers; it exchanges links and
/// pushes with its partners only, ranks whose boxes are within reach.
#pragma once

#include "Index/CollisionGrid.h"
#include "Model/FiberModel.h"
#include "Parallel/Comm.h"
#include "Solver/Decomposition.h"

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace fiberpli
{

/// HeldLinkInfo::local of a link whose fiber another rank owns.
constexpr std::uint32_t kNotOwned = UINT32_MAX;

/// Global link order (of fiber, then link index), as one integer: the merge of held links
/// (exchangeLinks) and the merge of pushes (forPushesInPairOrder) must agree on it.
inline std::uint64_t linkKey(std::uint32_t fiber, std::uint32_t k)
{
  return (static_cast<std::uint64_t>(fiber) << 32) | k;
}

/// What a rank knows of each link it holds, besides its capsule. pointRadius and owner are set
/// only for the links of other ranks' fibers (local kNotOwned): this rank's own are its model's
/// and its own, and leaving them unwritten spares the exchange a tenth of what it writes.
struct HeldLinkInfo
{
  std::vector<double> pointRadius;  ///< the smaller radius of the link's two points (unscaled)
  std::vector<int> owner;           ///< the rank owning the link's fiber
  std::vector<std::uint32_t> local; ///< the fiber's index in this rank's model, or kNotOwned
  std::vector<char> tested; ///< 1: a link of this rank's tester box (testedPairs says which of its
                            ///< pairs the rank tests)
  /// The first held link of each fiber's links (they are consecutive: global link order), + the
  /// total.
  std::vector<std::size_t> fiberRuns;
  std::size_t received = 0; ///< the held links of other ranks' fibers (local kNotOwned)
};

/// Which pairs a rank tests among the links it holds (HeldLinkInfo::tested flags its own tester
/// box's): without a cell every pair with a flagged link (a rank holds besides them only links of
/// higher boxes, exchangeLinks), in a periodic cell those whose lower link is flagged (the cell
/// has no lowest box; its ghost images rely on that rule, Index/PeriodicPairs.h).
inline TestedPairs testedPairs(const BoxLayout& layout)
{
  return layout.periodic() ? TestedPairs::LowerLink : TestedPairs::EitherLink;
}

/// A link's capsule radius from its points' radii at radius scale `scale` (radius growth); the
/// solver's links and the received ones use this one formula, so they have the same bits.
double capsuleRadius(double r0, double r1, double scale);

/// exchangeLinks routes a fiber's links (without a cell) in blocks of this many consecutive links.
constexpr std::size_t kLinkBlock = 16;

/// The blocks of a fiber with `links` links (the last one may be shorter).
inline std::size_t linkBlockCount(std::size_t links)
{
  return (links + kLinkBlock - 1) / kLinkBlock;
}

/// The bounding box of the points of a block of links.
struct BlockBox
{
  Vec3 lo, hi;
};

/// The boxes of the blocks of the first `links` links of a fiber with points p (block b: links
/// kLinkBlock·b, … and their points), in order; `out` is overwritten, its capacity kept. Returns
/// the box of all of them (of points 0, …, links; an empty box without links).
BlockBox linkBlockBoxes(const Vec3* p, std::size_t links, std::vector<BlockBox>& out);

/// A block of consecutive own links of one fiber as exchangeLinks routes them: up to kLinkBlock,
/// or all of a fiber's links when they lie in one tester box.
struct LinkBlock
{
  std::uint32_t f, k0, k1; ///< links k0, …, k1 − 1 of fiber f
  bool inside;             ///< in tester layers `layer`, by the rounding margin
  int layer[3];
  Vec3 lo, hi; ///< the bounding box of its points
};

/// What exchangeLinks builds per own link and block every step, kept from call to call by the
/// caller: at millions of links these are tens of megabytes, which allocated afresh every step had
/// every page faulted in again.
struct LinkExchangeBuffers
{
  std::vector<int> tester;            ///< per own link, the box testing its pairs
  std::vector<Vec3> shift;            ///< per own link in a periodic cell, its wrap
  std::vector<LinkBlock> blocks;      ///< the own links in blocks (without a cell)
  std::vector<std::vector<char>> out; ///< per rank, the runs (later the pushes) sent to it
  std::vector<std::vector<char>> in;  ///< per rank, the runs (later the pushes) it sent here
  /// Per fiber of the model, its blocks' boxes (linkBlockBoxes of its own links), for the caller
  /// to fill while it has the final points of a step at hand (the solver's shape control): the
  /// routing then reads two corners per block instead of a pass over all own points. Read by the
  /// next exchangeLinks only if blockBoxesCurrent, which that call clears (they describe the
  /// points of one moment); whoever changes the points before it must clear it too.
  std::vector<std::vector<BlockBox>> blockBoxes;
  std::vector<BlockBox> fiberBoxes; ///< per fiber, the box of all its blocks (what linkBlockBoxes
                                    ///< returns), current with blockBoxes
  bool blockBoxesCurrent = false;
};

/// Sends every owned link to every rank whose tester box, grown by how far any link reaches beyond
/// the faces of its own tester box, comes within `reach` of the link's bounding box (modulo the
/// cell), without a cell only to the ranks of its own tester box and lower ones (testedPairs).
/// The links and pushes go to `partners` only (set here, ascending, without this rank): the ranks
/// whose tester box comes within reach of this rank's owner box grown by how far any fiber reaches
/// beyond its owner's box, or whose owner box does so with this rank's tester box; every rank
/// computes the same symmetric relation from the boxes and four maxima per axis. The owned links
/// are those buildLinks(model, active, …, closed, scale) makes, read from the model as they are
/// routed (no list of them is built); global: the fibers' global indices, ascending (so the
/// owned links are in global link order). Consecutive links of a fiber travel as one run of
/// points (about 32 bytes a link). Returns in `held` (CapsuleLink::fiber = global fiber index,
/// in global link order, merged from the senders' runs and this rank's own, which have the bits
/// buildLinks gives them; the buffers' capacity is kept) and `info` what this rank holds: with
/// reach at least 2·ρmax + gap every colliding partner of a link tested here is held here.
/// Collective (a maximum of 12 values, one exchange with the partners); returns what was sent to
/// other ranks. buffers: the routing tables' storage, reused between calls (null: a call's own).
TrafficCount exchangeLinks(const FiberModel& model, const std::vector<char>* active,
  const std::vector<char>* closed, const std::vector<std::int64_t>& global, double scale,
  const BoxLayout& layout, double reach, Comm& comm, std::vector<CapsuleLink>& held,
  HeldLinkInfo& info, std::vector<int>& partners, LinkExchangeBuffers* buffers = nullptr);

/// The pushes of one pair on the end points of its links (§4.1): link a (fiber, k) gets a0 and
/// a1, link b gets b0 and b1. Pair order is that of (fiberA, kA, fiberB, kB).
struct LinkPairPush
{
  std::uint32_t fiberA = 0, kA = 0, fiberB = 0, kB = 0;
  std::int32_t ownerA = 0, ownerB = 0; ///< the ranks owning the two fibers
  Vec3 a0, a1, b0, b1;
};

/// The model indices on this rank of the fibers of a tested pair's two links (kNotOwned: another
/// rank's, the one its LinkPairPush names).
struct PairLocals
{
  std::uint32_t a = kNotOwned, b = kNotOwned;
};

/// A push another tester sent here, with the model indices on this rank of its links' fibers
/// (kNotOwned: that side was not sent here, its fiber is another rank's).
struct ReceivedPush
{
  LinkPairPush push;
  std::uint32_t localA = kNotOwned, localB = kNotOwned;
};

/// Sends every tested pair's pushes to the owners of its two links on other ranks (each owner
/// its side; both sides once when one rank owns both) and returns in `received` (per sender, the
/// buffers reused) the pushes other ranks tested on this rank's links, each sender's in pair
/// order (a side not received is zero). `tested` must be in pair order, `locals` its pairs' fibers
/// on this rank (a side with a local fiber stays here); global: this rank's fibers' global indices,
/// ascending; partners: those of the exchangeLinks that sent the links. Collective; `sent` counts
/// what went to other ranks. buffers (optional): its `out` holds the buffers sent, reused between
/// calls (early in a solve they are tens of megabytes a step).
void returnPushes(const std::vector<LinkPairPush>& tested, const std::vector<PairLocals>& locals,
  const std::vector<std::int64_t>& global, const std::vector<int>& partners, Comm& comm,
  TrafficCount& sent, std::vector<std::vector<ReceivedPush>>& received,
  LinkExchangeBuffers* buffers = nullptr);

/// Every push on this rank's links in pair order, as the serial solver adds them (§4.4):
/// take(push, fa, fb) with the model indices of its links' fibers (kNotOwned: another rank's).
/// The pairs this rank tested (tested[i], its fibers here locals[i]) with a link of this rank are
/// merged with those received: every tester sends in pair order, the global one (its held links
/// are in global link order), and each pair comes from one tester only.
template <class Take>
void forPushesInPairOrder(const std::vector<LinkPairPush>& tested,
  const std::vector<PairLocals>& locals, const std::vector<std::vector<ReceivedPush>>& received,
  Take take)
{
  using Key = std::pair<std::uint64_t, std::uint64_t>;
  const auto key = [](const LinkPairPush& x)
  { return Key(linkKey(x.fiberA, x.kA), linkKey(x.fiberB, x.kB)); };
  const auto mine = [&locals](std::size_t i)
  { return locals[i].a != kNotOwned || locals[i].b != kNotOwned; };
  // Each sender's next key is kept; only the senders with records left are searched (a rank
  // hears from its partners only, a few of R).
  std::vector<std::size_t> at(received.size(), 0); // next record of each sender
  std::vector<Key> next(received.size());          // its key
  std::vector<std::size_t> live;                   // the senders with records left
  for (std::size_t q = 0; q < received.size(); ++q)
  {
    if (!received[q].empty())
    {
      next[q] = key(received[q][0].push);
      live.push_back(q);
    }
  }
  const std::size_t n = tested.size();
  std::size_t i = 0; // next pair tested here
  for (;;)
  {
    std::size_t from = SIZE_MAX; // the sender with the least next pair, SIZE_MAX: none left
    std::size_t where = 0;       // its place in live
    for (std::size_t j = 0; j < live.size(); ++j)
    {
      if (from == SIZE_MAX || next[live[j]] < next[from])
      {
        from = live[j];
        where = j;
      }
    }
    if (from == SIZE_MAX) // the rest are this rank's own tests: no key to compare
    {
      for (; i < n; ++i)
        if (mine(i))
          take(tested[i], locals[i].a, locals[i].b);
      return;
    }
    // Most pairs are tested by the rank owning their links: the run of own tests before the
    // next received pair goes in one loop.
    for (; i < n; ++i)
    {
      if (!mine(i))
        continue;
      if (next[from] < key(tested[i]))
        break;
      take(tested[i], locals[i].a, locals[i].b);
    }
    const ReceivedPush& r = received[from][at[from]++];
    if (at[from] < received[from].size())
      next[from] = key(received[from][at[from]].push);
    else
      live.erase(live.begin() + static_cast<std::ptrdiff_t>(where));
    take(r.push, r.localA, r.localB);
  }
}

} // namespace fiberpli
