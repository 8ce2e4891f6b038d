#include "Solver/TortuosityHold.h"

#include "Solver/TortuosityControl.h"
#include "Util/NumberFormat.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace fiberpli
{

namespace
{
// Path length over span of the fiber with its deviation scaled by k.
double tortuosityScaled(const Fiber& f, const FiberDeviation& fd, double k)
{
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < f.size(); ++i)
  {
    const Vec3 a = f.points[i] + (k - 1.0) * fd.deviation[i];
    const Vec3 b = f.points[i + 1] + (k - 1.0) * fd.deviation[i + 1];
    length += distance(a, b);
  }
  return length / fd.span;
}

// Means are summed in fixed point (1e-9 of tortuosity excess) so that they are the same bits for
// any order of the fibers and any split over ranks.
constexpr double kFixedPoint = 1e9;

struct BundleIndex
{
  int first = 0; // smallest bundle id
  int count = 1; // bundles told apart (1: all pooled)
  std::size_t of(int bundle) const
  {
    return count == 1 ? 0 : static_cast<std::size_t>(bundle - first);
  }
};

// The bundles of the undulating fibers over all ranks (ids spanning at most 1024 values are told
// apart, else pooled).
BundleIndex bundleIndex(const FiberModel& model, const std::vector<char>& undulating, Comm* comm)
{
  std::vector<double> range{ -HUGE_VAL, -HUGE_VAL }; // −min, max
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    if (undulating[f])
    {
      range[0] = std::max(range[0], -static_cast<double>(model.fibers[f].bundle));
      range[1] = std::max(range[1], static_cast<double>(model.fibers[f].bundle));
    }
  }
  if (comm)
  {
    comm->max(range);
  }
  BundleIndex index;
  if (range[1] > -HUGE_VAL && range[1] + range[0] < 1024.0)
  {
    index.first = static_cast<int>(-range[0]);
    index.count = static_cast<int>(range[1] + range[0]) + 1;
  }
  return index;
}

// Each bundle's mean tortuosity over its undulating fibers, over all ranks (0 for a bundle
// without any). closures: per fiber its closure through the cell, null for an open fiber (a solve
// keeps a closure exactly).
std::vector<double> bundleMeans(const FiberModel& model, const std::vector<char>& undulating,
  const std::vector<const Vec3*>& closures, const BundleIndex& index, Comm* comm)
{
  const std::size_t nb = static_cast<std::size_t>(index.count);
  std::vector<std::int64_t> sums(2 * nb, 0); // excess sum, fibers
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fib = model.fibers[f];
    if (!undulating[f])
    {
      continue;
    }
    const double tau = fiberTortuosity(fib, closures[f]);
    const std::size_t b = index.of(fib.bundle);
    sums[2 * b] += static_cast<std::int64_t>(std::llround((tau - 1.0) * kFixedPoint));
    sums[2 * b + 1] += 1;
  }
  if (comm)
  {
    comm->sum(sums);
  }
  std::vector<double> means(nb, 0.0);
  for (std::size_t b = 0; b < nb; ++b)
  {
    if (sums[2 * b + 1] > 0)
    {
      means[b] =
        1.0 + static_cast<double>(sums[2 * b]) / kFixedPoint / static_cast<double>(sums[2 * b + 1]);
    }
  }
  return means;
}
} // namespace

double scaleUndulation(Fiber& f, double target, const Vec3* closure)
{
  const std::size_t n = f.size();
  if (n < 3 || !(fiberTortuosity(f, closure) > 1.0))
  {
    return 1.0;
  }
  const FiberDeviation fd = fiberDeviation(f, closure);
  // τ(k) grows with k (a fiber's links lengthen as its deviation grows): bisection.
  double lo = 0.0, hi = 1.0;
  if (tortuosityScaled(f, fd, 0.0) >= target)
  {
    hi = 0.0;
  }
  else
  {
    while (tortuosityScaled(f, fd, hi) < target && hi < 1e6)
    {
      lo = hi;
      hi *= 2.0;
    }
    for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i)
    {
      const double mid = 0.5 * (lo + hi);
      (tortuosityScaled(f, fd, mid) < target ? lo : hi) = mid;
    }
  }
  const double k = hi;
  // The ends of an open fiber have no deviation and stay exactly.
  const std::size_t first = closure ? 0 : 1;
  for (std::size_t i = first; i + 1 < n; ++i)
  {
    f.points[i] += (k - 1.0) * fd.deviation[i];
  }
  if (closure)
  {
    f.points.back() = f.points.front() + *closure; // exactly, whatever the rounding
  }
  return k;
}

