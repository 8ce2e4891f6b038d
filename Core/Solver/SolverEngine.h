/// SolverEngine: the working state of one collision solve and the operations a step is made of
/// (docs/solver.md §3–§6, §13). Internal to Core/Solver: CollisionSolverRun (SolverRun.h) drives
/// it; the operations live in one file per job: SolverDistribution.cxx (the boxes and the
/// exchanges of a distributed run), SolverDetection.cxx (the colliding pairs and their limits),
/// SolverMoves.cxx (pushes and shape control), SolverMeasures.cxx (overlap and gap figures of the
/// result), SolverSetup.cxx (preparing the fibers and the step size).
#pragma once

#include "Index/CollisionGrid.h"
#include "Index/PeriodicPairs.h"
#include "Parallel/Collectives.h"
#include "Solver/CollisionSolver.h"
#include "Solver/Decomposition.h"
#include "Solver/LinkExchange.h"
#include "Solver/PairBound.h"
#include "Solver/QuietLinks.h"
#include "Solver/SolverLinks.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

// Steps between re-cuts of the distributed solver's tester boxes (two sums each time).
constexpr int kBalanceSteps = 32;
// What a held link costs a step whether or not its pairs are tested (built, boxed, sorted,
// compared with the last step's), in box tests (CollisionGrid::work): late in a solve, when few
// links are loud, that is nearly all of a step (0.34 s a step for 5.8 M links, about 60 ns a
// link). The re-cuts balance it with the pair work; the pair work alone let the few loud links
// drag the cut between two ranks of a section far from its owner cut, and each rank held a
// quarter of its links for the other (bench/README.md).
constexpr std::uint64_t kHeldLinkWork = 30;
// Pairs per link below which the packing bound (>= 27 per link, Index/CollisionGrid.h) cannot be
// exceeded, so its exact sum over all links is skipped.
constexpr int kPairsPerLinkBelowBound = 26;

class SolverEngine
{
public:
  SolverEngine(FiberModel& model, const CollisionSolverOptions& o, int threads)
    : model_(model)
    , o_(o)
    , threads_(threads)
  {
  }

  FiberModel& model_;
  const CollisionSolverOptions& o_;
  int threads_;
  CollisionSolverState st_; // what a step hands to the next (header); the rest is rebuilt per step
  std::vector<CapsuleLink> links_; // what the pairs are found among (distributed: the held links)
  std::vector<std::size_t> pointOffset_;
  std::vector<CapsulePair> pairs_;
  std::vector<LinkPairPush> push_;     // per pair found here, in pair order
  std::vector<PairLocals> pairLocals_; // distributed: per pair of push_, its fibers on this rank
  std::vector<Vec3> force_;
  CollisionGrid grid_;
  PeriodicPairs periodic_; // [ours] the image-aware detector of a periodic cell
  std::string detectError_;
  // [ours] The links whose pairs a detection tests (§3.4), with quietLinks.
  QuietLinks quiet_;
  const std::vector<char>* loud_ = nullptr;               // this detection's loud flags (null: all)
  std::uint64_t detectedLinks_ = 0, loudLinks_ = 0;       // summed over the detections of the run
  std::size_t lastDetectedLinks_ = 0, lastLoudLinks_ = 0; // of the last detection
  // Distributed run (docs/solver.md §13); comm_ null: this process alone. The model holds the
  // fibers this rank owns; the pairs are found among the links near its box (LinkExchange.h).
  Comm* comm_ = nullptr;
  // Distributed: the links of the fibers this rank owns (links_ holds those near its box).
  std::size_t ownLinkCount_ = 0;
  HeldLinkInfo held_; // per link of links_
  BoxLayout layout_;
  // The tester boxes of the last detection when a re-cut moved them since (testersMoved_): a link
  // whose tester box changed is loud at the next detection (§3.4, §13).
  BoxLayout testersBefore_;
  bool testersMoved_ = false;
  std::vector<int> partners_; // the ranks the last gatherLinks exchanged with (pushes go back)
  LinkExchangeBuffers exchangeBuffers_; // the routing tables, kept from step to step
  // Per sender, the pushes other ranks tested on this rank's links (kept from step to step: early
  // in a solve they are tens of megabytes, allocated afresh every step).
  std::vector<std::vector<ReceivedPush>> pushesReceived_;
  // Per fiber, the owner box its middle lies in after the last move (separate() finds it while
  // the fiber's points are at hand; leavingFibers() counts those that left), -1: not moved.
  std::vector<int> movedOwner_;
  // Links closer than this to a rank's grown tester box go there: for the pairs of a step, and
  // for the minimum-gap probe at the end.
  double pairReach_ = 0.0, probeReach_ = 0.0;
  bool migrationDue_ = false; // some rank holds a fiber another rank's box owns (last step's move)
  // The detections' work since the tester boxes were cut: CollisionGrid::work plus
  // kHeldLinkWork per held link.
  std::uint64_t pairWork_ = 0;
  std::size_t testerRecuts_ = 0; // balanceTesters calls that moved a cut ...
  double testerCutMove_ = 0.0;   // ... and the largest move, as a fraction of the axis' span
  std::size_t migrations_ = 0, haloExchanges_ = 0, haloBytes_ = 0, peakHaloLinks_ = 0,
              peakRankPoints_ = 0, peakHeldLinks_ = 0, peakPartners_ = 0;

  RankFibers rankFibers() { return RankFibers{ model_, st_ }; }

