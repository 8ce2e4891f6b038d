// CollisionSolverRun: the steps, their stop rules and the result (docs/solver.md §6, §9).
#include "Solver/SolverRun.h"

#include "Solver/PushBoost.h"
#include "Util/NumberFormat.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fiberpli
{

namespace
{
// [ours] Radius growth per step while the deepest overlap is below 5 % of the median radius, and
// the move steps without growth after which growth gives up.
constexpr double kGrowth = 0.002;
constexpr int kGrowthStall = 2000;
// From this many links a step takes long enough (~0.1 s per 1e5 links on one core) that abort
// is also checked in the middle of a step.
constexpr std::size_t kLinksForMidStepProgress = 200000;
} // namespace

bool CollisionSolverRun::step()
{
  Impl& r = *impl_;
  if (r.phase != Impl::Phase::Running)
  {
    return false;
  }
  SolverEngine& s = r.s;
  CollisionSolverState& st = s.st_;
  const CollisionSolverOptions& o = r.options;
  const bool changed = s.shapeControl();
  if (s.comm_)
  {
    s.balanceTesters();
  }
  SolverEngine::Counts counts;
  if (!s.detect(&counts, changed))
  {
    r.failDetection(" (at step " + formatNumber(st.steps) + ")");
    return false;
  }
  st.changed = counts.changed;
  const std::size_t count = counts.pairs;
  // Progress: the larger of the steps' share of MaxSteps and the collisions resolved since the
  // first step (log scale: the last few take most of the steps), never going back.
  if (st.firstCount == static_cast<std::size_t>(-1))
  {
    st.firstCount = count;
    st.pushScale = pushScaleFor(count, counts.links, o.pushBoost);
  }
  const double stepShare = r.stepShareAfter(st.steps);
  const double resolved = st.firstCount > 0
    ? 1.0 - std::log1p(static_cast<double>(count)) / std::log1p(static_cast<double>(st.firstCount))
    : 1.0;
  st.done = std::max(st.done, std::min(0.99, std::max(stepShare, resolved)));
  // A step of a large model takes long (~0.1 s per 1e5 links): then abort is also checked
  // between its two long phases (shape control and detection; moves), so a stop request waits
  // for at most one phase. Decided by size, not by the clock, so that where a solve stops for a
  // given progress callback is reproducible on any machine and under any load.
  if (counts.links >= kLinksForMidStepProgress && !r.report(std::max(st.done, 1e-9)))
  {
    r.result.aborted = true;
    st.changed = !s.shapeWithinLimits();
    r.phase = Impl::Phase::Ended;
    return false;
  }
  const bool growing = st.scale < 1.0; // count is at the size before any growth below
  if (growing && s.maxOverlap() <= st.growthTolerance * st.scale)
  {
    // [ours] Overlaps shallow at this size: grow for the next step.
    st.scale = std::min(1.0, st.scale + kGrowth);
    st.sinceGrowth = 0;
    st.sinceImprovement = 0;
    st.first = true;
  }
  const auto end = [&r]()
  {
    r.phase = Impl::Phase::Ended;
    return false;
  };
  if (st.scale < 1.0 && st.sinceGrowth >= kGrowthStall)
  {
    return end();
  }
  if (st.first || count < st.bestCollisions)
  {
    st.bestCollisions = count;
    st.bestStep = st.steps;
    st.sinceImprovement = 0;
    st.first = false;
  }
  else
  {
    ++st.sinceImprovement;
  }
  if ((count == 0 && !st.changed && !growing) || st.steps >= o.maxSteps)
  {
    return end();
  }
  if (o.stallSteps > 0 && st.sinceImprovement >= o.stallSteps)
  {
    st.warnings.push_back("stopped after " + formatNumber(st.sinceImprovement) +
      " steps without fewer collisions (StallSteps)");
    return end();
  }
  if (!st.warnedStall && st.sinceImprovement >= 1000)
  {
    st.warnedStall = true;
    st.warnings.push_back("1000 steps passed without fewer collisions");
  }
  s.separate();
  std::int64_t leaving = s.comm_ ? s.leavingFibers() : 0;
  ++st.steps;
  ++st.sinceGrowth;
  if (r.observer)
  {
    r.observer(st.steps, r.model);
  }
  const bool go = r.report(std::max(st.done, r.stepShareAfter(st.steps)), &leaving);
  s.migrationDue_ = leaving > 0;
  if (!go)
  {
    r.result.aborted = true;
    if (!s.detect()) // collisions must describe the geometry that is returned
    {
      s.detectError_ += " (at step " + formatNumber(st.steps) + ")";
      r.takeState();
      r.result.error = s.detectError_;
      r.phase = Impl::Phase::Failed;
      return false;
    }
    st.changed = !s.shapeWithinLimits();
    return end();
  }
  return true;
}

CollisionSolverResult CollisionSolverRun::finish()
{
  Impl& r = *impl_;
  if (r.phase == Impl::Phase::Created)
  {
    r.result.error = "the solver run was not started";
    r.phase = Impl::Phase::Failed;
  }
  if (r.phase == Impl::Phase::Running) // step() was not driven to the end: finish where it is
  {
    if (!r.s.detect())
    {
      r.failDetection(" (at step " + formatNumber(r.s.st_.steps) + ")");
    }
    else
    {
      r.s.st_.changed = !r.s.shapeWithinLimits();
      r.phase = Impl::Phase::Ended;
    }
  }
  if (r.phase == Impl::Phase::Failed || r.phase == Impl::Phase::Finished)
  {
    return r.result;
  }
  SolverEngine& s = r.s;
  CollisionSolverState& st = s.st_;
  const CollisionSolverOptions& o = r.options;
  FiberModel& model = r.model;
  CollisionSolverResult& result = r.result;
  result.radiusScale = st.scale;
  if (st.scale < 1.0)
  {
    // The output has the input radii: count what is left at full size.
    const double reached =
      s.periodic() ? s.fiberVolume() / o.periodicCell.volume() * st.scale * st.scale : -1.0;
    st.scale = 1.0;
    if (!s.detect())
    {
      r.takeState();
      result.error = s.detectError_ + " (at full radius after step " + formatNumber(st.steps) + ")";
      r.phase = Impl::Phase::Failed;
      return result;
    }
    if (!result.aborted)
    {
      std::ostringstream w;
      w << "radius growth stalled at " << 100.0 * result.radiusScale << " % of the radii";
      if (reached >= 0.0)
      {
        w << " (volume fraction " << reached << " of the requested "
          << s.fiberVolume() / o.periodicCell.volume() << ")";
      }
      w << " after " << st.steps << " steps; " << s.globalCounts(false).pairs
        << " pairs overlap at full size: the target is too dense for these fibers";
      st.warnings.push_back(w.str());
    }
  }
  r.takeState();
  result.collisions = s.globalCounts(false).pairs;
  result.solved = result.collisions == 0;
  result.shapeOk = !st.changed;
  result.maxOverlap = s.maxOverlap();
  if (s.periodic())
  {
    result.volumeFraction = s.fiberVolume() / o.periodicCell.volume();
  }
  // How far it got: the radius scale at which this geometry would be free of overlaps.
  const bool unsolved = !result.solved && !result.aborted;
  const double free = unsolved && s.periodic() ? s.overlapFreeScale() : 1.0;
  result.minGapProbe = s.median();
  result.minGap = smallestGap(s, result.minGapProbe);
  if (unsolved)
  {
    std::ostringstream w;
    w << result.collisions << " capsule pairs still overlap after " << result.steps
      << " steps (best " << result.bestCollisions << " at step " << result.bestStep
      << ", max overlap " << result.maxOverlap << " um";
    if (s.periodic())
    {
      w << "; overlap-free at " << 100.0 * free << " % of the radii, i.e. a volume fraction of "
        << result.volumeFraction * free * free << " of the requested " << result.volumeFraction;
    }
    w << "); raise MaxSteps, lower the density or the radii";
    result.warnings.push_back(w.str());
  }
  if (s.comm_)
  {
    r.goHome();
  }
  const std::size_t nf = model.fibers.size();
  result.sourceIndex.resize(nf);
  for (std::size_t f = 0; f < nf; ++f)
  {
    result.sourceIndex[f] = st.points[f].source; // the state stays whole (a checkpoint may follow)
  }
  r.phase = Impl::Phase::Finished;
  return result;
}

CollisionSolverResult solveCollisions(FiberModel& model, const CollisionSolverOptions& options,
  const ProgressFn& progress, const StepObserver& observer, Comm* comm)
{
  CollisionSolverRun run(model, options, progress, observer, comm);
  if (run.start())
  {
    while (run.step())
    {
    }
  }
  return run.finish();
}

} // namespace fiberpli
