#include "Solver/LinkExchange.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <tuple>
#include <type_traits>

namespace fiberpli
{

namespace
{
// A link as it travels: its capsule (fiber = global index) and the smaller radius of its points.
struct LinkRecord
{
  CapsuleLink link;
  double pointRadius;
};
static_assert(std::is_trivially_copyable<LinkRecord>::value, "sent as bytes");
static_assert(std::is_trivially_copyable<LinkPairPush>::value, "sent as bytes");

template <class T> void append(std::vector<char>& out, const T& v)
{
  const std::size_t at = out.size();
  out.resize(at + sizeof(T));
  std::memcpy(out.data() + at, &v, sizeof(T));
}

template <class T> std::vector<T> records(const std::vector<char>& in)
{
  std::vector<T> v(in.size() / sizeof(T));
  if (!v.empty())
    std::memcpy(v.data(), in.data(), v.size() * sizeof(T));
  return v;
}

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
} // namespace

TrafficCount exchangeLinks(const std::vector<CapsuleLink>& own, const FiberModel& model,
  const std::vector<std::int64_t>& global, const SlabLayout& layout, double reach, SolverComm& comm,
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
  std::vector<std::vector<char>> out(nr);
  for (const CapsuleLink& l : own)
  {
    const Fiber& fib = model.fibers[l.fiber];
    LinkRecord rec{ l, std::min(fib.radii[l.k], fib.radii[l.k + 1]) };
    rec.link.fiber = static_cast<std::uint32_t>(global[l.fiber]);
    const double lo = std::min(l.p0[axis], l.p1[axis]), hi = std::max(l.p0[axis], l.p1[axis]);
    for (std::size_t q = 0; q < nr; ++q)
    {
      if (region[2 * q + 1] > -HUGE_VAL && within(lo, hi, -region[2 * q], region[2 * q + 1], reach, layout.period()))
        append(out[q], rec);
    }
  }
  TrafficCount sent;
  const std::vector<std::vector<char>> in = exchangeAll(out, comm, sent);
  std::vector<LinkRecord> all;
  std::vector<int> from;
  for (std::size_t q = 0; q < nr; ++q)
  {
    const std::vector<LinkRecord> part = records<LinkRecord>(in[q]);
    all.insert(all.end(), part.begin(), part.end());
    from.insert(from.end(), part.size(), static_cast<int>(q));
  }
  // Global link order: the pair list found among them is then the serial one's, restricted.
  std::vector<std::size_t> order(all.size());
  std::iota(order.begin(), order.end(), std::size_t{ 0 });
  std::sort(order.begin(), order.end(), [&all](std::size_t a, std::size_t b) {
    return std::tie(all[a].link.fiber, all[a].link.k) < std::tie(all[b].link.fiber, all[b].link.k);
  });
  held.resize(all.size());
  info.pointRadius.resize(all.size());
  info.owner.resize(all.size());
  info.tested.resize(all.size());
  for (std::size_t i = 0; i < order.size(); ++i)
  {
    const LinkRecord& rec = all[order[i]];
    held[i] = rec.link;
    info.pointRadius[i] = rec.pointRadius;
    info.owner[i] = from[order[i]];
    info.tested[i] = layout.testerOf(centre(rec.link, axis)) == me ? 1 : 0;
  }
  return sent;
}

std::vector<LinkPairPush> returnPushes(const std::vector<LinkPairPush>& tested, SolverComm& comm, TrafficCount& sent)
{
  std::vector<std::vector<char>> out(static_cast<std::size_t>(comm.size()));
  for (const LinkPairPush& p : tested)
  {
    append(out[static_cast<std::size_t>(p.ownerA)], p);
    if (p.ownerB != p.ownerA)
      append(out[static_cast<std::size_t>(p.ownerB)], p);
  }
  const std::vector<std::vector<char>> in = exchangeAll(out, comm, sent);
  std::vector<LinkPairPush> mine;
  for (const std::vector<char>& buffer : in)
  {
    const std::vector<LinkPairPush> part = records<LinkPairPush>(buffer);
    mine.insert(mine.end(), part.begin(), part.end());
  }
  std::sort(mine.begin(), mine.end(), [](const LinkPairPush& x, const LinkPairPush& y) {
    return std::tie(x.fiberA, x.kA, x.fiberB, x.kB) < std::tie(y.fiberA, y.kA, y.fiberB, y.kB);
  });
  return mine;
}

} // namespace fiberpli
