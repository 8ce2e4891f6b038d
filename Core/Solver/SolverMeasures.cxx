// SolverEngine: overlap and gap figures of a solve's result (docs/solver.md §9).

#include "Solver/SolverEngine.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

// Largest factor s <= 1 with δ >= s·(ρa + ρb) + g for every colliding pair.
double SolverEngine::overlapFreeScale() const
{
  double f = 1.0;
  for (const CapsulePair& p : pairs_)
  {
    f =
      std::min(f, std::max(0.0, p.distance - o_.minimumGap) / (links_[p.a].rho + links_[p.b].rho));
  }
  return comm_ ? minOverRanks(*comm_, f) : f;
}

double SolverEngine::maxOverlap() const
{
  double m = 0.0;
  for (const CapsulePair& p : pairs_)
  {
    m = std::max(m, links_[p.a].rho + links_[p.b].rho + o_.minimumGap - p.distance);
  }
  return comm_ ? maxOverRanks(*comm_, m) : m;
}

// Smallest surface gap over pairs closer than probe (µm); probe when no pair is that close.
// Distributed, the links are gathered again with the probe's reach (the pairs found before no
// longer index them), and each rank examines only the pairs it tests (the minimum over the ranks
// is the serial one). This search set a solve's peak memory (bench/README.md "Memory per rank"):
// the step's pair and push lists (and the pushes received), no longer needed, are released
// before it.
double smallestGap(SolverEngine& s, double probe)
{
  std::vector<CapsulePair>().swap(s.pairs_);
  std::vector<LinkPairPush>().swap(s.push_);
  std::vector<PairLocals>().swap(s.pairLocals_);
  std::vector<std::vector<ReceivedPush>>().swap(s.pushesReceived_);
  if (s.comm_)
  {
    s.quiet_.forget(); // links_ no longer holds the last detection's links
    s.gatherLinks(&s.st_.active, s.periodic() ? &s.st_.closed : nullptr, s.st_.scale, true);
  }
  const std::vector<char>* tested = s.comm_ ? &s.held_.tested : nullptr;
  std::vector<CapsulePair> near;
  bool tooSmall = false;
  if (s.periodic())
  {
    // Too small for the whole probe: no gap below it is known (judged at the probe, not per
    // stage, so the answer does not depend on the stage that finds a pair). Each rank judges its
    // own links (their widest radius); all must agree, or minGap would differ from the serial
    // one. Called on every rank alike.
    tooSmall = !PeriodicPairs::cellTooSmall(s.links_, s.o_.periodicCell, probe).empty();
    if (s.comm_)
    {
      tooSmall = anyRank(*s.comm_, tooSmall);
    }
  }
  // Widening: a pair found within gap g is nearer than every pair not found, so the first g
  // (probe/16, probe/4, probe) that finds any pair on any rank gives the same minimum as the
  // whole probe, and packed or still colliding fibers stop at the first: it stores a fraction
  // of the ~11 pairs per link within one median radius of the 1000-fiber cubes.
  for (double g = probe / 16.0; !tooSmall; g = std::min(probe, 4.0 * g))
  {
    if (s.periodic())
    {
      s.periodic_.findPairs(s.links_, s.o_.periodicCell, g, s.threads_, near,
        static_cast<std::size_t>(-1), nullptr, tested);
    }
    else
    {
      s.grid_.findPairs(s.links_, g, s.threads_, near, static_cast<std::size_t>(-1), tested,
        testedPairs(s.layout_));
    }
    const bool any = s.comm_ ? anyRank(*s.comm_, !near.empty()) : !near.empty();
    if (any || !(g < probe))
    {
      break;
    }
  }
  double gap = probe;
  for (const CapsulePair& p : near)
  {
    gap = std::min(gap, p.distance - s.links_[p.a].rho - s.links_[p.b].rho);
  }
  return s.comm_ ? minOverRanks(*s.comm_, gap) : gap;
}

} // namespace fiberpli
