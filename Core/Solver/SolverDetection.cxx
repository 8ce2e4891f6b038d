// SolverEngine: the colliding pairs of a step and their limits (docs/solver.md §3, §8, §13).

#include "Solver/SolverEngine.h"

#include "Util/MemoryBudget.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fiberpli
{

SolverEngine::Counts SolverEngine::globalCounts(bool changed) const
{
  if (!comm_)
  {
    return { pairs_.size(), links_.size(), changed };
  }
  std::vector<std::int64_t> v = localCounts(changed);
  comm_->sum(v);
  return countsOf(v);
}

// False when the pairs cannot be found: a periodic cell too small for the links, or more pairs
// than their limit (the whole model's packingPairBound or this process's memory budget);
// detectError_ says why. counts (if given): the global counts, with `changed` (shape control's)
// or-ed over the ranks. boundFirst: distributed, the packing bound is also computed before the
// search, so that a stack of fibers stops it early (the start; later steps check the count).
bool SolverEngine::detect(Counts* counts, bool changed, bool boundFirst)
{
  if (comm_)
  {
    migrate();
  }
  // [ours] §3.4: the pairs of two links that are quiet since the last detection are skipped (the
  // same pairs are found). Distributed, each rank judges the links it holds: a pair of two quiet
  // links was tested here last time too (the tester of a pair follows from its links' places
  // and the tester boxes; a re-cut makes the links whose tester box moved loud).
  const bool quiet = o_.quietLinks;
  if (quiet)
  {
    quiet_.keep(links_);
  }
  gatherLinks(&st_.active, periodic() ? &st_.closed : nullptr, st_.scale);
  loud_ = quiet ? quiet_.mark(links_, threads_, &held_.fiberRuns) : nullptr;
  if (loud_ && testersMoved_)
  {
    quiet_.makeLoud(
      [this](std::size_t i)
      {
        const Vec3 c = 0.5 * (links_[i].p0 + links_[i].p1);
        return testersBefore_.testerOf(c) != layout_.testerOf(c);
      });
  }
  testersMoved_ = false;
  const bool found = findBoundedPairs(boundFirst);
  loud_ = nullptr;
  lastDetectedLinks_ = links_.size();
  lastLoudLinks_ = quiet ? quiet_.loudLinks() : links_.size();
  detectedLinks_ += lastDetectedLinks_;
  loudLinks_ += lastLoudLinks_;
  if (quiet && found)
  {
    quiet_.remember(links_.size(), pairs_);
  }
  else if (quiet)
  {
    quiet_.forget();
  }
  if (!comm_)
  {
    if (counts)
    {
      *counts = { pairs_.size(), links_.size(), changed };
    }
    return found;
  }
  // One sum per step for whether any rank failed and the counts; the failing rank's message
  // then takes a second round (rare: the run ends).
  std::vector<std::int64_t> v = localCounts(changed);
  v.push_back(found ? 0 : 1);
  comm_->sum(v);
  if (v[3] > 0)
  {
    detectError_ = agreeOnError(*comm_, found ? std::string() : detectError_);
    return false;
  }
  detectError_.clear();
  // Below kPairsPerLinkBelowBound the whole model's bound need not be summed (most steps: 4–9
  // pairs per link in dense cubes).
  if (v[0] > kPairsPerLinkBelowBound * v[1])
  {
    const PairBound bound = wholeModelPairBound();
    if (static_cast<double>(v[0]) > bound.pairs)
    {
      detectError_ = packingMessage(bound);
      return false;
    }
  }
  if (counts)
  {
    *counts = countsOf(v);
  }
  return true;
}

// The packing bound of all links (of every rank: collective when distributed, where each rank
// builds its owned fibers' links for it: links_ holds the links near its box instead).
PairBound SolverEngine::wholeModelPairBound() const
{
  if (!comm_)
  {
    return packingPairBound(links_, o_.minimumGap, nullptr);
  }
  std::vector<CapsuleLink> own;
  buildLinks(
    model_, &st_.active, threads_, own, nullptr, periodic() ? &st_.closed : nullptr, st_.scale);
  return packingPairBound(own, o_.minimumGap, comm_);
}

std::string SolverEngine::packingMessage(const PairBound& bound) const
{
  std::ostringstream msg;
  msg
    << "more than " << static_cast<std::size_t>(bound.pairs) << " capsule pairs of " << bound.links
    << " links collide (MinimumGap " << o_.minimumGap
    << "), more than any packing of fibers of capsule radius up to " << bound.rhoMax
    << " um can have: the fibers lie (nearly) on top of each other; spread them or lower the radii";
  return msg.str();
}

// The pairs among links_ (docs/solver.md §8, §13). Two limits: the whole model's packing bound
// (a property of the model: decided alike for any rank count), and the pairs this process's
// memory budget affords beside the links it holds (a property of the process: a rank holds at
// most the serial run's links and pairs, so it refuses only what the serial run would refuse,
// and every rank reports the lowest refusing rank's message). The bound is at least 27 pairs per
// link and costs an exact sum over all links (~3 ms per 32 000 links, a tenth of a step), so it
// is summed only when needed: serially when the pairs exceed 26 per link (then the search
// runs again up to it), distributed before the search only with boundFirst (the start, so that
// a stack stops early), otherwise detect() checks the summed count afterwards.
bool SolverEngine::findBoundedPairs(bool boundFirst)
{
  PairBound bound;
  bound.pairs = HUGE_VAL; // not known yet
  if (comm_ && boundFirst)
  {
    bound = wholeModelPairBound();
  }
  const double budget = memoryBudgetBytes() - bytesPerPoint() * static_cast<double>(links_.size());
  const double affordable = std::max(0.0, budget) / bytesPerPair();
  const double belowBound =
    comm_ ? HUGE_VAL : kPairsPerLinkBelowBound * static_cast<double>(links_.size());
  double limit = std::min({ bound.pairs, affordable, belowBound });
  bool overflow = false;
  if (!searchPairs(limit, overflow))
  {
    return false;
  }
  if (overflow && limit == belowBound && belowBound < affordable)
  {
    bound = wholeModelPairBound();
    limit = std::min(bound.pairs, affordable);
    if (!searchPairs(limit, overflow))
    {
      return false;
    }
  }
  if (!overflow)
  {
    return true;
  }
  if (limit == bound.pairs)
  {
    detectError_ = packingMessage(bound);
    return false;
  }
  const auto maxPairs = static_cast<std::size_t>(limit);
  std::ostringstream msg;
  msg << "more than " << maxPairs << " capsule pairs of " << links_.size() << " links";
  if (comm_)
  {
    msg << " held on rank " << comm_->rank() << " of " << comm_->size();
  }
  msg << " collide (MinimumGap " << o_.minimumGap << "): "
      << checkMemoryBudget((static_cast<double>(maxPairs) + 1.0) * bytesPerPair() +
             bytesPerPoint() * static_cast<double>(links_.size()),
           "storing them beside the links")
      << "; lower the density or MinimumGap";
  if (comm_)
  {
    msg << ", or use more ranks";
  }
  detectError_ = msg.str();
  return false;
}

// One search of pairs_, stopping above `limit` pairs (overflow). False: the periodic cell is too
// small for the links (detectError_ says so). Distributed: each pair is tested on one rank only
// (LinkExchange.h, testedPairs); the finder skips the others before their exact test.
bool SolverEngine::searchPairs(double limit, bool& overflow)
{
  const auto maxPairs = static_cast<std::size_t>(limit);
  const std::vector<char>* tested = comm_ ? &held_.tested : nullptr;
  overflow = false;
  pairWork_ += kHeldLinkWork * links_.size();
  if (periodic())
  {
    detectError_ = periodic_.findPairs(
      links_, o_.periodicCell, o_.minimumGap, threads_, pairs_, maxPairs, &overflow, tested, loud_);
    pairWork_ += periodic_.work();
    return detectError_.empty();
  }
  overflow = !grid_.findPairs(
    links_, o_.minimumGap, threads_, pairs_, maxPairs, tested, testedPairs(layout_), loud_);
  pairWork_ += grid_.work();
  return true;
}

} // namespace fiberpli
