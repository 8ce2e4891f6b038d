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

BoxLayout BoxLayout::make(const FiberModel& local, const PeriodicCell& cell, Comm& comm)
{
  BoxLayout s;
  s.ranks_ = comm.size();
  s.periodic_ = cell.enabled();
  s.cell_ = cell;
  // Per axis, exactly over all ranks: the links' summed extent and count, the bounds of all points
  // (the domain without a cell) and of the link centres (the room they spread over).
  std::vector<std::int64_t> links{ 0 };
  double extentSum[3];
  std::vector<double> m(12, -HUGE_VAL); // −lo, hi of the points, −lo, hi of the centres, per axis
  for (int d = 0; d < 3; ++d)
  {
    ExactSum sum;
    for (const Fiber& f : local.fibers)
    {
      for (std::size_t k = 0; k < f.points.size(); ++k)
      {
        const double x = f.points[k][d];
        m[d] = std::max(m[d], -x);
        m[3 + d] = std::max(m[3 + d], x);
        if (k + 1 < f.points.size())
        {
          const double y = f.points[k + 1][d];
          sum.add(std::fabs(y - x));
          const double c = 0.5 * (x + y);
          m[6 + d] = std::max(m[6 + d], -c);
          m[9 + d] = std::max(m[9 + d], c);
          links[0] += d == 0 ? 1 : 0;
        }
      }
    }
    extentSum[d] = sum.total(&comm);
  }
  comm.sum(links);
  comm.max(m);
  const double reach = 2.0 * maxOverRanks(comm, largestRadius(local));
  double room[3], halo[3];
  for (int d = 0; d < 3; ++d)
  {
    s.lo_[d] = s.periodic_ ? cell.lo[d] : (m[d] > -HUGE_VAL ? -m[d] : 0.0);
    s.hi_[d] = s.periodic_ ? cell.hi[d] : (m[3 + d] > -HUGE_VAL ? m[3 + d] : 0.0);
    room[d] = s.periodic_ ? s.hi_[d] - s.lo_[d] : std::max(0.0, m[9 + d] + m[6 + d]);
    halo[d] = (links[0] > 0 ? extentSum[d] / static_cast<double>(links[0]) : 0.0) + reach;
  }
  // The factorisation of least held volume per rank: a box of widths w_d holds the links whose
  // centres lie within about h_d of it (its own links reach half their extent out, a partner's
  // half its extent in, and the pair reach between them). Boxes thinner than their halo, or cuts
  // of an axis the model does not span, are taken only when nothing else is possible (many ranks
  // on a small model). Enumerated with the most cuts along x first: equal volumes keep the first.
  const int R = s.ranks_;
  double best = HUGE_VAL;
  bool bestFits = false;
  for (int nx = R; nx >= 1; --nx)
  {
    if (R % nx != 0)
      continue;
    for (int ny = R / nx; ny >= 1; --ny)
    {
      if ((R / nx) % ny != 0)
        continue;
      const int n[3] = { nx, ny, R / nx / ny };
      bool spans = true, fits = true;
      double volume = 1.0;
      for (int d = 0; d < 3; ++d)
      {
        const double w = room[d] / n[d];
        spans = spans && (n[d] == 1 || (s.hi_[d] > s.lo_[d] && room[d] > 0.0));
        fits = fits && (n[d] == 1 || w >= halo[d]);
        volume *= w + 2.0 * halo[d];
      }
      if (spans && ((fits && !bestFits) || (fits == bestFits && volume < best)))
      {
        best = volume;
        bestFits = fits;
        s.n_[0] = n[0];
        s.n_[1] = n[1];
        s.n_[2] = n[2];
      }
    }
  }
  if (best == HUGE_VAL) // no axis is spanned: one layer along x holds everything in its first box
  {
    s.n_[0] = R;
    s.n_[1] = s.n_[2] = 1;
  }
  s.cutTesterBoxes(local, comm, -1);
  return s;
}

void BoxLayout::indicesOf(int r, int idx[3]) const
{
  idx[2] = r % n_[2];
  idx[1] = (r / n_[2]) % n_[1];
  idx[0] = r / (n_[2] * n_[1]);
}

