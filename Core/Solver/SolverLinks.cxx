#include "Solver/SolverLinks.h"

#include "Parallel/Collectives.h"
#include "Solver/Decomposition.h"
#include "Solver/LinkExchange.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

// Offsets first (serial prefix sums), then the fibers in parallel: each writes its own range.
void buildLinks(const FiberModel& model, const std::vector<char>* active, int threads,
  std::vector<CapsuleLink>& links, std::vector<std::size_t>* pointOffset,
  const std::vector<char>* closed, double scale, std::vector<std::size_t>* fiberRuns)
{
  const std::size_t nf = model.fibers.size();
  std::vector<std::size_t> linkOffset(nf + 1, 0);
  if (pointOffset)
  {
    pointOffsets(model, *pointOffset);
  }
  std::size_t nLinks = 0;
  for (std::size_t f = 0; f < nf; ++f)
  {
    linkOffset[f] = nLinks;
    nLinks += linksOf(model, active, f);
  }
  linkOffset[nf] = nLinks;
  if (fiberRuns)
  {
    fiberRuns->clear();
    for (std::size_t f = 0; f < nf; ++f)
      if (linkOffset[f + 1] > linkOffset[f])
        fiberRuns->push_back(linkOffset[f]);
    fiberRuns->push_back(nLinks);
  }
  links.resize(nLinks);
  const std::int64_t n = static_cast<std::int64_t>(nf);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t ff = 0; ff < n; ++ff)
  {
    const std::size_t f = static_cast<std::size_t>(ff);
    const Fiber& fib = model.fibers[f];
    const std::size_t count = linkOffset[f + 1] - linkOffset[f];
    double arc = 0.0;
    for (std::size_t k = 0; k < count; ++k)
    {
      CapsuleLink& l = links[linkOffset[f] + k];
      l.p0 = fib.points[k];
      l.p1 = fib.points[k + 1];
      l.rho = capsuleRadius(fib.radii[k], fib.radii[k + 1], scale);
      l.fiber = static_cast<std::uint32_t>(f);
      l.k = static_cast<std::uint32_t>(k);
      l.arc0 = arc;
      arc += distance(l.p0, l.p1);
      l.arc1 = arc;
    }
    // Every link gets its closedLength (0 = open): `links` is reused from the last step, and a
    // stale length left on an open fiber's link would skip its real fold-back pairs.
    const double closedLength = closed && (*closed)[f] ? arc : 0.0;
    for (std::size_t k = 0; k < count; ++k)
    {
      links[linkOffset[f] + k].closedLength = closedLength;
    }
  }
}

void pointOffsets(const FiberModel& model, std::vector<std::size_t>& offsets)
{
  offsets.assign(model.fibers.size() + 1, 0);
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    offsets[f + 1] = offsets[f] + model.fibers[f].points.size();
  }
}

double medianRadius(const FiberModel& model, Comm* comm)
{
  std::vector<double> r;
  for (const Fiber& fib : model.fibers)
  {
    if (fib.points.size() >= 2)
    {
      r.insert(r.end(), fib.radii.begin(), fib.radii.end());
    }
  }
  if (comm)
  {
    std::vector<std::int64_t> n{ static_cast<std::int64_t>(r.size()) };
    comm->sum(n);
    return globalNthValue(r, n[0] / 2, *comm);
  }
  if (r.empty())
  {
    return 0.0;
  }
  std::nth_element(r.begin(), r.begin() + static_cast<long>(r.size() / 2), r.end());
  return r[r.size() / 2];
}

double capsuleVolume(const FiberModel& model, Comm* comm)
{
  ExactSum sum;
  for (const Fiber& f : model.fibers)
  {
    for (std::size_t k = 0; k + 1 < f.size(); ++k)
    {
      const double rho = f.linkRadius(k);
      sum.add(M_PI * rho * rho * distance(f.points[k], f.points[k + 1]));
    }
  }
  return sum.total(comm);
}

namespace
{
// What the solver keeps per point (model point and radius, velocity and source index, force) and
// per link (its capsule, the last detection's copy with its colliding and loud flags (QuietLinks)
// and the grid's buffers); links ≈ points.
constexpr double kBytesPerPoint = 2.0 * sizeof(Vec3) + 2.0 * sizeof(double) + sizeof(Vec3) +
  2.0 * sizeof(CapsuleLink) + 2.0 * sizeof(char);
} // namespace

double bytesPerPoint()
{
  return kBytesPerPoint + CollisionGrid::bytesPerLink();
}
double bytesPerPair()
{
  return CollisionGrid::bytesPerPair() + static_cast<double>(sizeof(LinkPairPush));
}

} // namespace fiberpli