CollisionSolverResult solveHoldingTortuosity(
  FiberModel& model, const CollisionSolverOptions& options, const ProgressFn& progress, Comm* comm)
{
  const double target = options.tortuosity;
  CollisionSolverOptions once = options;
  once.holdTortuosity = false;
  if (!options.holdTortuosity)
  {
    return solveCollisions(model, once, progress, {}, comm);
  }
  CollisionSolverResult result;
  result.error = validateCollisionSolverOptions(options); // Tortuosity > 1 among them
  if (!result.error.empty())
  {
    return result;
  }
  const PeriodicCell& cell = options.periodicCell;
  // The fibers that undulate in the input: the ones the hold scales and measures.
  std::vector<char> undulating(model.fibers.size(), 0);
  std::vector<Vec3> closure(model.fibers.size());
  std::vector<const Vec3*> closures(model.fibers.size(), nullptr); // null: open
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fib = model.fibers[f];
    if (cell.enabled() && isClosedFiber(fib, cell, closure[f]))
    {
      closures[f] = &closure[f];
    }
    undulating[f] = fib.size() >= 3 && fiberTortuosity(fib, closures[f]) > 1.0 ? 1 : 0;
  }
  const BundleIndex index = bundleIndex(model, undulating, comm);
  const std::size_t nb = static_cast<std::size_t>(index.count);
  const double tolerance = kTortuosityHoldTolerance * (target - 1.0);
  // Per bundle: the input tortuosity of this solve (x) and the last solve's (x, solved y).
  std::vector<double> x = bundleMeans(model, undulating, closures, index, comm);
  std::vector<double> lastX(nb, 0.0), lastY(nb, 0.0);
  for (int solve = 0; solve < kTortuosityHoldSolves; ++solve)
  {
    FiberModel trial = model;
    CollisionSolverOptions o = once;
    if (solve > 0)
    {
      double lowest = target;
      for (std::size_t f = 0; f < trial.fibers.size(); ++f)
      {
        if (undulating[f])
        {
          scaleUndulation(trial.fibers[f], x[index.of(trial.fibers[f].bundle)], closures[f]);
        }
      }
      for (std::size_t b = 0; b < nb; ++b)
      {
        lowest = x[b] > 1.0 ? std::min(lowest, x[b]) : lowest;
      }
      // The rule keeps every fiber at least at the lowest input asked: pushes must not flatten
      // what the weave does not replace.
      o.tortuosity = lowest;
    }
    const ProgressFn share = [&progress, solve](double done)
    { return reportProgress(progress, (solve + done) / kTortuosityHoldSolves); };
    result = solveCollisions(trial, o, progress ? share : ProgressFn{}, {}, comm);
    result.tortuositySolves = solve + 1;
    if (!result.error.empty() || result.aborted)
    {
      return result; // the model stays the input
    }
    const std::vector<double> y = bundleMeans(trial, undulating, closures, index, comm);
    bool off = false;
    std::vector<double> next = x;
    for (std::size_t b = 0; b < nb; ++b)
    {
      if (!(y[b] > 0.0) || std::abs(y[b] - target) <= tolerance)
      {
        continue;
      }
      off = true;
      // Secant on (input, solved): the weave grows a little with the undulation; the first step
      // takes it as constant (slope 1).
      double slope = 1.0;
      if (solve > 0 && std::abs(x[b] - lastX[b]) > 1e-12)
      {
        slope = std::clamp((y[b] - lastY[b]) / (x[b] - lastX[b]), 0.25, 4.0);
      }
      next[b] = std::clamp(x[b] + (target - y[b]) / slope, 1.0 + 0.05 * (target - 1.0),
        std::min(3.0, 1.0 + 2.0 * (target - 1.0)));
      lastX[b] = x[b];
      lastY[b] = y[b];
    }
    if (!off || solve + 1 == kTortuosityHoldSolves)
    {
      for (std::size_t b = 0; off && b < nb; ++b)
      {
        if (y[b] > 0.0 && std::abs(y[b] - target) > tolerance)
        {
          const std::string which = index.count == 1
            ? std::string("the fibers have")
            : "bundle " + std::to_string(index.first + static_cast<int>(b)) + " has";
          result.warnings.push_back("HoldTortuosity: " + which + " a mean tortuosity of " +
            formatNumber(y[b]) + " after " + std::to_string(kTortuosityHoldSolves) +
            " solves (target " + formatNumber(target) + ")");
        }
      }
      model = std::move(trial);
      return result;
    }
    x = next;
  }
  return result; // not reached
}

} // namespace fiberpli
