#include "Checkpoint/CheckpointState.h"

#include "Solver/ShapeControl.h"
#include "Util/NumberFormat.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

namespace
{
bool finite(const Vec3& v)
{
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string field(const std::string& name, double value, const std::string& must)
{
  return "the saved " + name + " is " + formatNumber(value) + ", must be " + must;
}

std::string vecText(const Vec3& v)
{
  return "(" + formatNumber(v.x) + ", " + formatNumber(v.y) + ", " + formatNumber(v.z) + ")";
}

// Two consecutive points at the same place, or fewer than two points: the solver leaves such a
// fiber inactive (copied through).
bool degenerate(const Fiber& f)
{
  if (f.points.size() < 2)
  {
    return true;
  }
  for (std::size_t i = 1; i < f.points.size(); ++i)
  {
    if (f.points[i] == f.points[i - 1])
    {
      return true;
    }
  }
  return false;
}

std::string checkFibers(const FiberModel& model, const CollisionSolverState& st,
  const CollisionSolverOptions& o, int ranks)
{
  const std::size_t nf = model.fibers.size();
  if (st.points.size() != nf || st.active.size() != nf || st.closed.size() != nf ||
    st.closure.size() != nf)
  {
    return "the saved solver state is for " + formatNumber(st.points.size()) +
      " fibers, the model has " + formatNumber(nf);
  }
  const bool distributed = st.global.size() == nf && st.home.size() == nf;
  const PeriodicCell& cell = o.periodicCell;
  for (std::size_t f = 0; f < nf; ++f)
  {
    const Fiber& fib = model.fibers[f];
    const FiberPointState& ps = st.points[f];
    const std::string which =
      "fiber " + formatNumber(f) + " (fiber_id " + formatNumber(fib.id) + ")";
    if (ps.velocity.size() != fib.points.size() || ps.source.size() != fib.points.size())
    {
      return "the saved solver state of " + which + " has " + formatNumber(ps.velocity.size()) +
        " points, the model " + formatNumber(fib.points.size());
    }
    if (st.active[f] > 1 || st.active[f] < 0 || st.closed[f] > 1 || st.closed[f] < 0)
    {
      return "the saved flags of " + which + " are not 0 or 1";
    }
    if (st.active[f] && degenerate(fib))
    {
      return "the saved state flags " + which + " active, but it has fewer than 2 distinct points";
    }
    if (!st.active[f] && !degenerate(fib))
    {
      return "the saved state flags " + which + " inactive, but it has " +
        formatNumber(fib.points.size()) + " distinct points (the solver solves every such fiber)";
    }
    for (std::size_t i = 0; i < fib.points.size(); ++i)
    {
      if (!finite(ps.velocity[i]))
      {
        return "the saved velocity of " + which + " point " + formatNumber(i) + " is " +
          vecText(ps.velocity[i]) + ", must be finite";
      }
      if (!std::isfinite(ps.source[i]) || ps.source[i] < 0.0)
      {
        return field("source index of " + which + " point " + formatNumber(i), ps.source[i],
          "finite and >= 0");
      }
      if (!ps.inputRadii.empty() && ps.source[i] > static_cast<double>(ps.inputRadii.size() - 1))
      {
        return field("source index of " + which + " point " + formatNumber(i), ps.source[i],
          "at most " + formatNumber(ps.inputRadii.size() - 1) +
            " (its input radius profile's last point)");
      }
    }
    for (std::size_t i = 0; i < ps.inputRadii.size(); ++i)
    {
      if (!std::isfinite(ps.inputRadii[i]) || !(ps.inputRadii[i] > 0.0))
      {
        return field(
          "input radius " + formatNumber(i) + " of " + which, ps.inputRadii[i], "finite and > 0");
      }
    }
    if (!finite(st.closure[f]))
    {
      return "the saved closure vector of " + which + " is " + vecText(st.closure[f]) +
        ", must be finite";
    }
    if (st.closed[f])
    {
      Vec3 lattice;
      if (!cell.enabled() || !st.active[f] || !isClosedFiber(fib, cell, lattice) ||
        !(lattice == st.closure[f]))
      {
        return "the saved closure vector of " + which + " is " + vecText(st.closure[f]) +
          ", must be the lattice vector from its first point to its last (" +
          vecText(fib.points.back() - fib.points.front()) + ") in the periodic cell";
      }
    }
    if (distributed && (st.home[f] < 0 || st.home[f] >= ranks))
    {
      return field("home rank of " + which, st.home[f], "in [0, " + formatNumber(ranks - 1) + "]");
    }
  }
  return {};
}

std::string checkScalars(const FiberModel& model, const CollisionSolverState& st,
  const CollisionSolverOptions& o, int ranks)
{
  double rMin = HUGE_VAL, rMax = 0.0;
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    for (double r : model.fibers[f].radii)
    {
      if (st.active[f])
      {
        rMin = std::min(rMin, r);
        rMax = std::max(rMax, r);
      }
    }
  }
  const bool anyActive = rMax > 0.0;
  const int maxSteps = std::max(0, o.maxSteps);
  if (st.steps < 0 || st.steps > maxSteps)
  {
    return field("step count", st.steps, "in [0, MaxSteps " + formatNumber(o.maxSteps) + "]");
  }
  for (const auto& [name, value] :
    { std::pair<const char*, int>{ "step of the best collision count", st.bestStep },
      { "steps since the last growth", st.sinceGrowth },
      { "steps since the last improvement", st.sinceImprovement } })
  {
    if (value < 0 || value > st.steps)
    {
      return field(name, value, "in [0, the step count " + formatNumber(st.steps) + "]");
    }
  }
  const double initial = o.initialRadiusScale > 0.0 ? o.initialRadiusScale : 1.0;
  if (!(st.scale >= initial && st.scale <= 1.0))
  {
    return field("radius scale", st.scale,
      "in [" + formatNumber(initial) + ", 1] (InitialRadiusScale " +
        formatNumber(o.initialRadiusScale) + ")");
  }
  if (o.segmentLength > 0.0 && !(st.segmentLength == o.segmentLength))
  {
    return field(
      "segment length", st.segmentLength, "SegmentLength " + formatNumber(o.segmentLength));
  }
  if (o.segmentLength < 0.0 && !(st.segmentLength < 0.0))
  {
    return field("segment length", st.segmentLength,
      "< 0 (SegmentLength " + formatNumber(o.segmentLength) + " = off)");
  }
  if (o.segmentLength == 0.0 && anyActive)
  {
    // Automatic: 2 × the median radius of the whole model. Serial, that lies within 2 × the
    // radii here; a distributed piece may lack the median fiber, so it is held to 1000 × that.
    const double slack = ranks > 1 ? 1e3 : 1.0;
    if (!(st.segmentLength >= 2.0 * rMin / slack && st.segmentLength <= 2.0 * rMax * slack))
    {
      return field("segment length", st.segmentLength,
        "2 x the median radius (SegmentLength 0 = automatic), within 2 x the radii [" +
          formatNumber(rMin) + ", " + formatNumber(rMax) + "]");
    }
  }
  // The move cap is MaxDisplacement × the smallest radius of the whole model: at most that of
  // this piece's radii.
  if (!std::isfinite(st.vMax) || st.vMax < 0.0 || (anyActive && !(st.vMax > 0.0)) ||
    (anyActive && st.vMax > o.maxDisplacement * rMin * (1.0 + 1e-12)))
  {
    return field("move cap", st.vMax,
      anyActive ? "in (0, MaxDisplacement x the smallest radius = " +
          formatNumber(o.maxDisplacement * rMin) + "]"
                : std::string("finite and >= 0"));
  }
  if (!std::isfinite(st.growthTolerance) || st.growthTolerance < 0.0)
  {
    return field("growth tolerance", st.growthTolerance, "finite and >= 0");
  }
  if (!(st.pushScale >= 1.0 && st.pushScale <= std::max(1.0, o.pushBoost)))
  {
    return field("push scale", st.pushScale, "in [1, PushBoost " + formatNumber(o.pushBoost) + "]");
  }
  if (!(st.done >= 0.0 && st.done <= 1.0) || !(st.reported >= 0.0 && st.reported <= 1.0))
  {
    return field("progress",
      std::isfinite(st.done) && st.done >= 0.0 && st.done <= 1.0 ? st.reported : st.done,
      "in [0, 1]");
  }
  // Coordinates: the solver must resolve its links (SegmentLength, or without split/merge the
  // thinnest fiber's diameter as the length scale).
  const double length = st.segmentLength > 0.0 ? st.segmentLength : (anyActive ? 2.0 * rMin : -1.0);
  const std::string far = checkCoordinateResolution(model, length);
  return far.empty() ? far : "the saved model's " + far;
}
} // namespace

std::string checkResumedState(const FiberModel& model, const CollisionSolverState& state,
  const CollisionSolverOptions& options, int ranks)
{
  // A model that breaks the data contract is refused by the resume itself, as fresh input is
  // (CollisionSolverRun::resume, naming the fiber by its index in the whole model); the checks
  // below need finite radii > 0.
  if (!validateModel(model, nullptr, ShortFibers::Allowed).empty())
  {
    return {};
  }
  const std::string error = checkFibers(model, state, options, ranks);
  return error.empty() ? checkScalars(model, state, options, ranks) : error;
}

} // namespace fiberpli
