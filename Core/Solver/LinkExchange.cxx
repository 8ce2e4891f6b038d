#include "Solver/LinkExchange.h"

#include "Solver/SolverLinks.h"
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

// The exchange of the buffers with the partners (this rank's own links and pushes never go
// into a buffer: out[me] stays empty, as does every buffer for a rank that is no partner), into
// `in`, whose capacity is kept.
void exchangeWithPartners(const std::vector<std::vector<char>>& out,
  const std::vector<int>& partners, Comm& comm, TrafficCount& sent,
  std::vector<std::vector<char>>& in)
{
  for (const std::vector<char>& b : out)
    sent.bytes += b.size();
  comm.exchangeWithInto(partners, out, in);
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

Vec3 centre(const CapsuleLink& l)
{
  return 0.5 * (l.p0 + l.p1);
}

// Lower and upper bound along d of tester (owners: owner) layer i, the outermost faces of an open
// model infinite (a coordinate beyond them belongs to that layer).
double layerLo(const BoxLayout& layout, int d, int i, bool owners)
{
  return !layout.periodic() && i == 0 ? -HUGE_VAL : layout.cut(d, i, owners);
}
double layerHi(const BoxLayout& layout, int d, int i, bool owners)
{
  return !layout.periodic() && i + 1 == layout.boxes(d) ? HUGE_VAL : layout.cut(d, i + 1, owners);
}

// The owned fibers' links as buildLinks makes them (the same bits), read from the model where they
// are needed instead of built into a list first: own link i is link k of fiber f, i = begin[f] + k.
// A rank's links are most of what it holds, and a list of them would be written, read for the
// routing and copied into the held links every step.
struct OwnLinks
{
  const FiberModel& model;
  std::vector<std::size_t> begin;   // per fiber, its first own link (+ the total)
  std::vector<double> closedLength; // per fiber: its arc length when closed through the cell, or 0

  OwnLinks(const FiberModel& m, const std::vector<char>* active, const std::vector<char>* closed)
    : model(m)
    , begin(m.fibers.size() + 1, 0)
    , closedLength(m.fibers.size(), 0.0)
  {
    for (std::size_t f = 0; f < m.fibers.size(); ++f)
    {
      const std::size_t n = linksOf(m, active, f);
      begin[f + 1] = begin[f] + n;
      if (n > 0 && closed && (*closed)[f])
        closedLength[f] = arcTo(f, n);
    }
  }
  std::size_t size() const { return begin.back(); }
  std::size_t links(std::size_t f) const { return begin[f + 1] - begin[f]; }
  const Vec3* points(std::size_t f) const { return model.fibers[f].points.data(); }
  // The arc length from fiber f's first point to its point k, summed as buildLinks sums it.
  double arcTo(std::size_t f, std::size_t k) const { return arcFrom(f, 0, 0.0, k); }
  double arcFrom(std::size_t f, std::size_t from, double arc, std::size_t k) const
  {
    const Vec3* p = points(f);
    for (std::size_t j = from; j < k; ++j)
      arc += distance(p[j], p[j + 1]);
    return arc;
  }
};

// A run of own links: links k0, …, k0 + count − 1 of fiber f (own links i, …), arc0 the arc length
// at its first point.
struct OwnRun
{
  std::size_t i = 0;
  std::uint32_t f = 0, k0 = 0;
  std::size_t count = 0;
  double arc0 = 0.0;
};

// Writes an own run as it travels.
void writeRun(std::vector<char>& out, const OwnLinks& own, const OwnRun& run,
  const std::vector<std::int64_t>& global)
{
  const Fiber& fib = own.model.fibers[run.f];
  RunHeader h;
  std::memset(&h, 0, sizeof h); // its padding bytes too: nothing uninitialised goes out
  h.fiber = static_cast<std::uint32_t>(global[run.f]);
  h.k0 = run.k0;
  h.count = static_cast<std::uint32_t>(run.count);
  h.arc0 = run.arc0;
  h.closedLength = own.closedLength[run.f];
  appendBytes(out, &h, 1);
  appendBytes(out, fib.points.data() + run.k0, run.count + 1);
  appendBytes(out, fib.radii.data() + run.k0, run.count + 1);
}
} // namespace

