#include "Solver/LinkExchange.h"

#include "Util/ByteBuffer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace fiberpli
{

namespace
{
// A run of consecutive links of one fiber as it travels: this header, then its count + 1 points
// and their radii. The receiver rebuilds the capsules exactly as buildLinks made them (arc
// lengths summed from the run's first one in the same order, the same radius formula).
struct RunHeader
{
  std::uint32_t fiber; // global index
  std::uint32_t k0;    // first link
  std::uint32_t count; // links
  double arc0;         // arc length at the run's first point
  double closedLength;
};
// One side or both of a pair's pushes as they travel: this header, then a0, a1 (sides & 1) and
// b0, b1 (sides & 2).
struct PushHeader
{
  std::uint32_t fiberA, kA, fiberB, kB, sides;
};

using Reader = ByteReader;

// The all-to-all of the buffers for other ranks (this rank's own links and pushes never go
// into a buffer: out[me] stays empty).
std::vector<std::vector<char>> exchangeAll(
  const std::vector<std::vector<char>>& out, Comm& comm, TrafficCount& sent)
{
  for (const std::vector<char>& b : out)
    sent.bytes += b.size();
  return comm.exchange(out);
}

// Merges streams of records, each in ascending key order (keys unique across streams), into one
// ascending order without a sort: repeatedly the stream whose next record has the least key
// hands it over. peek(s, key) gives stream s's next key (false: s is done); take(s) consumes
// that record. Each record is peeked once, then taken.
template <class Key, class Peek, class Take>
void mergeStreams(std::size_t streams, Peek peek, Take take)
{
  std::vector<Key> next(streams);
  std::vector<std::size_t> live; // streams with records left
  for (std::size_t s = 0; s < streams; ++s)
  {
    if (peek(s, next[s]))
      live.push_back(s);
  }
  while (!live.empty())
  {
    std::size_t j = 0;
    for (std::size_t i = 1; i < live.size(); ++i)
      j = next[live[i]] < next[live[j]] ? i : j;
    const std::size_t s = live[j];
    take(s);
    if (!peek(s, next[s]))
      live.erase(live.begin() + static_cast<std::ptrdiff_t>(j));
  }
}

// Intervals [a, b] and [c, d] closer than reach, modulo period when period > 0: there is an
// integer k with a − reach + kP <= d and b + reach + kP >= c.
bool within(double a, double b, double c, double d, double reach, double period)
{
  if (period <= 0.0)
  {
    return a - reach <= d && b + reach >= c;
  }
  return std::floor((d - a + reach) / period) >= std::ceil((c - b - reach) / period);
}

double centre(const CapsuleLink& l, int axis)
{
  return 0.5 * (l.p0[axis] + l.p1[axis]);
}

// Calls f(q) for every tester slab q that [a, b] touches (modulo the cell) and one more on each
// side (rounding). In a cell an interval shorter than the cell minus the widest slab cannot wrap
// back into the slab it starts in, so its slabs run cyclically from a's to b's.
// widest: the widest tester slab.
template <class F>
void forNearbySlabs(const SlabLayout& layout, int ranks, double widest, double a, double b, F f)
{
  const double period = layout.period();
  if (period > 0.0 && b - a >= 0.999 * (period - widest))
  {
    for (int q = 0; q < ranks; ++q)
      f(static_cast<std::size_t>(q));
    return;
  }
  const int qa = layout.testerOf(a), qb = layout.testerOf(b);
  if (period > 0.0)
  {
    const int n =
      std::min(ranks, ((qb - qa) % ranks + ranks) % ranks + 3); // qa − 1 … qb + 1, cyclic
    for (int j = 0; j < n; ++j)
      f(static_cast<std::size_t>(((qa - 1 + j) % ranks + ranks) % ranks));
    return;
  }
  for (int q = std::max(0, qa - 1); q <= std::min(ranks - 1, qb + 1); ++q)
    f(static_cast<std::size_t>(q));
}

// Writes the run of own[first, first + count) (links of one fiber, consecutive).
void writeRun(std::vector<char>& out, const std::vector<CapsuleLink>& own, std::size_t first,
  std::size_t count, const FiberModel& model, const std::vector<std::int64_t>& global)
{
  const CapsuleLink& l = own[first];
  const Fiber& fib = model.fibers[l.fiber];
  RunHeader h;
  std::memset(&h, 0, sizeof h); // its padding bytes too: nothing uninitialised goes out
  h.fiber = static_cast<std::uint32_t>(global[l.fiber]);
  h.k0 = l.k;
  h.count = static_cast<std::uint32_t>(count);
  h.arc0 = l.arc0;
  h.closedLength = l.closedLength;
  appendBytes(out, &h, 1);
  appendBytes(out, fib.points.data() + l.k, count + 1);
  appendBytes(out, fib.radii.data() + l.k, count + 1);
}
} // namespace

double capsuleRadius(double r0, double r1, double scale)
{
  const double rho = r0 > r1 ? r0 : r1;
  return scale == 1.0 ? rho : scale * rho;
}

TrafficCount exchangeLinks(const std::vector<CapsuleLink>& own, const FiberModel& model,
  const std::vector<std::int64_t>& global, double scale, const SlabLayout& layout, double reach,
  Comm& comm, std::vector<CapsuleLink>& held, HeldLinkInfo& info)
{
  const int axis = layout.axis();
  const std::size_t nr = static_cast<std::size_t>(comm.size());
  const int me = comm.rank();
  // Every rank's test region (−lo, hi; none: −∞, −∞) from the links of all owners.
  // tester: per own link, the rank testing its pairs (kept for the held copy below).
  std::vector<double> region(2 * nr, -HUGE_VAL);
  std::vector<int> tester(own.size());
  for (std::size_t i = 0; i < own.size(); ++i)
  {
    const CapsuleLink& l = own[i];
    const double c = centre(l, axis);
    tester[i] = layout.testerOf(c);
    const std::size_t q = static_cast<std::size_t>(tester[i]);
    const double shift = layout.wrapShift(c);
    region[2 * q] = std::max(region[2 * q], -(std::min(l.p0[axis], l.p1[axis]) + shift));
    region[2 * q + 1] = std::max(region[2 * q + 1], std::max(l.p0[axis], l.p1[axis]) + shift);
  }
  comm.max(region);
  // Every region lies in its slab grown by `grow`: a link can only reach the regions of the slabs
  // its extent grown by reach + grow touches (and, for rounding, one more on each side), so a
  // link tests a few ranks, not all.
  // Without a period the outer sides of the first and last slab do not count: forNearbySlabs
  // clamps a coordinate beyond them to that slab anyway (open-model fibers drifting outward
  // would otherwise widen every link's search).
  const bool aperiodic = layout.period() <= 0.0;
  // Without a cell a pair is tested by the lower of its links' tester slabs: a link goes to no
  // rank above its own.
  const bool downOnly = testedPairs(layout) == TestedPairs::EitherLink;
  double grow = 0.0, widest = 0.0;
  for (std::size_t q = 0; q < nr; ++q)
  {
    widest = std::max(
      widest, layout.testerLo(static_cast<int>(q) + 1) - layout.testerLo(static_cast<int>(q)));
    if (region[2 * q + 1] > -HUGE_VAL)
    {
      const int r = static_cast<int>(q);
      if (!(aperiodic && q == 0))
        grow = std::max(grow, layout.testerLo(r) + region[2 * q]);
      if (!(aperiodic && q + 1 == nr))
        grow = std::max(grow, region[2 * q + 1] - layout.testerLo(r + 1));
    }
  }
  grow +=
    1e-9 * (layout.testerLo(static_cast<int>(nr)) - layout.testerLo(0)); // testerLo's rounding
  // Down-only routing without a cell: below[t] is the highest top of the regions of the slabs
  // below t, so a link of slab t whose extent lies more than reach above it goes to t alone
  // (most links; the general search below would find the same).
  std::vector<double> below(nr, -HUGE_VAL);
  for (std::size_t q = 1; downOnly && q < nr; ++q)
    below[q] = std::max(below[q - 1], region[2 * (q - 1) + 1]);
  // Per destination, the run of links being collected (first link, length); `open`: those with
  // a run, `stamp[q] == i`: link i goes to q. This rank's own runs are only noted (mine).
  std::vector<std::vector<char>> out(nr);
  std::vector<std::size_t> first(nr), count(nr, 0), stamp(nr, SIZE_MAX), open, dests;
  std::vector<std::pair<std::size_t, std::size_t>> mine;
  const auto closeRun = [&](std::size_t q)
  {
    if (q == static_cast<std::size_t>(me))
      mine.emplace_back(first[q], count[q]);
    else
      writeRun(out[q], own, first[q], count[q], model, global);
    count[q] = 0;
  };
  for (std::size_t i = 0; i < own.size(); ++i)
  {
    const CapsuleLink& l = own[i];
    const double lo = std::min(l.p0[axis], l.p1[axis]), hi = std::max(l.p0[axis], l.p1[axis]);
    dests.clear();
    const std::size_t t = static_cast<std::size_t>(tester[i]);
    if (downOnly && lo - reach > below[t])
    {
      dests.push_back(t); // its own region holds it
      stamp[t] = i;
    }
    else
    {
      forNearbySlabs(layout, static_cast<int>(nr), widest, lo - reach - grow, hi + reach + grow,
        [&](std::size_t q)
        {
          if ((!downOnly || q <= t) && region[2 * q + 1] > -HUGE_VAL &&
            within(lo, hi, -region[2 * q], region[2 * q + 1], reach, layout.period()))
          {
            dests.push_back(q);
            stamp[q] = i;
          }
        });
    }
    const bool continues = i > 0 && own[i - 1].fiber == l.fiber && own[i - 1].k + 1 == l.k;
    std::size_t kept = 0;
    for (std::size_t q : open)
    {
      if (continues && stamp[q] == i)
      {
        open[kept++] = q;
        continue;
      }
      closeRun(q);
    }
    open.resize(kept);
    for (std::size_t q : dests)
    {
      if (count[q]++ == 0)
      {
        first[q] = i;
        open.push_back(q);
      }
    }
  }
  for (std::size_t q : open)
    closeRun(q);
  TrafficCount sent;
  const std::vector<std::vector<char>> in = exchangeAll(out, comm, sent);
  // Each sender's runs come in its link order, which is global order (an owner's fibers are in
  // global order), and no two senders send links of one fiber: taking the run with the lowest
  // first link among the senders' next ones gives global link order without a sort. This
  // rank's own links are copied from `own` as buildLinks made them (the receivers rebuild the
  // same bits).
  held.clear();
  info.pointRadius.clear();
  info.owner.clear();
  info.local.clear();
  info.tested.clear();
  std::vector<Reader> readers;
  readers.reserve(nr);
  for (const std::vector<char>& b : in)
    readers.emplace_back(b);
  std::vector<RunHeader> head(nr);
  std::size_t nextMine = 0;
  std::vector<Vec3> p;
  std::vector<double> r;
  const auto peek = [&](std::size_t q, std::uint64_t& key)
  {
    if (q == static_cast<std::size_t>(me))
    {
      if (nextMine == mine.size())
        return false;
      const CapsuleLink& l = own[mine[nextMine].first];
      key = linkKey(static_cast<std::uint32_t>(global[l.fiber]), l.k);
      return true;
    }
    if (readers[q].done())
      return false;
    readers[q].get(&head[q]);
    key = linkKey(head[q].fiber, head[q].k0);
    return true;
  };
  const auto take = [&](std::size_t q)
  {
    if (q == static_cast<std::size_t>(me))
    {
      const auto [at, n] = mine[nextMine++];
      for (std::size_t i = at; i < at + n; ++i)
      {
        CapsuleLink l = own[i];
        const std::vector<double>& radii = model.fibers[l.fiber].radii;
        info.pointRadius.push_back(std::min(radii[l.k], radii[l.k + 1]));
        info.owner.push_back(me);
        info.local.push_back(l.fiber);
        info.tested.push_back(tester[i] == me ? 1 : 0);
        l.fiber = static_cast<std::uint32_t>(global[l.fiber]);
        held.push_back(l);
      }
      return;
    }
    const RunHeader& h = head[q];
    p.resize(h.count + 1);
    r.resize(h.count + 1);
    readers[q].get(p.data(), p.size());
    readers[q].get(r.data(), r.size());
    double arc = h.arc0;
    for (std::uint32_t k = 0; k < h.count; ++k)
    {
      CapsuleLink l;
      l.p0 = p[k];
      l.p1 = p[k + 1];
      l.rho = capsuleRadius(r[k], r[k + 1], scale);
      l.fiber = h.fiber;
      l.k = h.k0 + k;
      l.arc0 = arc;
      arc += distance(l.p0, l.p1);
      l.arc1 = arc;
      l.closedLength = h.closedLength;
      held.push_back(l);
      info.pointRadius.push_back(std::min(r[k], r[k + 1]));
      info.owner.push_back(static_cast<int>(q));
      info.local.push_back(kNotOwned);
      info.tested.push_back(layout.testerOf(centre(l, axis)) == me ? 1 : 0);
    }
  };
  mergeStreams<std::uint64_t>(nr, peek, take);
  return sent;
}

void returnPushes(const std::vector<LinkPairPush>& tested, const std::vector<std::int64_t>& global,
  Comm& comm, TrafficCount& sent, std::vector<std::vector<ReceivedPush>>& received)
{
  const std::size_t nr = static_cast<std::size_t>(comm.size());
  const int me = comm.rank();
  // Sizes first, so that every buffer is written once into its final place (no regrowth).
  std::vector<std::size_t> size(nr, 0);
  const auto bytes = [](std::uint32_t sides)
  {
    return sizeof(PushHeader) + ((sides & 1) ? 2 * sizeof(Vec3) : 0) +
      ((sides & 2) ? 2 * sizeof(Vec3) : 0);
  };
  const auto route = [me](const LinkPairPush& p, auto send)
  {
    if (p.ownerA == p.ownerB)
    {
      if (p.ownerA != me)
        send(p.ownerA, 3u);
    }
    else // each owner gets its side only
    {
      if (p.ownerA != me)
        send(p.ownerA, 1u);
      if (p.ownerB != me)
        send(p.ownerB, 2u);
    }
  };
  for (const LinkPairPush& p : tested)
    route(
      p, [&](int to, std::uint32_t sides) { size[static_cast<std::size_t>(to)] += bytes(sides); });
  std::vector<std::vector<char>> out(nr);
  for (std::size_t q = 0; q < nr; ++q)
    out[q].reserve(size[q]);
  for (const LinkPairPush& p : tested)
  {
    route(p,
      [&](int to, std::uint32_t sides)
      {
        ByteWriter w(out[static_cast<std::size_t>(to)]);
        w.put(PushHeader{ p.fiberA, p.kA, p.fiberB, p.kB, sides });
        if (sides & 1)
        {
          w.put(p.a0);
          w.put(p.a1);
        }
        if (sides & 2)
        {
          w.put(p.b0);
          w.put(p.b1);
        }
      });
  }
  const std::vector<std::vector<char>> in = exchangeAll(out, comm, sent);
  // A side not sent stays zero: its fiber is not this rank's. A sender's pairs come in pair
  // order, so their first fibers ascend: one cursor through `global` finds them.
  const auto localOf = [&global](std::uint32_t fiber)
  {
    const auto it = std::lower_bound(global.begin(), global.end(), std::int64_t{ fiber });
    return it != global.end() && *it == fiber ? static_cast<std::uint32_t>(it - global.begin())
                                              : kNotOwned;
  };
  received.resize(nr);
  for (std::size_t q = 0; q < nr; ++q)
  {
    received[q].clear();
    received[q].reserve(
      in[q].size() / (sizeof(PushHeader) + 2 * sizeof(Vec3))); // at most this many
    Reader rd(in[q]);
    std::size_t cursor = 0;
    while (!rd.done())
    {
      PushHeader h;
      rd.get(&h);
      ReceivedPush x;
      x.push.fiberA = h.fiberA;
      x.push.kA = h.kA;
      x.push.fiberB = h.fiberB;
      x.push.kB = h.kB;
      if (h.sides & 1)
      {
        rd.get(&x.push.a0);
        rd.get(&x.push.a1);
        while (cursor < global.size() && global[cursor] < h.fiberA)
          ++cursor;
        x.localA = cursor < global.size() && global[cursor] == h.fiberA
          ? static_cast<std::uint32_t>(cursor)
          : kNotOwned;
      }
      if (h.sides & 2)
      {
        rd.get(&x.push.b0);
        rd.get(&x.push.b1);
        x.localB = localOf(h.fiberB);
      }
      received[q].push_back(x);
    }
  }
}

} // namespace fiberpli
