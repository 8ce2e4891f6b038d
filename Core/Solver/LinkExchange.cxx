#include "Solver/LinkExchange.h"

#include "Util/ByteBuffer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>

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

// The all-to-all without copying this rank's own buffer through the communicator.
std::vector<std::vector<char>> exchangeAll(std::vector<std::vector<char>>& out, SolverComm& comm, TrafficCount& sent)
{
  const std::size_t me = static_cast<std::size_t>(comm.rank());
  std::vector<char> self;
  self.swap(out[me]);
  for (const std::vector<char>& b : out)
    sent.bytes += b.size();
  std::vector<std::vector<char>> in = comm.exchange(out);
  in[me] = std::move(self);
  return in;
}

// Merges the senders' streams of records, each already in ascending key order, into one ascending
// order without a sort: repeatedly the sender whose next record has the least key (keys are unique
// across senders) hands it to take(sender, record, reader), which may read the record's body.
// read(reader, record) reads a record's head.
template <class Record, class Read, class Key, class Take>
void mergeSenders(const std::vector<std::vector<char>>& in, Read read, Key key, Take take)
{
  std::vector<Reader> readers;
  readers.reserve(in.size());
  std::vector<Record> next(in.size());
  std::vector<std::size_t> live; // senders with records left; next[q] is q's next one
  for (std::size_t q = 0; q < in.size(); ++q)
  {
    readers.emplace_back(in[q]);
    if (!readers[q].done())
    {
      read(readers[q], next[q]);
      live.push_back(q);
    }
  }
  while (!live.empty())
  {
    std::size_t j = 0;
    for (std::size_t i = 1; i < live.size(); ++i)
      j = key(next[live[i]]) < key(next[live[j]]) ? i : j;
    const std::size_t q = live[j];
    take(q, next[q], readers[q]);
    if (readers[q].done())
    {
      live.erase(live.begin() + static_cast<std::ptrdiff_t>(j));
    }
    else
    {
      read(readers[q], next[q]);
    }
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
template <class F> void forNearbySlabs(const SlabLayout& layout, int ranks, double widest, double a, double b, F f)
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
    const int n = std::min(ranks, ((qb - qa) % ranks + ranks) % ranks + 3); // qa − 1 … qb + 1, cyclic
    for (int j = 0; j < n; ++j)
      f(static_cast<std::size_t>(((qa - 1 + j) % ranks + ranks) % ranks));
    return;
  }
  for (int q = std::max(0, qa - 1); q <= std::min(ranks - 1, qb + 1); ++q)
    f(static_cast<std::size_t>(q));
}