void BoxLayout::cutTesterBoxes(const FiberModel& local, Comm& comm, std::int64_t work)
{
  // Per axis a histogram of all ranks' link centres (exact integer sums, the same on every rank),
  // cut where its running sum passes k/n_d of the links: within one bin (1/4096 of the axis) of
  // the balanced cut. With the boxes' pair work, each link weighs its box's work per link instead
  // of 1, in fixed point (2^20 for the costliest box) so that the sums stay exact integers. One
  // pass over the links makes a histogram per tester box they lie in (a rank's links lie in a few)
  // along the axes that are cut; the weights, known once every rank's boxes are counted, then
  // scale them: the same integer sums as weighing each link.
  constexpr std::size_t kBins = 4096;
  const std::size_t nr = static_cast<std::size_t>(ranks_);
  std::vector<int> axes; // the axes with more than one layer and a span
  for (int d = 0; d < 3; ++d)
    if (n_[d] > 1 && hi_[d] > lo_[d])
      axes.push_back(d);
  const std::size_t na = axes.size();
  std::vector<int> boxOfSlot;           // the tester box of each histogram
  std::vector<std::int64_t> histograms; // per slot, per cut axis, kBins counts
  std::vector<std::int64_t> linksOfSlot;
  int lastBox = -1;
  std::size_t lastSlot = 0;
  for (const Fiber& f : local.fibers)
  {
    for (std::size_t k = 0; k + 1 < f.points.size(); ++k)
    {
      const Vec3 c = 0.5 * (f.points[k] + f.points[k + 1]);
      const int box = work >= 0 ? testerOf(c) : 0; // unweighed: one histogram
      if (box != lastBox)
      {
        lastBox = box;
        lastSlot = static_cast<std::size_t>(
          std::find(boxOfSlot.begin(), boxOfSlot.end(), box) - boxOfSlot.begin());
        if (lastSlot == boxOfSlot.size())
        {
          boxOfSlot.push_back(box);
          linksOfSlot.push_back(0);
          histograms.resize(histograms.size() + na * kBins, 0);
        }
      }
      ++linksOfSlot[lastSlot];
      std::int64_t* h = histograms.data() + lastSlot * na * kBins;
      for (std::size_t a = 0; a < na; ++a)
      {
        const double bin = std::floor(fraction(axes[a], c[axes[a]]) * static_cast<double>(kBins));
        ++h[a * kBins + (bin < 0.0 ? 0 : bin >= kBins ? kBins - 1 : static_cast<std::size_t>(bin))];
      }
    }
  }
  std::vector<std::int64_t> weight(nr, 1); // per box
  if (work >= 0)
  {
    std::vector<std::int64_t> perBox(2 * nr, 0); // links (current cuts), then work
    for (std::size_t s = 0; s < boxOfSlot.size(); ++s)
      perBox[static_cast<std::size_t>(boxOfSlot[s])] += linksOfSlot[s];
    perBox[nr + static_cast<std::size_t>(comm.rank())] = work;
    comm.sum(perBox);
    double most = 0.0;
    for (std::size_t q = 0; q < nr; ++q)
    {
      if (perBox[q] > 0 && perBox[nr + q] <= 0)
        return; // a box with links and no measured work: keep the cuts
      if (perBox[q] > 0)
        most = std::max(most, static_cast<double>(perBox[nr + q]) / static_cast<double>(perBox[q]));
    }
    if (!(most > 0.0))
      return;
    for (std::size_t q = 0; q < nr; ++q)
      weight[q] = perBox[q] > 0 ? std::llround(static_cast<double>(perBox[nr + q]) /
                                    static_cast<double>(perBox[q]) / most * 1048576.0)
                                : 0;
  }
  std::vector<std::int64_t> count(3 * kBins, 0);
  for (std::size_t s = 0; s < boxOfSlot.size(); ++s)
  {
    const std::int64_t w = weight[static_cast<std::size_t>(boxOfSlot[s])];
    const std::int64_t* h = histograms.data() + s * na * kBins;
    for (std::size_t a = 0; a < na; ++a)
      for (std::size_t b = 0; b < kBins; ++b)
        count[static_cast<std::size_t>(axes[a]) * kBins + b] += w * h[a * kBins + b];
  }
  comm.sum(count);
  for (int d = 0; d < 3; ++d)
  {
    const std::int64_t* h = count.data() + d * kBins;
    std::int64_t total = 0;
    for (std::size_t b = 0; b < kBins; ++b)
      total += h[b];
    cuts_[d].clear();
    std::int64_t below = 0;
    std::size_t b = 0;
    for (int k = 1; k < n_[d]; ++k)
    {
      // The first bin edge b with below(b) >= k/n of all (equal widths when there are no links).
      if (total <= 0)
      {
        cuts_[d].push_back(static_cast<double>(k) / n_[d]);
        continue;
      }
      while (b < kBins &&
        static_cast<double>(below) * n_[d] < static_cast<double>(k) * static_cast<double>(total))
      {
        below += h[b];
        ++b;
      }
      cuts_[d].push_back(static_cast<double>(b) / static_cast<double>(kBins));
    }
  }
}

void BoxLayout::balanceTesterBoxes(const FiberModel& local, std::int64_t work, Comm& comm)
{
  cutTesterBoxes(local, comm, std::max<std::int64_t>(0, work));
}

double BoxLayout::largestCutMove(const BoxLayout& before) const
{
  double moved = 0.0;
  for (int d = 0; d < 3; ++d)
    for (std::size_t i = 0; i < cuts_[d].size() && i < before.cuts_[d].size(); ++i)
      moved = std::max(moved, std::fabs(cuts_[d][i] - before.cuts_[d][i]));
  return moved;
}

double BoxLayout::cut(int d, int i, bool owners) const
{
  const double t = i <= 0 ? 0.0
    : i >= n_[d]          ? 1.0
    : owners              ? static_cast<double>(i) / n_[d]
                          : cuts_[d][static_cast<std::size_t>(i - 1)];
  return lo_[d] + (hi_[d] - lo_[d]) * t;
}

LayoutBox BoxLayout::box(int r, bool owners) const
{
  int idx[3];
  indicesOf(r, idx);
  LayoutBox b;
  for (int d = 0; d < 3; ++d)
  {
    b.lo[d] = !periodic_ && idx[d] == 0 ? -HUGE_VAL : cut(d, idx[d], owners);
    b.hi[d] = !periodic_ && idx[d] + 1 == n_[d] ? HUGE_VAL : cut(d, idx[d] + 1, owners);
  }
  return b;
}

Vec3 BoxLayout::middle(const Fiber& f)
{
  // One pass over the points for the three axes (the solver asks every step).
  Vec3 lo{ HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi{ -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
  for (const Vec3& p : f.points)
  {
    lo = componentMin(lo, p);
    hi = componentMax(hi, p);
  }
  return middleOf(lo, hi);
}

int BoxLayout::owner(const Fiber& f) const
{
  if (f.points.empty() || ranks_ == 1)
  {
    return 0;
  }
  return ownerOf(middle(f));
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