  // SolverDistribution.cxx
  void startDistribution();
  void balanceTesters();
  void resetTraffic();
  void migrate();
  void gatherLinks(const std::vector<char>* active, const std::vector<char>* closed, double scale,
    bool forGapProbe = false);
  std::int64_t leavingFibers() const;

  // Collisions and links of the whole model: a pair counts on the rank testing it.
  struct Counts
  {
    std::size_t pairs = 0;
    std::size_t links = 0;
    bool changed = false;
  };
  // This rank's share of the counts: pairs, links, changed.
  std::vector<std::int64_t> localCounts(bool changed) const
  {
    return { static_cast<std::int64_t>(pairs_.size()), static_cast<std::int64_t>(ownLinkCount_),
      changed ? 1 : 0 };
  }
  static Counts countsOf(const std::vector<std::int64_t>& v)
  {
    return { static_cast<std::size_t>(v[0]), static_cast<std::size_t>(v[1]), v[2] > 0 };
  }

  // SolverDetection.cxx
  Counts globalCounts(bool changed) const;
  bool detect(Counts* counts = nullptr, bool changed = false, bool boundFirst = false);
  PairBound wholeModelPairBound() const;
  std::string packingMessage(const PairBound& bound) const;
  bool findBoundedPairs(bool boundFirst);
  bool searchPairs(double limit, bool& overflow);

  // SolverMoves.cxx
  bool shapeControl();
  bool shapeWithinLimits() const;
  bool localShapeWithinLimits() const;
  void separate();

  // SolverMeasures.cxx
  double overlapFreeScale() const;
  double maxOverlap() const;

  double median() { return medianRadius(model_, comm_); }

  // Σ π ρ² · link length of the fibers of all ranks, the same bits for any split.
  double fiberVolume() { return capsuleVolume(model_, comm_); }

  bool periodic() const { return o_.periodicCell.enabled(); }

  // A fiber's tortuosity is restored once it falls this far below the target (§5.3): 5 % of the
  // target's excess over 1, so the solved fibers keep at least 95 % of the requested excess.
  double tortuosityTolerance() const { return 0.05 * (o_.tortuosity - 1.0); }

  // Largest move of a point per step, boosted with the pushes (PushBoost 2: fastPLI's 0.2·r); the
  // curvature correction steps scale with it as in fastPLI.
  double moveCap() const { return st_.vMax * (1.0 + 0.6 * (st_.pushScale - 1.0)); }

  // The last point of a closed fiber is its first point shifted by the closure, exactly.
  void close(std::size_t f)
  {
    if (periodic() && st_.closed[f])
    {
      Fiber& fib = model_.fibers[f];
      fib.points.back() = fib.points.front() + st_.closure[f];
    }
  }

  // Point index (into force_) of the outer neighbour of the first (before) or second (after)
  // point of link k of fiber f, or SIZE_MAX at an open end; through the closure on a closed fiber.
  std::size_t outerBefore(std::size_t f, std::size_t k) const
  {
    const std::size_t base = pointOffset_[f];
    if (k > 0)
      return base + k - 1;
    const std::size_t n = model_.fibers[f].size();
    return periodic() && st_.closed[f] ? base + n - 2 : SIZE_MAX;
  }
  std::size_t outerAfter(std::size_t f, std::size_t k) const
  {
    const std::size_t base = pointOffset_[f];
    const std::size_t n = model_.fibers[f].size();
    if (k + 2 < n)
      return base + k + 2;
    return periodic() && st_.closed[f] ? base + 1 : SIZE_MAX;
  }

  // Link i of links_ as its pairs' pushes need it: its fiber's index in this rank's model
  // (kNotOwned: another rank's; serial: the link's fiber), the rank owning that fiber (`me`: this
  // rank's) and the smaller radius of its two points (from the model, or as another rank sent it).
  struct LinkSide
  {
    std::uint32_t local;
    int owner;
    double pointRadius;
  };
  LinkSide sideOf(std::size_t i, int me) const
  {
    const CapsuleLink& l = links_[i];
    const std::uint32_t f = comm_ ? held_.local[i] : l.fiber;
    if (f == kNotOwned)
      return { f, held_.owner[i], held_.pointRadius[i] };
    const Fiber& fib = model_.fibers[f];
    return { f, me, std::min(fib.radii[l.k], fib.radii[l.k + 1]) };
  }
};

// SolverSetup.cxx: per fiber, source indices, repeated points removed (§9), fibers without 2
// distinct points excluded from solving; the warnings count all ranks.
void prepareFibers(SolverEngine& s, std::vector<std::string>& warnings);
// [ours] Periodic cell: which fibers are closed through it (snapped to the exact lattice vector).
void prepareClosures(SolverEngine& s);
// [ours] Radius growth: the capsule size to start from (collision-solver option doc).
double initialScale(const CollisionSolverOptions& o);
// L̄ (§5.1): 0 = automatic, 2 × median radius (the fastPLI author's choice); < 0 = off.
double resolveSegmentLength(SolverEngine& s, const CollisionSolverOptions& o);
// v_max and the parameter sanity warnings of §4.2 / §5.2.
void configure(SolverEngine& s, std::vector<std::string>& warnings);

// SolverMeasures.cxx: smallest surface gap over pairs closer than probe (µm); probe when no pair
// is that close.
double smallestGap(SolverEngine& s, double probe);

} // namespace fiberpli
