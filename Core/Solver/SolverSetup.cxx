// SolverEngine set-up: the fibers prepared for solving, the closures of a periodic cell, the
// segment length and the step cap with their warnings (docs/solver.md §4.2, §5, §9).
#include "Solver/SolverEngine.h"
#include "Util/NumberFormat.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace fiberpli
{

namespace
{
// Repeated consecutive points have no direction (§9): keep the first of a run.
std::size_t removeRepeatedPoints(Fiber& f, FiberPointState& st)
{
  std::size_t removed = 0;
  std::size_t out = 0;
  for (std::size_t i = 0; i < f.points.size(); ++i)
  {
    if (out > 0 && f.points[i] == f.points[out - 1])
    {
      ++removed;
      continue;
    }
    f.points[out] = f.points[i];
    f.radii[out] = f.radii[i];
    st.source[out] = st.source[i];
    ++out;
  }
  f.points.resize(out);
  f.radii.resize(out);
  st.source.resize(out);
  st.velocity.assign(out, Vec3{});
  return removed;
}
} // namespace

void prepareFibers(SolverEngine& s, std::vector<std::string>& warnings)
{
  const std::size_t nf = s.model_.fibers.size();
  s.st_.points.resize(nf);
  s.st_.active.assign(nf, 1);
  std::size_t repeated = 0;
  std::size_t tooShort = 0;
  for (std::size_t f = 0; f < nf; ++f)
  {
    Fiber& fib = s.model_.fibers[f];
    FiberPointState& st = s.st_.points[f];
    st.source.resize(fib.points.size());
    for (std::size_t i = 0; i < fib.points.size(); ++i)
    {
      st.source[i] = static_cast<double>(i);
    }
    st.inputRadii = fib.radii;
    if (fib.points.size() >= 2)
    {
      // A fiber of identical points would collapse to one point: leave it as it came.
      Fiber copy = fib;
      FiberPointState stCopy = st;
      const std::size_t r = removeRepeatedPoints(copy, stCopy);
      if (copy.points.size() >= 2)
      {
        fib = std::move(copy);
        st = std::move(stCopy);
        repeated += r;
      }
    }
    st.velocity.assign(fib.points.size(), Vec3{});
    bool degenerate = fib.points.size() < 2;
    for (std::size_t i = 1; !degenerate && i < fib.points.size(); ++i)
    {
      degenerate = fib.points[i] == fib.points[i - 1];
    }
    if (degenerate)
    {
      ++tooShort;
      s.st_.active[f] = 0;
    }
  }
  if (s.comm_) // the warnings count all ranks
  {
    std::vector<std::int64_t> n{ static_cast<std::int64_t>(repeated),
      static_cast<std::int64_t>(tooShort) };
    s.comm_->sum(n);
    repeated = static_cast<std::size_t>(n[0]);
    tooShort = static_cast<std::size_t>(n[1]);
  }
  if (repeated > 0)
  {
    warnings.push_back(formatNumber(repeated) + " repeated consecutive points removed");
  }
  if (tooShort > 0)
  {
    warnings.push_back(formatNumber(tooShort) +
      " fibers with fewer than 2 distinct points are not solved (copied through)");
  }
}

void prepareClosures(SolverEngine& s)
{
  const std::size_t nf = s.model_.fibers.size();
  s.st_.closed.assign(nf, 0);
  s.st_.closure.assign(nf, Vec3{});
  if (!s.periodic())
  {
    return;
  }
  for (std::size_t f = 0; f < nf; ++f)
  {
    const Fiber& fib = s.model_.fibers[f];
    s.st_.closed[f] = s.st_.active[f] && isClosedFiber(fib, s.o_.periodicCell, s.st_.closure[f]);
    s.close(f);
  }
}

double initialScale(const CollisionSolverOptions& o)
{
  if (o.initialRadiusScale > 0.0)
  {
    return o.initialRadiusScale;
  }
  return 1.0; // growth measured slower than plain pushing so far (bench/README.md)
}

double resolveSegmentLength(SolverEngine& s, const CollisionSolverOptions& o)
{
  const double l = o.segmentLength == 0.0 ? 2.0 * s.median() : o.segmentLength;
  return l == 0.0 ? -1.0 : l; // no fibers to take a radius from
}

void configure(SolverEngine& s, std::vector<std::string>& warnings)
{
  const std::size_t nf = s.model_.fibers.size();
  const double rMedian = s.median();
  double rMin = HUGE_VAL;
  for (std::size_t f = 0; f < nf; ++f)
  {
    if (s.st_.active[f])
    {
      for (double r : s.model_.fibers[f].radii)
      {
        rMin = std::min(rMin, r);
      }
    }
  }
  if (s.comm_)
  {
    rMin = minOverRanks(*s.comm_, rMin);
  }
  if (rMin == HUGE_VAL)
  {
    rMin = 0.0;
  }
  // The step cap follows the smallest radius (a thin fiber must not be jumped over), so broadly
  // polydisperse radii slow every fiber down; dense cells of them need a larger MaxDisplacement
  // (0.4 where the default leaves collisions, docs/solver.md §4.2).
  if (rMin < 0.5 * rMedian && s.o_.maxDisplacement < 0.4)
  {
    warnings.push_back("smallest radius " + formatNumber(rMin) +
      " is below 1/2 of the median radius " + formatNumber(rMedian) +
      ": every point moves at most MaxDisplacement " + formatNumber(s.o_.maxDisplacement) +
      " x this radius = " + formatNumber(s.o_.maxDisplacement * rMin) +
      " um per step (slow; dense targets of such radii may need MaxDisplacement 0.4)");
  }
  if (s.o_.maxDisplacement > 1.0)
  {
    warnings.push_back("MaxDisplacement " + formatNumber(s.o_.maxDisplacement) +
      " is above 1: a point may move farther than the thinnest fiber's radius per step, so fibers "
      "can "
      "pass through each other unseen");
  }
  s.st_.vMax = s.o_.maxDisplacement * rMin;
  // Parameter sanity (§5.2): warn, do not fail.
  double rMax = largestRadius(s.model_);
  if (s.comm_)
  {
    rMax = maxOverRanks(*s.comm_, rMax);
  }
  if (s.o_.minCurvatureRadius > 0.0 && s.o_.minCurvatureRadius < rMax)
  {
    warnings.push_back("MinCurvatureRadius " + formatNumber(s.o_.minCurvatureRadius) +
      " is below the largest radius " + formatNumber(rMax) +
      ": a tube bent that tightly intersects itself on the inside");
  }
  if (s.st_.segmentLength > 0.0 && s.o_.minCurvatureRadius > 0.0 &&
    s.o_.minCurvatureRadius < s.st_.segmentLength / std::sqrt(3.0))
  {
    warnings.push_back("MinCurvatureRadius " + formatNumber(s.o_.minCurvatureRadius) +
      " is below SegmentLength/sqrt(3): only the 60 degree rule can act");
  }
  if (s.st_.segmentLength > 0.0 && s.st_.segmentLength < 0.25 * rMedian)
  {
    warnings.push_back("SegmentLength " + formatNumber(s.st_.segmentLength) +
      " is below 1/4 of the median radius: many points, slow and memory hungry");
  }
}

} // namespace fiberpli