// Writes the run of own[first, first + count) (links of one fiber, consecutive).
void writeRun(std::vector<char>& out, const std::vector<CapsuleLink>& own, std::size_t first, std::size_t count,
  const FiberModel& model, const std::vector<std::int64_t>& global)
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
  const std::vector<std::int64_t>& global, double scale, const SlabLayout& layout, double reach, SolverComm& comm,
  std::vector<CapsuleLink>& held, HeldLinkInfo& info)
{
  const int axis = layout.axis();
  const std::size_t nr = static_cast<std::size_t>(comm.size());
  const int me = comm.rank();
  // Every rank's test region (−lo, hi; none: −∞, −∞) from the links of all owners.
  std::vector<double> region(2 * nr, -HUGE_VAL);
  for (const CapsuleLink& l : own)
  {
    const double c = centre(l, axis);
    const std::size_t q = static_cast<std::size_t>(layout.testerOf(c));
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
  double grow = 0.0, widest = 0.0;
  for (std::size_t q = 0; q < nr; ++q)
  {
    widest = std::max(widest, layout.testerLo(static_cast<int>(q) + 1) - layout.testerLo(static_cast<int>(q)));
    if (region[2 * q + 1] > -HUGE_VAL)
    {
      const int r = static_cast<int>(q);
      if (!(aperiodic && q == 0))
        grow = std::max(grow, layout.testerLo(r) + region[2 * q]);
      if (!(aperiodic && q + 1 == nr))
        grow = std::max(grow, region[2 * q + 1] - layout.testerLo(r + 1));
    }
  }
  grow += 1e-9 * (layout.testerLo(static_cast<int>(nr)) - layout.testerLo(0)); // testerLo's rounding
  // Per destination, the run of links being collected (first link, length); `open`: those with
  // a run, `stamp[q] == i`: link i goes to q.
  std::vector<std::vector<char>> out(nr);
  std::vector<std::size_t> first(nr), count(nr, 0), stamp(nr, SIZE_MAX), open, dests;
  for (std::size_t i = 0; i < own.size(); ++i)
  {
    const CapsuleLink& l = own[i];
    const double lo = std::min(l.p0[axis], l.p1[axis]), hi = std::max(l.p0[axis], l.p1[axis]);
    dests.clear();
    forNearbySlabs(layout, static_cast<int>(nr), widest, lo - reach - grow, hi + reach + grow, [&](std::size_t q) {
      if (region[2 * q + 1] > -HUGE_VAL && within(lo, hi, -region[2 * q], region[2 * q + 1], reach, layout.period()))
      {
        dests.push_back(q);
        stamp[q] = i;
      }
    });
    const bool continues = i > 0 && own[i - 1].fiber == l.fiber && own[i - 1].k + 1 == l.k;
    std::size_t kept = 0;
    for (std::size_t q : open)
    {
      if (continues && stamp[q] == i)
      {
        open[kept++] = q;
        continue;
      }
      writeRun(out[q], own, first[q], count[q], model, global);
      count[q] = 0;
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
    writeRun(out[q], own, first[q], count[q], model, global);
  TrafficCount sent;
  const std::vector<std::vector<char>> in = exchangeAll(out, comm, sent);
  // Each sender's runs come in its link order, which is global order (an owner's fibers are in
  // global order), and no two senders send links of one fiber: taking the run with the lowest
  // first link among the senders' next ones gives global link order without a sort.
  held.clear();
  info.pointRadius.clear();
  info.owner.clear();
  std::vector<Vec3> p;
  std::vector<double> r;
  mergeSenders<RunHeader>(
    in, [](Reader& rd, RunHeader& h) { rd.get(&h); },
    [](const RunHeader& h) { return std::make_tuple(h.fiber, h.k0); },
    [&](std::size_t q, const RunHeader& h, Reader& rd) {
      p.resize(h.count + 1);
      r.resize(h.count + 1);
      rd.get(p.data(), p.size());
      rd.get(r.data(), r.size());
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
      }
    });
  info.tested.resize(held.size());
  for (std::size_t i = 0; i < held.size(); ++i)
    info.tested[i] = layout.testerOf(centre(held[i], axis)) == me ? 1 : 0;
  return sent;
}

void returnPushes(const std::vector<LinkPairPush>& tested, SolverComm& comm, TrafficCount& sent,
  std::vector<LinkPairPush>& mine)
{
  std::vector<std::vector<char>> out(static_cast<std::size_t>(comm.size()));
  const auto write = [&out](const LinkPairPush& p, int to, std::uint32_t sides) {
    std::vector<char>& b = out[static_cast<std::size_t>(to)];
    const PushHeader h{ p.fiberA, p.kA, p.fiberB, p.kB, sides };
    appendBytes(b, &h, 1);
    if (sides & 1)
    {
      appendBytes(b, &p.a0, 1);
      appendBytes(b, &p.a1, 1);
    }
    if (sides & 2)
    {
      appendBytes(b, &p.b0, 1);
      appendBytes(b, &p.b1, 1);
    }
  };
  for (const LinkPairPush& p : tested)
  {
    if (p.ownerA == p.ownerB)
    {
      write(p, p.ownerA, 3);
    }
    else // each owner gets its side only
    {
      write(p, p.ownerA, 1);
      write(p, p.ownerB, 2);
    }
  }
  const std::vector<std::vector<char>> in = exchangeAll(out, comm, sent);
  // A side not sent stays zero: its fiber is not this rank's.
  const auto read = [](Reader& rd, LinkPairPush& p) {
    PushHeader h;
    rd.get(&h);
    p = LinkPairPush{};
    p.fiberA = h.fiberA;
    p.kA = h.kA;
    p.fiberB = h.fiberB;
    p.kB = h.kB;
    if (h.sides & 1)
    {
      rd.get(&p.a0);
      rd.get(&p.a1);
    }
    if (h.sides & 2)
    {
      rd.get(&p.b0);
      rd.get(&p.b1);
    }
  };
  // Every tester sends in its pair order, which is the global one (its held links are in global
  // link order), and each pair comes from one tester only: merging the senders' lists by their
  // next pair gives pair order without a sort.
  mine.clear();
  mergeSenders<LinkPairPush>(
    in, read, [](const LinkPairPush& x) { return std::make_tuple(x.fiberA, x.kA, x.fiberB, x.kB); },
    [&mine](std::size_t, const LinkPairPush& x, Reader&) { mine.push_back(x); });
}

} // namespace fiberpli
