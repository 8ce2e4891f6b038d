#include "Index/PeriodicPairs.h"

#include "Util/Threads.h"

#include <algorithm>
#include <sstream>

namespace fiberpli
{

namespace
{
CapsuleLink shifted(const CapsuleLink& l, const Vec3& t)
{
  CapsuleLink s = l;
  s.p0 += t;
  s.p1 += t;
  return s;
}

double boxEdge(const CapsuleLink& l, double gap)
{
  const Vec3 d = l.p1 - l.p0;
  return std::max(std::fabs(d.x), std::max(std::fabs(d.y), std::fabs(d.z))) + 2.0 * l.rho + gap;
}
} // namespace

// Reach w: two boxes that overlap have centres closer than w on every axis.
double PeriodicPairs::reach(const std::vector<CapsuleLink>& links, double minimumGap)
{
  double w = 0.0;
  for (const CapsuleLink& l : links)
  {
    w = std::max(w, boxEdge(l, minimumGap));
  }
  return w;
}

std::string PeriodicPairs::cellTooSmall(double w, const PeriodicCell& cell)
{
  return periodicReachProblem(cell, w); // the one rule (Geometry/PeriodicCell.h)
}

std::string PeriodicPairs::cellTooSmall(
  const std::vector<CapsuleLink>& links, const PeriodicCell& cell, double minimumGap)
{
  return links.empty() ? std::string() : cellTooSmall(reach(links, minimumGap), cell);
}

std::string PeriodicPairs::findPairs(const std::vector<CapsuleLink>& links,
  const PeriodicCell& cell, double minimumGap, int threads, std::vector<CapsulePair>& pairs,
  std::size_t maxPairs, bool* overflow, const std::vector<char>* tested,
  const std::vector<char>* loud)
{
  pairs.clear();
  work_ = 0;
  if (overflow)
  {
    *overflow = false;
  }
  const std::size_t n = links.size();
  if (n == 0)
  {
    return {};
  }
  const double w = reach(links, minimumGap);
  const Vec3 e = cell.edge();
  const std::string tooSmall = cellTooSmall(w, cell);
  if (!tooSmall.empty())
  {
    return tooSmall;
  }
  // The links wrapped into the cell (ids 0..n-1), then their ghosts: every combination of the
  // faces a wrapped link is within w of (at most one face per axis since the cell exceeds 2w),
  // the zero shift excluded, in the order of their links. Counted per link first, so that both
  // are written in parallel.
  images_.resize(n);
  ghostStart_.resize(n + 1);
  const std::int64_t nn = static_cast<std::int64_t>(n);
  const int nThreads = resolveThreadCount(threads);
  const auto faceShifts = [&cell, &e, w](
                            const CapsuleLink& wrapped, double(&options)[3][2], int(&count)[3])
  {
    const Vec3 c = 0.5 * (wrapped.p0 + wrapped.p1);
    int ghosts = 1;
    for (int d = 0; d < 3; ++d)
    {
      options[d][0] = 0.0;
      count[d] = 1;
      if (c[d] - cell.lo[d] < w)
      {
        options[d][count[d]++] = e[d];
      }
      else if (cell.hi[d] - c[d] < w)
      {
        options[d][count[d]++] = -e[d];
      }
      ghosts *= count[d];
    }
    return ghosts - 1;
  };
#pragma omp parallel for num_threads(nThreads) schedule(static)
  for (std::int64_t ii = 0; ii < nn; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const CapsuleLink& l = links[i];
    images_[i] = shifted(l, cell.wrapShift(0.5 * (l.p0 + l.p1)));
    double options[3][2];
    int count[3];
    ghostStart_[i + 1] = static_cast<std::size_t>(faceShifts(images_[i], options, count));
  }
  ghostStart_[0] = n;
  for (std::size_t i = 0; i < n; ++i)
  {
    ghostStart_[i + 1] += ghostStart_[i];
  }
  images_.resize(ghostStart_[n]);
  source_.resize(ghostStart_[n] - n);
#pragma omp parallel for num_threads(nThreads) schedule(static)
  for (std::int64_t ii = 0; ii < nn; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const CapsuleLink& real = images_[i];
    double options[3][2];
    int count[3];
    faceShifts(real, options, count);
    std::size_t next = ghostStart_[i];
    for (int ix = 0; ix < count[0]; ++ix)
    {
      for (int iy = 0; iy < count[1]; ++iy)
      {
        for (int iz = 0; iz < count[2]; ++iz)
        {
          if (ix == 0 && iy == 0 && iz == 0)
          {
            continue;
          }
          const Vec3 t{ options[0][ix], options[1][iy], options[2][iz] };
          images_[next] = shifted(real, t);
          source_[next - n] = static_cast<std::uint32_t>(i);
          ++next;
        }
      }
    }
  }
  // Only pairs whose lower id is a real link are tested (a real link's own tested entry, 1
  // serially), never two ghosts: such a pair is an image of one found elsewhere. Each physical
  // pair then has at most two raw copies (real a with the ghost of b, real b with the ghost of
  // a), so more than twice the limit of raw pairs means more than the limit of physical ones, and
  // the physical count is checked after the deduplication below.
  const std::size_t rawLimit =
    maxPairs > static_cast<std::size_t>(-1) / 2 ? maxPairs : 2 * maxPairs;
  if (tested)
  {
    imageTested_.assign(tested->begin(), tested->end());
  }
  else
  {
    imageTested_.assign(n, 1);
  }
  imageTested_.resize(images_.size(), 0);
  if (loud)
  {
    // A pair of images is skipped when both links are quiet: then no image of the pair collides.
    imageLoud_.assign(loud->begin(), loud->end());
    imageLoud_.resize(images_.size());
    for (std::size_t g = n; g < images_.size(); ++g)
      imageLoud_[g] = (*loud)[source_[g - n]];
  }
  const bool within = grid_.findPairs(images_, minimumGap, threads, raw_, rawLimit, &imageTested_,
    TestedPairs::LowerLink, loud ? &imageLoud_ : nullptr);
  work_ = grid_.work();
  if (!within)
  {
    if (overflow)
    {
      *overflow = true;
    }
    return {};
  }
  // raw_ pairs have a < b; real ids are < n, ghosts >= n (no pair of two ghosts is tested);
  // (real a, ghost of b) and (real b, ghost of a) are the same pair: keep the
  // one whose real link has the smaller id, evaluated with it first (as a real pair would be).
  pairs.reserve(raw_.size());
  for (const CapsulePair& p : raw_)
  {
    if (p.b < n)
    {
      pairs.push_back(p);
    }
    else if (p.a < n)
    {
      const std::uint32_t b = source_[p.b - n];
      if (p.a < b)
      {
        CapsulePair q = p;
        q.b = b;
        pairs.push_back(q);
      }
    }
  }
  if (pairs.size() > maxPairs)
  {
    pairs.clear();
    if (overflow)
    {
      *overflow = true;
    }
    return {};
  }
  std::sort(pairs.begin(), pairs.end(),
    [](const CapsulePair& x, const CapsulePair& y) { return x.a != y.a ? x.a < y.a : x.b < y.b; });
  return {};
}

} // namespace fiberpli
