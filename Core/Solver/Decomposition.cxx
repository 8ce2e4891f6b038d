#include "Solver/Decomposition.h"

#include "Model/FiberWire.h"
#include "Parallel/Collectives.h"
#include "Util/ByteBuffer.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace fiberpli
{

namespace
{
// One fiber: the solver's per-fiber state, the fiber's own record (Model/FiberWire.h), then the
// solver's point state.
void writeFiber(ByteWriter& w, const RankFibers& r, std::size_t f)
{
  const CollisionSolverState& st = r.state;
  w.put<std::int64_t>(st.global[f]);
  w.put<std::int32_t>(st.home[f]);
  w.put<char>(st.active[f]);
  w.put<char>(st.closed[f]);
  w.put<Vec3>(st.closure[f]);
  putFiber(w, r.model.fibers[f]);
  w.putVector(st.points[f].velocity);
  w.putVector(st.points[f].source);
  w.putVector(st.points[f].inputRadii);
}

void readFiber(ByteReader& rd, RankFibers& r)
{
  CollisionSolverState& st = r.state;
  st.global.push_back(rd.get<std::int64_t>());
  st.home.push_back(rd.get<std::int32_t>());
  st.active.push_back(rd.get<char>());
  st.closed.push_back(rd.get<char>());
  st.closure.push_back(rd.get<Vec3>());
  Fiber fib = getFiber(rd);
  FiberPointState ps;
  rd.getVector(ps.velocity);
  rd.getVector(ps.source);
  rd.getVector(ps.inputRadii);
  st.points.push_back(std::move(ps));
  r.model.fibers.push_back(std::move(fib));
}

// Keeps the fibers with keep[f] and sorts everything by global index.
void keepAndSort(RankFibers& r, const std::vector<char>& keep)
{
  CollisionSolverState& st = r.state;
  std::vector<std::size_t> order;
  for (std::size_t f = 0; f < r.size(); ++f)
    if (keep[f])
      order.push_back(f);
  std::sort(order.begin(), order.end(),
    [&st](std::size_t a, std::size_t b) { return st.global[a] < st.global[b]; });
  const auto permute = [&order](auto& v)
  {
    std::remove_reference_t<decltype(v)> out;
    out.reserve(order.size());
    for (std::size_t i : order)
      out.push_back(std::move(v[i]));
    v = std::move(out);
  };
  permute(r.model.fibers);
  permute(st.points);
  permute(st.active);
  permute(st.closed);
  permute(st.closure);
  permute(st.global);
  permute(st.home);
}

// Extent [lo, hi] of a fiber's points along an axis.
void extent(const Fiber& f, int axis, double& lo, double& hi)
{
  lo = HUGE_VAL;
  hi = -HUGE_VAL;
  for (const Vec3& p : f.points)
  {
    lo = std::min(lo, p[axis]);
    hi = std::max(hi, p[axis]);
  }
}

TrafficCount send(RankFibers& r, const std::vector<std::vector<std::size_t>>& to,
  const std::vector<char>& keep, Comm& comm)
{
  TrafficCount t;
  std::vector<std::vector<char>> out(static_cast<std::size_t>(comm.size()));
  for (std::size_t q = 0; q < to.size(); ++q)
  {
    ByteWriter w(out[q]);
    for (std::size_t f : to[q])
      writeFiber(w, r, f);
    t.fibers += to[q].size();
    t.bytes += out[q].size();
  }
  keepAndSort(r, keep); // before the received fibers are appended: they are kept
  const std::vector<std::vector<char>> in = comm.exchange(out);
  for (const std::vector<char>& buffer : in)
  {
    ByteReader rd(buffer);
    while (!rd.done())
      readFiber(rd, r);
  }
  keepAndSort(r, std::vector<char>(r.size(), 1));
  return t;
}
} // namespace

SlabLayout SlabLayout::make(const FiberModel& local, const PeriodicCell& cell, Comm& comm)
{
  SlabLayout s;
  s.ranks_ = comm.size();
  s.periodic_ = cell.enabled();
  s.cell_ = cell;
  // Per axis: the fibers' summed extent (exactly over all ranks), the domain [lo, hi] the slabs
  // cut and the width `room` over which the fibers' middles, which decide the owners, spread.
  std::vector<std::int64_t> fibers{ 0 }; // with points, on all ranks
  for (const Fiber& f : local.fibers)
    fibers[0] += f.points.empty() ? 0 : 1;
  double extentSum[3];
  std::vector<double> m(12, -HUGE_VAL); // −lo, hi, −lowest middle, highest middle per axis
  for (int d = 0; d < 3; ++d)
  {
    ExactSum sum;
    for (const Fiber& f : local.fibers)
    {
      if (f.points.empty())
        continue;
      double a, b;
      extent(f, d, a, b);
      sum.add(b - a);
      m[d] = std::max(m[d], -a);
      m[3 + d] = std::max(m[3 + d], b);
      m[6 + d] = std::max(m[6 + d], -0.5 * (a + b));
      m[9 + d] = std::max(m[9 + d], 0.5 * (a + b));
    }
    extentSum[d] = sum.total(&comm);
  }
  comm.sum(fibers);
  comm.max(m);
  Vec3 lo, hi;
  double room[3];
  for (int d = 0; d < 3; ++d)
  {
    lo[d] = s.periodic_ ? cell.lo[d] : -m[d];
    hi[d] = s.periodic_ ? cell.hi[d] : m[3 + d];
    room[d] =
      s.periodic_ ? hi[d] - lo[d] : std::max(0.0, m[9 + d] + m[6 + d]); // middles wrap in a cell
  }
  // The axis with room for the most whole slabs that each own fibers and are wider than a fiber
  // and its halo: floor(room_a / (e_a + 2·reach)), e_a the mean fiber extent along a (a rank's
  // own fibers reach e_a/2 out of its slab on each side, its held links the pair reach 2·ρmax
  // beyond each face). Equal counts go to the axis of the shortest fibers (least summed extent:
  // fewest reach into other slabs), then to the lower axis. In an equal-sided cell that is
  // always the axis of the shortest fibers; in a section (1 cm × 1 cm × 60 µm, fibers in-plane
  // and shorter than the section) an in-plane axis, not the thickness. Whole slabs, because the
  // count is an estimate: an open cube's sides differ by where its outermost points lie, which
  // must not outweigh the fibers' extents. From exact sums and maxima: every rank picks the same
  // axis. Only axes the model spans: along a flat model's zero extent every link would be tested
  // on rank 0.
  const double reach = 2.0 * maxOverRanks(comm, largestRadius(local));
  const double n = static_cast<double>(fibers[0]);
  double slabs[3];
  for (int d = 0; d < 3; ++d)
  {
    const double need = extentSum[d] + 2.0 * n * reach; // N · (e_a + 2·reach)
    slabs[d] = need > 0.0 ? std::floor(room[d] * n / need) : 0.0;
  }
  const auto spans = [&](int d) { return hi[d] > lo[d]; };
  for (int d = 1; d < 3; ++d)
  {
    const int c = s.axis_;
    const bool better =
      slabs[d] > slabs[c] || (slabs[d] == slabs[c] && extentSum[d] < extentSum[c]);
    if (spans(d) && (!spans(c) || better))
      s.axis_ = d;
  }
  s.lo_ = lo[s.axis_];
  s.hi_ = hi[s.axis_];
  s.cutTesterSlabs(local, comm, -1);
  return s;
}

void SlabLayout::cutTesterSlabs(const FiberModel& local, Comm& comm, std::int64_t work)
{
  // A histogram of all ranks' link centres (exact integer sums, the same on every rank), cut
  // where its running sum passes k/R of the links: within one bin (1/4096 of [lo, hi]) of the
  // balanced cut. With the ranks' pair work (its R entries after the bins), each bin's links
  // weigh their slab's work per link instead of 1.
  constexpr std::size_t kBins = 4096;
  const std::size_t nr = static_cast<std::size_t>(ranks_);
  std::vector<std::int64_t> count(kBins + nr, 0);
  const std::size_t nf = hi_ > lo_ ? local.fibers.size() : 0; // (no copy of the piece)
  for (std::size_t i = 0; i < nf; ++i)
  {
    const Fiber& f = local.fibers[i];
    for (std::size_t k = 0; k + 1 < f.points.size(); ++k)
    {
      const double t = fraction(0.5 * (f.points[k][axis_] + f.points[k + 1][axis_]));
      const double bin = std::floor(t * static_cast<double>(kBins));
      ++count[bin < 0.0 ? 0 : bin >= kBins ? kBins - 1 : static_cast<std::size_t>(bin)];
    }
  }
  count[kBins + static_cast<std::size_t>(comm.rank())] = work;
  comm.sum(count);
  // Weight of one link of bin b: 1, or its slab's work per link (the current cuts lie on bin
  // edges, so a bin is in one slab). Every rank computes the same doubles in the same order.
  std::vector<double> weight(kBins, 1.0);
  if (work >= 0)
  {
    std::vector<std::int64_t> links(nr, 0);
    const auto slabOfBin = [this](std::size_t b)
    {
      return static_cast<std::size_t>(std::upper_bound(testCuts_.begin(), testCuts_.end(),
                                        static_cast<double>(b) / static_cast<double>(kBins)) -
        testCuts_.begin());
    };
    for (std::size_t b = 0; b < kBins; ++b)
      links[slabOfBin(b)] += count[b];
    for (std::size_t q = 0; q < nr; ++q)
    {
      if (links[q] > 0 && count[kBins + q] <= 0)
        return; // a slab with links and no measured work: keep the cuts
    }
    for (std::size_t b = 0; b < kBins; ++b)
    {
      const std::size_t q = slabOfBin(b);
      weight[b] =
        links[q] > 0 ? static_cast<double>(count[kBins + q]) / static_cast<double>(links[q]) : 0.0;
    }
  }
  double total = 0.0;
  for (std::size_t b = 0; b < kBins; ++b)
    total += weight[b] * static_cast<double>(count[b]);
  testCuts_.clear();
  double below = 0.0;
  std::size_t b = 0;
  for (int k = 1; k < ranks_; ++k)
  {
    // The first bin edge b with below(b) >= k/R of all (equal widths when there are no links).
    if (!(total > 0.0))
    {
      testCuts_.push_back(static_cast<double>(k) / ranks_);
      continue;
    }
    while (b < kBins && below * ranks_ < k * total)
    {
      below += weight[b] * static_cast<double>(count[b]);
      ++b;
    }
    testCuts_.push_back(static_cast<double>(b) / static_cast<double>(kBins));
  }
}

void SlabLayout::balanceTesterSlabs(const FiberModel& local, std::int64_t work, Comm& comm)
{
  cutTesterSlabs(local, comm, std::max<std::int64_t>(0, work));
}

double SlabLayout::fraction(double x) const
{
  const double t = (x - lo_) / (hi_ - lo_);
  return periodic_ ? t - std::floor(t) : t;
}

int SlabLayout::testerOf(double x) const
{
  if (ranks_ == 1 || !(hi_ > lo_))
  {
    return 0;
  }
  return static_cast<int>(
    std::upper_bound(testCuts_.begin(), testCuts_.end(), fraction(x)) - testCuts_.begin());
}

double SlabLayout::testerLo(int q) const
{
  const double t = q <= 0 ? 0.0 : q >= ranks_ ? 1.0 : testCuts_[static_cast<std::size_t>(q - 1)];
  return lo_ + (hi_ - lo_) * t;
}

int SlabLayout::owner(const Fiber& f) const
{
  if (f.points.empty() || ranks_ == 1 || !(hi_ > lo_))
  {
    return 0;
  }
  double a, b;
  extent(f, axis_, a, b);
  return slabOf(0.5 * (a + b));
}

int SlabLayout::slabOf(double x) const
{
  if (ranks_ == 1 || !(hi_ > lo_))
  {
    return 0;
  }
  const double slab = std::floor(fraction(x) * ranks_);
  return slab < 0.0 ? 0 : slab >= ranks_ ? ranks_ - 1 : static_cast<int>(slab);
}

double SlabLayout::wrapShift(double x) const
{
  return periodic_ ? cell_.wrapShift(x, axis_) : 0.0;
}

TrafficCount redistribute(RankFibers& r, const std::vector<int>& dest, Comm& comm)
{
  std::vector<std::vector<std::size_t>> to(static_cast<std::size_t>(comm.size()));
  std::vector<char> keep(r.size(), 1);
  for (std::size_t f = 0; f < r.size(); ++f)
  {
    if (dest[f] != comm.rank())
    {
      to[static_cast<std::size_t>(dest[f])].push_back(f);
      keep[f] = 0;
    }
  }
  return send(r, to, keep, comm);
}

} // namespace fiberpli
