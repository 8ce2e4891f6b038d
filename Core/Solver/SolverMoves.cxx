// SolverEngine: shape control and the pushes and moves of a step (docs/solver.md §4, §5).

#include "Solver/SolverEngine.h"

#include "Solver/BeadProfile.h"
#include "Solver/PushBoost.h"
#include "Solver/TortuosityControl.h"
#include "Util/Refill.h"

#include <cmath>

namespace fiberpli
{

// Tortuosity, length, beads, then curvature per fiber; parallel over fibers, each fiber sequential
// (§5).
bool SolverEngine::shapeControl()
{
  const std::int64_t nf = static_cast<std::int64_t>(model_.fibers.size());
  int changed = 0;
  // Distributed without a cell: the link exchange routes blocks of links by their boxes, taken
  // here while each fiber's final points are in cache (a pass of their own read them again from
  // memory, a few percent of a step).
  const bool boxes = comm_ && !periodic();
  std::vector<std::vector<BlockBox>>& blockBoxes = exchangeBuffers_.blockBoxes;
  std::vector<BlockBox>& fiberBoxes = exchangeBuffers_.fiberBoxes;
  if (boxes)
  {
    blockBoxes.resize(model_.fibers.size());
    fiberBoxes.resize(model_.fibers.size());
  }
#pragma omp parallel for num_threads(threads_) schedule(dynamic, 16) reduction(| : changed)
  for (std::int64_t f = 0; f < nf; ++f)
  {
    Fiber& fib = model_.fibers[static_cast<std::size_t>(f)];
    if (!st_.active[static_cast<std::size_t>(f)])
    {
      continue;
    }
    FiberPointState& st = st_.points[static_cast<std::size_t>(f)];
    const bool closed = periodic() && st_.closed[static_cast<std::size_t>(f)];
    const Vec3* closure = closed ? &st_.closure[static_cast<std::size_t>(f)] : nullptr;
    bool c = controlTortuosity(fib, o_.tortuosity, tortuosityTolerance(), moveCap(),
      5.0 * st_.segmentLength, closure, o_.tortuosityWavelength);
    c = controlSegmentLength(fib, st, st_.segmentLength, closed ? 3 : 2) || c;
    if (o_.keepBeads && closed)
    {
      c = followBeadProfile(fib, st) || c;
    }
    c = controlCurvature(fib, o_.minCurvatureRadius, moveCap(), o_.endPoints, closure) || c;
    close(static_cast<std::size_t>(f));
    if (boxes)
      fiberBoxes[static_cast<std::size_t>(f)] =
        linkBlockBoxes(fib.points.data(), linksOf(model_, &st_.active, static_cast<std::size_t>(f)),
          blockBoxes[static_cast<std::size_t>(f)]);
    changed |= c ? 1 : 0;
  }
  exchangeBuffers_.blockBoxesCurrent = boxes;
  return changed != 0;
}

// The state shape control would leave untouched (used after an abort, where it did not run).
bool SolverEngine::shapeWithinLimits() const
{
  const bool ok = localShapeWithinLimits();
  return comm_ ? !anyRank(*comm_, !ok) : ok;
}

bool SolverEngine::localShapeWithinLimits() const
{
  const double lMin = st_.segmentLength * (2.0 / 3.0);
  const double lMax = st_.segmentLength * (4.0 / 3.0);
  for (std::size_t f = 0; f < model_.fibers.size(); ++f)
  {
    const Fiber& fib = model_.fibers[f];
    if (!st_.active[f])
    {
      continue;
    }
    const bool closed = periodic() && st_.closed[f];
    const Vec3* closure = closed ? &st_.closure[f] : nullptr;
    if (!curvatureOk(fib, o_.minCurvatureRadius, closure))
    {
      return false;
    }
    if (o_.tortuosity > 1.0)
    {
      const double tau = fiberTortuosity(fib, closure);
      if (tau > 1.0 && tau < o_.tortuosity - tortuosityTolerance())
      {
        return false;
      }
    }
    for (std::size_t i = 0; st_.segmentLength > 0.0 && i + 1 < fib.size(); ++i)
    {
      const double len = distance(fib.points[i], fib.points[i + 1]);
      if (len > lMax || (len < lMin && fib.size() > 2))
      {
        return false;
      }
    }
  }
  return true;
}

// §4.4: pushes in parallel into their own slots, summed serially in pair order (distributed:
// by the owners of the links, LinkExchange.h), then moved per fiber in parallel: no floating
// result depends on the thread or the rank that computed it.
void SolverEngine::separate()
{
  const std::int64_t np = static_cast<std::int64_t>(pairs_.size());
  push_.resize(pairs_.size());
  if (comm_)
    pairLocals_.resize(pairs_.size());
  const int me = comm_ ? comm_->rank() : 0;
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (std::int64_t pi = 0; pi < np; ++pi)
  {
    const CapsulePair& p = pairs_[static_cast<std::size_t>(pi)];
    const CapsuleLink& la = links_[p.a];
    const CapsuleLink& lb = links_[p.b];
    const LinkSide sa = sideOf(p.a, me), sb = sideOf(p.b, me);
    const double rMin = std::min(sa.pointRadius, sb.pointRadius);
    const double overlap = la.rho + lb.rho + o_.minimumGap - p.distance;
    const double sigma = boostedPush(
      std::max(o_.separationSpeed * rMin, o_.overlapPush * overlap), st_.pushScale, overlap);
    const Vec3 n = sigma * p.direction;
    LinkPairPush& out = push_[static_cast<std::size_t>(pi)];
    out.fiberA = la.fiber;
    out.kA = la.k;
    out.fiberB = lb.fiber;
    out.kB = lb.k;
    out.ownerA = sa.owner;
    out.ownerB = sb.owner;
    if (comm_)
      pairLocals_[static_cast<std::size_t>(pi)] = PairLocals{ sa.local, sb.local };
    out.a0 = (1.0 - p.s) * n;
    out.a1 = p.s * n;
    out.b0 = -((1.0 - p.t) * n);
    out.b1 = -(p.t * n);
  }
  refill(force_, pointOffset_.back(), Vec3{});
  const double spread = o_.pushSpread;
  // One pair's pushes onto the points of its links that this rank owns (fa, fb: the links'
  // fibers in the model, SIZE_MAX: another rank's; that side is added there, in the same order).
  const auto apply = [this, spread](const LinkPairPush& p, std::size_t fa, std::size_t fb)
  {
    if (fa != SIZE_MAX)
    {
      force_[pointOffset_[fa] + p.kA] += p.a0;
      force_[pointOffset_[fa] + p.kA + 1] += p.a1;
    }
    if (fb != SIZE_MAX)
    {
      force_[pointOffset_[fb] + p.kB] += p.b0;
      force_[pointOffset_[fb] + p.kB + 1] += p.b1;
    }
    if (spread > 0.0)
    {
      // [ours] The outer neighbours follow: a bump instead of a kink, so the push does not
      // create the curvature violations that shape control then undoes step after step.
      const auto add = [this, spread](std::size_t i, const Vec3& push)
      {
        if (i != SIZE_MAX)
          force_[i] += spread * push;
      };
      if (fa != SIZE_MAX)
      {
        add(outerBefore(fa, p.kA), p.a0);
        add(outerAfter(fa, p.kA), p.a1);
      }
      if (fb != SIZE_MAX)
      {
        add(outerBefore(fb, p.kB), p.b0);
        add(outerAfter(fb, p.kB), p.b1);
      }
    }
  };
  if (!comm_)
  {
    for (const LinkPairPush& p : push_)
      apply(p, p.fiberA, p.fiberB);
  }
  else
  {
    TrafficCount sent;
    returnPushes(
      push_, pairLocals_, st_.global, partners_, *comm_, sent, pushesReceived_, &exchangeBuffers_);
    haloBytes_ += sent.bytes;
    const auto own = [](std::uint32_t f)
    { return f == kNotOwned ? SIZE_MAX : static_cast<std::size_t>(f); };
    forPushesInPairOrder(push_, pairLocals_, pushesReceived_,
      [&](const LinkPairPush& p, std::uint32_t fa, std::uint32_t fb)
      { apply(p, own(fa), own(fb)); });
  }
  const std::int64_t nf = static_cast<std::int64_t>(model_.fibers.size());
  if (comm_)
  {
    refill(movedOwner_, model_.fibers.size(), -1);
  }
  const bool remembers = o_.dragSteps == 0 || st_.steps < o_.dragSteps;
  const double drag = remembers ? o_.drag : 0.0;
  const double vMax = moveCap();
  const EndPointRule rule = o_.endPoints;
#pragma omp parallel for num_threads(threads_) schedule(static)
  for (std::int64_t f = 0; f < nf; ++f)
  {
    Fiber& fib = model_.fibers[static_cast<std::size_t>(f)];
    const std::size_t n = fib.points.size();
    if (!st_.active[static_cast<std::size_t>(f)])
    {
      continue;
    }
    std::vector<Vec3>& vel = st_.points[static_cast<std::size_t>(f)].velocity;
    Vec3* force = force_.data() + pointOffset_[static_cast<std::size_t>(f)];
    const bool closed = periodic() && st_.closed[static_cast<std::size_t>(f)];
    if (closed)
    {
      // First and last point are one point: both get the sum of their pushes.
      force[0] += force[n - 1];
      force[n - 1] = force[0];
    }
    for (std::size_t i = 0; i < n; ++i)
    {
      Vec3 v = drag == 0.0 ? force[i] : drag * vel[i] + force[i];
      const double vv = norm2(v);
      if (vv > vMax * vMax)
      {
        v *= vMax / std::sqrt(vv);
      }
      vel[i] = v;
    }
    // End-point rule after the cap, on the end links before this move (§4.2); a closed fiber
    // has no ends.
    if (!closed)
    {
      vel[0] = constrainEndMove(fib, 0, vel[0], rule);
      vel[n - 1] = constrainEndMove(fib, n - 1, vel[n - 1], rule);
    }
    // Distributed: the owner box of the fiber's middle after the move. An open fiber's extent is
    // taken while the moved points are at hand rather than in a pass of its own; a closed fiber's
    // last point is set by close(), so its extent is taken afterwards.
    if (!comm_ || closed)
    {
      for (std::size_t i = 0; i < n; ++i)
      {
        fib.points[i] += vel[i];
      }
      close(static_cast<std::size_t>(f));
      if (comm_)
      {
        movedOwner_[static_cast<std::size_t>(f)] = layout_.owner(fib);
      }
      continue;
    }
    Vec3 lo{ HUGE_VAL, HUGE_VAL, HUGE_VAL }, hi{ -HUGE_VAL, -HUGE_VAL, -HUGE_VAL };
    for (std::size_t i = 0; i < n; ++i)
    {
      fib.points[i] += vel[i];
      lo = componentMin(lo, fib.points[i]);
      hi = componentMax(hi, fib.points[i]);
    }
    movedOwner_[static_cast<std::size_t>(f)] = layout_.ownerOf(BoxLayout::middleOf(lo, hi));
  }
}

} // namespace fiberpli