BlockBox linkBlockBoxes(const Vec3* p, std::size_t links, std::vector<BlockBox>& out)
{
  out.resize(linkBlockCount(links));
  if (links == 0)
    return BlockBox{};
  BlockBox all{ p[0], p[0] };
  for (std::size_t b = 0; b < out.size(); ++b)
  {
    // The points of links k0..k1-1 are k0..k1 (consecutive links share a point), read in order.
    const std::size_t k0 = b * kLinkBlock, k1 = std::min(links, k0 + kLinkBlock);
    BlockBox box{ p[k0], p[k0] };
    for (std::size_t k = k0 + 1; k <= k1; ++k)
    {
      box.lo = componentMin(box.lo, p[k]);
      box.hi = componentMax(box.hi, p[k]);
    }
    out[b] = box;
    all.lo = componentMin(all.lo, box.lo);
    all.hi = componentMax(all.hi, box.hi);
  }
  return all;
}

double capsuleRadius(double r0, double r1, double scale)
{
  const double rho = r0 > r1 ? r0 : r1;
  return scale == 1.0 ? rho : scale * rho;
}

TrafficCount exchangeLinks(const FiberModel& model, const std::vector<char>* active,
  const std::vector<char>* closed, const std::vector<std::int64_t>& global, double scale,
  const BoxLayout& layout, double reach, Comm& comm, std::vector<CapsuleLink>& held,
  HeldLinkInfo& info, std::vector<int>& partners, LinkExchangeBuffers* buffers)
{
  LinkExchangeBuffers ownBuffers;
  LinkExchangeBuffers& buf = buffers ? *buffers : ownBuffers;
  const std::size_t nr = static_cast<std::size_t>(comm.size());
  const int me = comm.rank();
  const OwnLinks own(model, active, closed);
  // How far links reach beyond the faces of their tester box (`grow`, each link shifted as
  // wrapping its centre shifts it) and beyond the owner box of the rank owning their fiber
  // (`spread`, shifted as wrapping the fiber's middle shifts it): below / above, per axis, the
  // maxima over all ranks. tester: per own link, the box testing its pairs; shift: its wrap.
  const bool periodic = layout.periodic();
  // Per axis the faces of the tester layers (a link's tester box is its layers along the axes).
  std::vector<double> faceLo[3], faceHi[3];
  for (int d = 0; d < 3; ++d)
  {
    for (int j = 0; j < layout.boxes(d); ++j)
    {
      faceLo[d].push_back(layerLo(layout, d, j, false));
      faceHi[d].push_back(layerHi(layout, d, j, false));
    }
  }
  const LayoutBox ownerBox = layout.box(me, true);
  std::vector<double> m(12, 0.0); // grow below, grow above, spread below, spread above
  std::vector<int>& tester = buf.tester;
  tester.resize(own.size()); // every entry is set below
  std::vector<Vec3>& shift = buf.shift;
  shift.resize(periodic ? own.size() : 0); // without a cell no link is shifted
  // Without a cell the links go in blocks of up to kLinkBlock consecutive links of one fiber. A
  // block whose points lie inside one tester box by more than the rounding of layerOf (1e-9 of the
  // span, far above it) has that tester for every link and no link reaching beyond its faces;
  // the routing below then sends it whole when its bounding box comes within reach of that box
  // alone. Most links lie so (a box is much wider than a link): each costs its points' extremes,
  // which the caller may have taken already (LinkExchangeBuffers::blockBoxes). A fiber whose
  // points all lie so (every fiber on one rank; on more, those that cross no cut) is one block of
  // all its links when the caller gave the boxes: a test per fiber instead of one per block, and
  // the routing looks at its blocks only when the fiber comes within reach of another box.
  using Block = LinkBlock;
  const bool boxesGiven = buf.blockBoxesCurrent && buf.blockBoxes.size() == model.fibers.size() &&
    buf.fiberBoxes.size() == model.fibers.size();
  buf.blockBoxesCurrent = false;
  std::vector<BlockBox> computedBoxes; // one fiber's, when not given
  std::vector<Block>& blocks = buf.blocks;
  blocks.clear();
  std::size_t blockCount = 0; // sized once: growing it copied every block made so far
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
    blockCount += linkBlockCount(own.links(f));
  blocks.reserve(blockCount);
  double rounding[3];
  for (int d = 0; d < 3; ++d)
    rounding[d] = 1e-9 * layout.span(d);
  // The layers of the box's centre, and whether the box lies inside them by the rounding.
  const auto placeInLayers = [&](Block& block, const BlockBox& box)
  {
    block.lo = box.lo;
    block.hi = box.hi;
    block.inside = true;
    for (int d = 0; d < 3; ++d)
    {
      const int j = layout.layerOf(d, 0.5 * (block.lo[d] + block.hi[d]));
      block.layer[d] = j;
      block.inside = block.inside &&
        block.lo[d] >= faceLo[d][static_cast<std::size_t>(j)] + rounding[d] &&
        block.hi[d] <= faceHi[d][static_cast<std::size_t>(j)] - rounding[d];
    }
  };
  // An inside block: every link's centre is in its layers; no link reaches beyond their faces
  // (its growth is negative: the maxima, which start at 0, stay), and its spread beyond the owner
  // box is the block's.
  const auto addInside = [&](const Block& block)
  {
    const std::size_t i0 = own.begin[block.f];
    std::fill(tester.begin() + static_cast<std::ptrdiff_t>(i0 + block.k0),
      tester.begin() + static_cast<std::ptrdiff_t>(i0 + block.k1),
      layout.rankOf(block.layer[0], block.layer[1], block.layer[2]));
    for (int d = 0; d < 3; ++d)
    {
      m[6 + d] = std::max(m[6 + d], ownerBox.lo[d] - block.lo[d]);
      m[9 + d] = std::max(m[9 + d], block.hi[d] - ownerBox.hi[d]);
    }
    blocks.push_back(block);
  };
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const std::size_t nl = own.links(f);
    if (nl == 0)
      continue;
    const Vec3* p = own.points(f);
    const Vec3 fiberShift =
      periodic ? layout.wrapShift(BoxLayout::middle(model.fibers[f])) : Vec3{};
    const std::vector<BlockBox>* boxes = &computedBoxes;
    if (!periodic && boxesGiven && buf.blockBoxes[f].size() == linkBlockCount(nl))
    {
      boxes = &buf.blockBoxes[f];
      Block whole{ static_cast<std::uint32_t>(f), 0, static_cast<std::uint32_t>(nl), false,
        { 0, 0, 0 }, {}, {} };
      placeInLayers(whole, buf.fiberBoxes[f]);
      if (whole.inside)
      {
        addInside(whole);
        continue;
      }
    }
    else if (!periodic)
      linkBlockBoxes(p, nl, computedBoxes);
    for (std::size_t k0 = 0; k0 < nl; k0 += kLinkBlock)
    {
      const std::size_t k1 = std::min(nl, k0 + kLinkBlock);
      Block block{ static_cast<std::uint32_t>(f), static_cast<std::uint32_t>(k0),
        static_cast<std::uint32_t>(k1), false, { 0, 0, 0 }, {}, {} };
      const std::size_t i0 = own.begin[f];
      if (!periodic)
        placeInLayers(block, (*boxes)[k0 / kLinkBlock]);
      if (block.inside)
      {
        addInside(block);
        continue;
      }
      for (std::size_t k = k0; k < k1; ++k)
      {
        const std::size_t i = i0 + k;
        const Vec3 c = 0.5 * (p[k] + p[k + 1]);
        int layer[3];
        for (int d = 0; d < 3; ++d)
          layer[d] = layout.layerOf(d, c[d]);
        tester[i] = layout.rankOf(layer[0], layer[1], layer[2]); // layout.testerOf(c)
        Vec3 s;
        if (periodic)
          s = shift[i] = layout.wrapShift(c);
        for (int d = 0; d < 3; ++d)
        {
          const double lo = std::min(p[k][d], p[k + 1][d]), hi = std::max(p[k][d], p[k + 1][d]);
          m[d] = std::max(m[d], faceLo[d][static_cast<std::size_t>(layer[d])] - (lo + s[d]));
          m[3 + d] = std::max(m[3 + d], hi + s[d] - faceHi[d][static_cast<std::size_t>(layer[d])]);
          m[6 + d] = std::max(m[6 + d], ownerBox.lo[d] - (lo + fiberShift[d]));
          m[9 + d] = std::max(m[9 + d], hi + fiberShift[d] - ownerBox.hi[d]);
        }
      }
      blocks.push_back(block);
    }
  }
  comm.max(m);
  for (int d = 0; d < 3; ++d) // the rounding of the cuts and shifts
  {
    const double margin = 1e-9 * layout.span(d);
    for (int j = 0; j < 4; ++j)
      m[3 * j + d] += margin;
  }
  // Owner layer o (grown by the spread) and tester layer t (grown by the growth) closer than
  // reach along d (modulo the cell): then an owner of o may send a link to a tester of t. One
  // function of (d, o, t), so that every rank evaluates the relation alike.
  const auto near = [&](int d, int o, int t)
  {
    return within(layerLo(layout, d, o, true) - m[6 + d], layerHi(layout, d, o, true) + m[9 + d],
      layerLo(layout, d, t, false) - m[d], layerHi(layout, d, t, false) + m[3 + d], reach,
      layout.period(d));
  };
  // The partners: the tester boxes this rank's owner box may send links to, and the owner boxes
  // that may send links to this rank's tester box (pushes go back the same way). Symmetric: q is
  // a partner of r exactly when r is one of q.
  int idx[3];
  layout.indicesOf(me, idx);
  std::vector<int> sendsTo[3], getsFrom[3]; // per axis, the layers
  for (int d = 0; d < 3; ++d)
  {
    for (int j = 0; j < layout.boxes(d); ++j)
    {
      if (near(d, idx[d], j))
        sendsTo[d].push_back(j);
      if (near(d, j, idx[d]))
        getsFrom[d].push_back(j);
    }
  }
  partners.clear();
  const std::vector<int>* both[2] = { sendsTo, getsFrom };
  for (const std::vector<int>* layers : both)
    for (int i : layers[0])
      for (int j : layers[1])
        for (int k : layers[2])
          if (layout.rankOf(i, j, k) != me)
            partners.push_back(layout.rankOf(i, j, k));
  std::sort(partners.begin(), partners.end());
  partners.erase(std::unique(partners.begin(), partners.end()), partners.end());
  // Without a cell a pair is tested by the lower of its links' tester boxes: a link goes to no
  // box above its own.
  const bool downOnly = testedPairs(layout) == TestedPairs::EitherLink;
  // Per destination, the run of links being collected (run[q].count > 0); `open`: those with a
  // run, `stamp[q] == i`: link i goes to q. This rank's own runs are only noted (mine).
  std::vector<std::vector<char>>& out = buf.out;
  out.resize(nr);
  for (std::vector<char>& b : out)
    b.clear(); // the capacity is kept
  std::vector<OwnRun> run(nr);
  std::vector<std::size_t> stamp(nr, SIZE_MAX), open, dests;
  std::vector<OwnRun> mine;
  // The arc length at the first point of each run, summed along the fiber up to it as buildLinks
  // sums it (runs open in link order: one pass per fiber at most, none for a run starting it).
  std::size_t arcFiber = SIZE_MAX, arcK = 0;
  double arcAt = 0.0;
  const auto runArc0 = [&](std::size_t f, std::size_t k)
  {
    if (f != arcFiber)
    {
      arcFiber = f;
      arcK = 0;
      arcAt = 0.0;
    }
    arcAt = own.arcFrom(f, arcK, arcAt, k);
    arcK = k;
    return arcAt;
  };
  const auto closeRun = [&](std::size_t q)
  {
    if (q == static_cast<std::size_t>(me))
      mine.push_back(run[q]);
    else
      writeRun(out[q], own, run[q], global);
    run[q].count = 0;
  };
  // The layers this rank's owner box sends to, per axis, with their faces grown by the growth.
  struct Grown
  {
    int layer;
    double lo, hi;
  };
  std::vector<Grown> grown[3];
  for (int d = 0; d < 3; ++d)
  {
    for (int j : sendsTo[d])
    {
      grown[d].push_back({ j, faceLo[d][static_cast<std::size_t>(j)] - m[d],
        faceHi[d][static_cast<std::size_t>(j)] + m[3 + d] });
    }
  }
  // Link k of fiber f (own link i) goes to the ranks in `dests` (stamped i): the runs it does not
  // continue are closed, those it starts are opened.
  const auto route = [&](std::size_t i, std::uint32_t f, std::uint32_t k)
  {
    const bool continues = k > 0; // own links are consecutive along a fiber
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
      if (run[q].count++ == 0)
      {
        run[q].i = i;
        run[q].f = f;
        run[q].k0 = k;
        run[q].arc0 = runArc0(f, k);
        open.push_back(q);
      }
    }
  };
  // An inside block's box within reach of its own tester layer only, along every axis: so is
  // each of its links (it lies in that layer), which then goes to its tester box alone.
  const auto alone = [&](const Block& block)
  {
    for (int d = 0; d < 3; ++d)
    {
      int reached = 0;
      for (const Grown& g : grown[d])
      {
        if (within(block.lo[d], block.hi[d], g.lo, g.hi, reach, layout.period(d)))
        {
          ++reached;
          if (g.layer != block.layer[d])
            return false;
        }
      }
      if (reached != 1)
        return false;
    }
    return true;
  };
  // All the block's links to its tester box, one run.
  const auto routeWhole = [&](const Block& block)
  {
    const std::size_t i0 = own.begin[block.f];
    const std::size_t t = static_cast<std::size_t>(tester[i0 + block.k0]);
    dests.assign(1, t);
    stamp[t] = i0 + block.k0;
    route(i0 + block.k0, block.f, block.k0);
    // The block's further links continue the same run to t.
    run[t].count += block.k1 - block.k0 - 1;
  };
  std::vector<int> along[3];
  // Each of the block's links to the tester boxes (grown by the growth) it comes within reach
  // of, among the layers this rank's owner box sends to.
  const auto routeLinks = [&](const Block& block)
  {
    const std::size_t i0 = own.begin[block.f];
    const Vec3* p = own.points(block.f);
    for (std::uint32_t k = block.k0; k < block.k1; ++k)
    {
      const std::size_t i = i0 + k;
      for (int d = 0; d < 3; ++d)
      {
        const double s = periodic ? shift[i][d] : 0.0;
        const double lo = std::min(p[k][d], p[k + 1][d]) + s;
        const double hi = std::max(p[k][d], p[k + 1][d]) + s;
        along[d].clear();
        for (const Grown& g : grown[d])
        {
          if (within(lo, hi, g.lo, g.hi, reach, layout.period(d)))
            along[d].push_back(g.layer);
        }
      }
      dests.clear();
      const std::size_t t = static_cast<std::size_t>(tester[i]);
      for (int a : along[0])
        for (int b : along[1])
          for (int c : along[2])
          {
            const std::size_t q = static_cast<std::size_t>(layout.rankOf(a, b, c));
            if (!downOnly || q <= t)
            {
              dests.push_back(q);
              stamp[q] = i;
            }
          }
      route(i, block.f, k);
    }
  };
  for (const Block& block : blocks)
  {
    if (!block.inside)
      routeLinks(block);
    else if (alone(block))
      routeWhole(block);
    else if (block.k1 - block.k0 <= kLinkBlock)
      routeLinks(block);
    else
    {
      // A whole fiber in one layer, within reach of another: its blocks, in the same layer, as
      // they come (each routed as it would be as a block of its own).
      const std::vector<BlockBox>& boxes = buf.blockBoxes[block.f];
      for (std::uint32_t k0 = block.k0; k0 < block.k1; k0 += kLinkBlock)
      {
        Block part = block;
        part.k0 = k0;
        part.k1 = std::min<std::uint32_t>(block.k1, k0 + kLinkBlock);
        part.lo = boxes[k0 / kLinkBlock].lo;
        part.hi = boxes[k0 / kLinkBlock].hi;
        if (alone(part))
          routeWhole(part);
        else
          routeLinks(part);
      }
    }
  }
  for (std::size_t q : open)
    closeRun(q);
  TrafficCount sent;
  std::vector<std::vector<char>>& in = buf.in;
  exchangeWithPartners(out, partners, comm, sent, in);
  // Each sender's runs come in its link order, which is global order (an owner's fibers are in
  // global order), and no two senders send links of one fiber: taking the run with the lowest
  // first link among the senders' next ones gives global link order without a sort. This
  // rank's own runs are built from the model as buildLinks builds links (the receivers rebuild
  // the same bits).
  // Every list is sized once to all the links held and filled in place: `held` keeps the size
  // it had (a buffer of an earlier step, about as long), so growing it constructs few links.
  std::size_t total = 0;
  for (const OwnRun& o : mine)
    total += o.count;
  const std::size_t mineTotal = total;
  for (const std::vector<char>& b : in)
  {
    Reader rd(b);
    while (!rd.done())
    {
      const RunHeader h = rd.get<RunHeader>();
      rd.skip<Vec3>(h.count + 1);
      rd.skip<double>(h.count + 1);
      total += h.count;
    }
  }
  held.resize(total);
  info.pointRadius.resize(total);
  info.owner.resize(total);
  info.local.resize(total);
  info.tested.resize(total);
  std::size_t at = 0; // the next link to fill
  info.fiberRuns.clear();
  std::uint32_t lastFiber = 0; // of the last link filled (at > 0)
  std::vector<Reader> readers;
  readers.reserve(nr);
  for (const std::vector<char>& b : in)
    readers.emplace_back(b);
  std::vector<RunHeader> head(nr);
  std::size_t nextMine = 0;
  std::vector<Vec3> pts;
  std::vector<double> rad;
  const auto peek = [&](std::size_t q, std::uint64_t& key)
  {
    if (q == static_cast<std::size_t>(me))
    {
      if (nextMine == mine.size())
        return false;
      const OwnRun& r = mine[nextMine];
      key = linkKey(static_cast<std::uint32_t>(global[r.f]), r.k0);
      return true;
    }
    if (readers[q].done())
      return false;
    readers[q].get(&head[q]);
    key = linkKey(head[q].fiber, head[q].k0);
    return true;
  };
  // Fills the next count links: fiber `fiber` (global index) from its points p[0..count] and radii
  // r[0..count], link k0 first, at arc length arc0; tested(j, link): whether link j is this
  // rank's to test.
  const auto fill = [&](const Vec3* p, const double* r, std::uint32_t fiber, std::uint32_t k0,
                      std::size_t count, double arc0, double closedLength, int owner,
                      std::uint32_t local, auto tested)
  {
    // Raw pointers and a local index: the char stores of `tested` may alias anything, and the
    // vectors' data and `at` would be reloaded after each of them.
    CapsuleLink* links = held.data() + at;
    double* pointRadius = info.pointRadius.data() + at;
    int* owners = info.owner.data() + at;
    std::uint32_t* locals = info.local.data() + at;
    char* testedHere = info.tested.data() + at;
    if (count > 0 && (at == 0 || fiber != lastFiber)) // runs of one fiber arrive one after another
    {
      info.fiberRuns.push_back(at);
      lastFiber = fiber;
    }
    double arc = arc0;
    for (std::size_t j = 0; j < count; ++j)
    {
      CapsuleLink& l = links[j];
      l.p0 = p[j];
      l.p1 = p[j + 1];
      l.rho = capsuleRadius(r[j], r[j + 1], scale);
      l.fiber = fiber;
      l.k = k0 + static_cast<std::uint32_t>(j);
      l.arc0 = arc;
      arc += distance(l.p0, l.p1);
      l.arc1 = arc;
      l.closedLength = closedLength;
      locals[j] = local;
      testedHere[j] = tested(j, l) ? 1 : 0;
    }
    if (local == kNotOwned) // another rank's links: what this rank's model does not tell
    {
      for (std::size_t j = 0; j < count; ++j)
      {
        pointRadius[j] = std::min(r[j], r[j + 1]);
        owners[j] = owner;
      }
    }
    at += count;
  };
  const auto take = [&](std::size_t q)
  {
    if (q == static_cast<std::size_t>(me))
    {
      const OwnRun& o = mine[nextMine++];
      const Fiber& fib = model.fibers[o.f];
      fill(fib.points.data() + o.k0, fib.radii.data() + o.k0,
        static_cast<std::uint32_t>(global[o.f]), o.k0, o.count, o.arc0, own.closedLength[o.f], me,
        o.f, [&](std::size_t j, const CapsuleLink&) { return tester[o.i + j] == me; });
      return;
    }
    const RunHeader& h = head[q];
    pts.resize(h.count + 1);
    rad.resize(h.count + 1);
    readers[q].get(pts.data(), pts.size());
    readers[q].get(rad.data(), rad.size());
    fill(pts.data(), rad.data(), h.fiber, h.k0, h.count, h.arc0, h.closedLength,
      static_cast<int>(q), kNotOwned,
      [&](std::size_t, const CapsuleLink& l) { return layout.testerOf(centre(l)) == me; });
  };
  mergeStreams<std::uint64_t>(nr, peek, take);
  info.fiberRuns.push_back(at);
  info.received = total - mineTotal;
  return sent;
}

