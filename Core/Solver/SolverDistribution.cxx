// SolverEngine: the boxes, migrations and link exchanges of a distributed run (docs/solver.md §13).

#include "Solver/SolverEngine.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

// The boxes, the pair and probe reaches and every fiber to its owner (the run's first exchange).
void SolverEngine::startDistribution()
{
  layout_ = BoxLayout::make(model_, o_.periodicCell, *comm_);
  const double rhoMax = maxOverRanks(*comm_, largestRadius(model_));
  // Pairs collide closer than 2·ρmax + gap; the minimum gap probes pairs up to one median
  // radius (<= ρmax) apart; a relative margin covers the rounding of the distances.
  pairReach_ = (2.0 * rhoMax + o_.minimumGap) * (1.0 + 1e-6) + 1e-9;
  probeReach_ = 3.0 * rhoMax * (1.0 + 1e-6) + 1e-9;
  RankFibers r = rankFibers();
  std::vector<int> dest(r.size());
  for (std::size_t f = 0; f < r.size(); ++f)
  {
    dest[f] = layout_.owner(model_.fibers[f]);
  }
  redistribute(r, dest, *comm_);
  migrationDue_ = false;
  pairWork_ = 0;
}

// Every kBalanceSteps steps the tester boxes are re-cut at equal pair work of the steps since
// (the link counts they start with balance the links, not their pairs: the 1000-fiber cube's
// ranks did 52 / 48 % of the box tests).
void SolverEngine::balanceTesters()
{
  if (st_.steps > 0 && st_.steps % kBalanceSteps == 0)
  {
    const BoxLayout before = layout_;
    layout_.balanceTesterBoxes(model_, static_cast<std::int64_t>(pairWork_), *comm_);
    pairWork_ = 0;
    const double moved = layout_.largestCutMove(before);
    if (moved > 0.0)
    {
      // A pair's tester follows from its two links' tester boxes: the links whose tester box
      // moved are loud at the next detection (§3.4), the pairs of the others kept their tester.
      if (!testersMoved_)
      {
        testersBefore_ = before;
        testersMoved_ = true;
      }
      ++testerRecuts_;
      testerCutMove_ = std::max(testerCutMove_, moved);
    }
  }
}

void SolverEngine::resetTraffic()
{
  migrations_ = haloExchanges_ = haloBytes_ = peakHaloLinks_ = peakRankPoints_ = peakHeldLinks_ =
    peakPartners_ = 0;
  testerRecuts_ = 0;
  testerCutMove_ = 0.0;
}

// Before a detection: fibers whose owner box changed go to their new owner (only when a rank said
// so at the end of the last step: most steps move no fiber out of its box, and the links go to
// every rank whose tester box they reach whoever owns them).
void SolverEngine::migrate()
{
  if (migrationDue_)
  {
    RankFibers r = rankFibers();
    std::vector<int> dest(r.size());
    for (std::size_t f = 0; f < r.size(); ++f)
    {
      dest[f] = layout_.owner(model_.fibers[f]);
    }
    migrations_ += redistribute(r, dest, *comm_).fibers;
    migrationDue_ = false;
    exchangeBuffers_.blockBoxesCurrent = false; // they were taken of the fibers before
  }
}

// links_ (and pointOffset_) of the owned fibers; distributed: the links near this rank's box,
// from all owners, with the current positions (so they are complete for this step), or with
// the wider reach of the minimum-gap probe (then not counted as a step's traffic).
void SolverEngine::gatherLinks(
  const std::vector<char>* active, const std::vector<char>* closed, double scale, bool forGapProbe)
{
  if (!comm_)
  {
    buildLinks(model_, active, threads_, links_, &pointOffset_, closed, scale, &held_.fiberRuns);
    return;
  }
  pointOffsets(model_, pointOffset_);
  ownLinkCount_ = 0;
  for (std::size_t f = 0; f < model_.fibers.size(); ++f)
  {
    ownLinkCount_ += linksOf(model_, active, f);
  }
  const double reach = forGapProbe ? probeReach_ : pairReach_;
  const TrafficCount sent = exchangeLinks(model_, active, closed, st_.global, scale, layout_, reach,
    *comm_, links_, held_, partners_, &exchangeBuffers_);
  if (forGapProbe)
  {
    return;
  }
  haloBytes_ += sent.bytes;
  ++haloExchanges_;
  const std::size_t halo = held_.received;
  peakHeldLinks_ = std::max(peakHeldLinks_, links_.size());
  peakPartners_ = std::max(peakPartners_, partners_.size());
  peakHaloLinks_ = std::max(peakHaloLinks_, halo);
  peakRankPoints_ =
    std::max(peakRankPoints_, pointOffset_.back() + halo); // owned points + halo links
}

// Owned fibers whose middle left this rank's owner box (after a move): they migrate next step.
std::int64_t SolverEngine::leavingFibers() const
{
  std::int64_t n = 0;
  const int me = comm_->rank();
  for (std::size_t f = 0; f < model_.fibers.size(); ++f)
  {
    const int owner = f < movedOwner_.size() && movedOwner_[f] >= 0
      ? movedOwner_[f]
      : layout_.owner(model_.fibers[f]);
    n += owner != me ? 1 : 0;
  }
  return n;
}

} // namespace fiberpli