void returnPushes(const std::vector<LinkPairPush>& tested, const std::vector<PairLocals>& locals,
  const std::vector<std::int64_t>& global, const std::vector<int>& partners, Comm& comm,
  TrafficCount& sent, std::vector<std::vector<ReceivedPush>>& received,
  LinkExchangeBuffers* buffers)
{
  std::vector<std::vector<char>> ownOut, ownIn;
  std::vector<std::vector<char>>& out = buffers ? buffers->out : ownOut;
  std::vector<std::vector<char>>& in = buffers ? buffers->in : ownIn;
  const std::size_t nr = static_cast<std::size_t>(comm.size());
  // Sizes first, so that every buffer is written once into its final place (no regrowth).
  std::vector<std::size_t> size(nr, 0);
  const auto bytes = [](std::uint32_t sides)
  {
    return sizeof(PushHeader) + ((sides & 1) ? 2 * sizeof(Vec3) : 0) +
      ((sides & 2) ? 2 * sizeof(Vec3) : 0);
  };
  // A side whose fiber is this rank's stays here; the record is read only for a side that leaves
  // (most pairs have both links here: their records are not touched).
  const auto route = [&](std::size_t i, auto send)
  {
    const PairLocals& l = locals[i];
    if (l.a != kNotOwned && l.b != kNotOwned)
      return;
    const LinkPairPush& p = tested[i];
    if (p.ownerA == p.ownerB) // neither is this rank's
      send(p.ownerA, 3u);
    else // each owner gets its side only
    {
      if (l.a == kNotOwned)
        send(p.ownerA, 1u);
      if (l.b == kNotOwned)
        send(p.ownerB, 2u);
    }
  };
  for (std::size_t i = 0; i < tested.size(); ++i)
    route(
      i, [&](int to, std::uint32_t sides) { size[static_cast<std::size_t>(to)] += bytes(sides); });
  out.resize(nr);
  for (std::size_t q = 0; q < nr; ++q)
  {
    out[q].clear(); // the capacity is kept
    out[q].reserve(size[q]);
  }
  for (std::size_t i = 0; i < tested.size(); ++i)
  {
    route(i,
      [&](int to, std::uint32_t sides)
      {
        const LinkPairPush& p = tested[i];
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
  exchangeWithPartners(out, partners, comm, sent, in);
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
