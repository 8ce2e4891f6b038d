#include "Solver/CollisionSolver.h"

#include "Index/CollisionGrid.h"
#include "Index/PeriodicPairs.h"
#include "Model/PeriodicCellRule.h"
#include "Solver/Decomposition.h"
#include "Solver/LinkExchange.h"
#include "Solver/PairBound.h"
#include "Solver/PushBoost.h"
#include "Util/MemoryBudget.h"
#include "Util/Threads.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <numeric>
#include <sstream>
#include <unordered_map>

namespace fiberpli
{

namespace
{
// Flat link array of all fibers with >= 2 points; the index is the global link id (§1).
// Offsets first (serial prefix sums), then the fibers in parallel: each writes its own range.
// closed (optional): fibers closed through a periodic cell; scale: capsule radii × scale (growth).
void buildLinks(const FiberModel& model, const std::vector<char>* active, int threads,
  std::vector<CapsuleLink>& links, std::vector<std::size_t>* pointOffset,
  const std::vector<char>* closed = nullptr, double scale = 1.0)
{
  const std::size_t nf = model.fibers.size();
  std::vector<std::size_t> linkOffset(nf + 1, 0);
  if (pointOffset)
  {
    pointOffset->assign(nf + 1, 0);
  }
  std::size_t points = 0;
  std::size_t nLinks = 0;
  for (std::size_t f = 0; f < nf; ++f)
  {
    const Fiber& fib = model.fibers[f];
    if (pointOffset)
    {
      (*pointOffset)[f] = points;
    }
    points += fib.points.size();
    linkOffset[f] = nLinks;
    if (fib.points.size() >= 2 && !(active && !(*active)[f]))
    {
      nLinks += fib.points.size() - 1;
    }
  }
  linkOffset[nf] = nLinks;
  if (pointOffset)
  {
    (*pointOffset)[nf] = points;
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

// Median point radius of the fibers with >= 2 points; distributed (comm): of all ranks' fibers,
// exactly the same value.
double medianRadius(const FiberModel& model, SolverComm* comm = nullptr)
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

// What the solver keeps per point (model point and radius, velocity and source index, force) and
// per link (its capsule and the grid's buffers); links ≈ points.
constexpr double kBytesPerPoint = 2.0 * sizeof(Vec3) + 2.0 * sizeof(double) + sizeof(Vec3) + sizeof(CapsuleLink);
double bytesPerPoint()
{
  return kBytesPerPoint + CollisionGrid::bytesPerLink();
}
double bytesPerPair()
{
  return CollisionGrid::bytesPerPair() + static_cast<double>(sizeof(LinkPairPush));
}

// Exact copies of fibers (same points and radii): how many fibers repeat an earlier one, and the
// id and copy count of the largest stack. Hash first, then compare bytes.
struct DuplicateStacks
{
  std::size_t copies = 0;
  std::size_t largest = 0;
  std::int64_t largestId = 0;
};

// A few exact copies separate like any overlap; a stack of many is a data error (tractography
// output repeating a streamline) whose pairs grow with the square of its height.
constexpr std::size_t kMaxExactCopies = 16;
// Gaps beyond a few radii make every link collide with the links of all fibers nearby.
constexpr double kMaxGapRadii = 10.0;
// From this many links a step takes long enough (~0.1 s per 1e5 links on one core) that abort
// is also checked in the middle of a step.
constexpr std::size_t kLinksForMidStepProgress = 200000;

DuplicateStacks findDuplicateStacks(const FiberModel& model)
{
  DuplicateStacks d;
  std::unordered_multimap<std::size_t, std::size_t> seen;
  std::vector<std::size_t> count(model.fibers.size(), 0);
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fib = model.fibers[f];
    std::size_t h = fib.points.size();
    const auto mix = [&h](const void* data, std::size_t bytes) {
      const auto* c = static_cast<const unsigned char*>(data);
      for (std::size_t i = 0; i < bytes; ++i)
        h = h * 1099511628211ull + c[i];
    };
    mix(fib.points.data(), fib.points.size() * sizeof(Vec3));
    mix(fib.radii.data(), fib.radii.size() * sizeof(double));
    bool copy = false;
    const auto range = seen.equal_range(h);
    for (auto it = range.first; it != range.second && !copy; ++it)
    {
      const Fiber& o = model.fibers[it->second];
      if (o.points.size() == fib.points.size() &&
        std::memcmp(o.points.data(), fib.points.data(), fib.points.size() * sizeof(Vec3)) == 0 &&
        std::memcmp(o.radii.data(), fib.radii.data(), fib.radii.size() * sizeof(double)) == 0)
      {
        copy = true;
        ++d.copies;
        if (++count[it->second] > d.largest)
        {
          d.largest = count[it->second];
          d.largestId = o.id;
        }
      }
    }
    if (!copy)
    {
      seen.emplace(h, f);
    }
  }
  return d;
}

// Steps between re-cuts of the distributed solver's tester slabs (a histogram sum each time).
constexpr int kBalanceSteps = 32;
// Pairs per link below which the packing bound (>= 27 per link, Index/CollisionGrid.h) cannot be
// exceeded, so its exact sum over all links is skipped.
constexpr int kPairsPerLinkBelowBound = 26;

class Solver
{
public:
  Solver(FiberModel& model, const CollisionSolverOptions& o, int threads)
    : model_(model), o_(o), threads_(threads)
  {
  }

  FiberModel& model_;
  const CollisionSolverOptions& o_;
  int threads_;
  CollisionSolverState st_; // what a step hands to the next (header); the rest is rebuilt per step
  std::vector<CapsuleLink> links_; // what the pairs are found among (distributed: the held links)
  std::vector<std::size_t> pointOffset_;
  std::vector<CapsulePair> pairs_;
  std::vector<LinkPairPush> push_; // per pair found here, in pair order
  std::vector<Vec3> force_;
  CollisionGrid grid_;
  PeriodicPairs periodic_; // [ours] the image-aware detector of a periodic cell
  std::string detectError_;
  // Distributed run (docs/solver.md §13); comm_ null: this process alone. The model holds the
  // fibers this rank owns; the pairs are found among the links near its slab (LinkExchange.h).
  SolverComm* comm_ = nullptr;
  std::vector<CapsuleLink> ownLinks_; // the owned fibers' links (fiber = index in the model)
  HeldLinkInfo held_;                 // per link of links_
  SlabLayout layout_;
  // Links closer than this along the slab axis to a rank's test region go there: for the pairs of
  // a step, and for the minimum-gap probe at the end.
  double pairReach_ = 0.0, probeReach_ = 0.0;
  bool migrationDue_ = false; // some rank holds a fiber another rank's slab owns (last step's move)
  std::uint64_t pairWork_ = 0; // the pair search's work (CollisionGrid::work) since the tester slabs were cut
  std::size_t testerRecuts_ = 0; // balanceTesters calls that moved a cut ...
  double testerCutMove_ = 0.0;   // ... and the largest move, as a fraction of the axis' span
  std::size_t migrations_ = 0, haloExchanges_ = 0, haloBytes_ = 0, peakHaloLinks_ = 0, peakRankPoints_ = 0,
              peakHeldLinks_ = 0;

  RankFibers rankFibers() { return RankFibers{ model_, st_ }; }

  // The slabs, the pair and probe reaches and every fiber to its owner (the run's first exchange).
  void startDistribution()
  {
    layout_ = SlabLayout::make(model_, o_.periodicCell, *comm_);
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
  // Every kBalanceSteps steps the tester slabs are re-cut at equal pair work of the steps since
  // (the link counts they start with balance the links, not their pairs: the 1000-fiber cube's
  // ranks did 52 / 48 % of the box tests).
  void balanceTesters()
  {
    if (st_.steps > 0 && st_.steps % kBalanceSteps == 0)
    {
      const SlabLayout before = layout_;
      layout_.balanceTesterSlabs(model_, static_cast<std::int64_t>(pairWork_), *comm_);
      pairWork_ = 0;
      const double span = layout_.testerLo(comm_->size()) - layout_.testerLo(0);
      double moved = 0.0;
      for (int q = 1; q < comm_->size(); ++q)
        moved = std::max(moved, std::abs(layout_.testerLo(q) - before.testerLo(q)));
      if (moved > 0.0)
      {
        ++testerRecuts_;
        testerCutMove_ = std::max(testerCutMove_, moved / span);
      }
    }
  }
  void resetTraffic()
  {
    migrations_ = haloExchanges_ = haloBytes_ = peakHaloLinks_ = peakRankPoints_ = peakHeldLinks_ = 0;
    testerRecuts_ = 0;
    testerCutMove_ = 0.0;
  }

  // Before a detection: fibers whose slab changed go to their new owner (only when a rank said so
  // at the end of the last step: most steps move no fiber out of its slab, and the links go to
  // every rank whose region they reach whoever owns them).
  void migrate()
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
    }
  }

  // links_ (and pointOffset_) of the owned fibers; distributed: the links near this rank's slab,
  // from all owners, with the current positions (so they are complete for this step), or with
  // the wider reach of the minimum-gap probe (then not counted as a step's traffic).
  void gatherLinks(const std::vector<char>* active, const std::vector<char>* closed, double scale,
    bool forGapProbe = false)
  {
    buildLinks(model_, active, threads_, comm_ ? ownLinks_ : links_, &pointOffset_, closed, scale);
    if (!comm_)
    {
      return;
    }
    const double reach = forGapProbe ? probeReach_ : pairReach_;
    const TrafficCount sent = exchangeLinks(ownLinks_, model_, st_.global, scale, layout_, reach, *comm_, links_, held_);
    if (forGapProbe)
    {
      return;
    }
    haloBytes_ += sent.bytes;
    ++haloExchanges_;
    std::size_t halo = 0;
    for (std::uint32_t f : held_.local)
      halo += f == kNotOwned ? 1 : 0;
    peakHeldLinks_ = std::max(peakHeldLinks_, links_.size());
    peakHaloLinks_ = std::max(peakHaloLinks_, halo);
    peakRankPoints_ = std::max(peakRankPoints_, pointOffset_.back() + halo); // owned points + halo links
  }

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
    return { static_cast<std::int64_t>(pairs_.size()), static_cast<std::int64_t>(ownLinks_.size()), changed ? 1 : 0 };
  }
  static Counts countsOf(const std::vector<std::int64_t>& v)
  {
    return { static_cast<std::size_t>(v[0]), static_cast<std::size_t>(v[1]), v[2] > 0 };
  }
  Counts globalCounts(bool changed) const
  {
    if (!comm_)
    {
      return { pairs_.size(), links_.size(), changed };
    }
    std::vector<std::int64_t> v = localCounts(changed);
    comm_->sum(v);
    return countsOf(v);
  }
  // Owned fibers whose middle left this rank's slab (after a move): they migrate next step.
  std::int64_t leavingFibers() const
  {
    std::int64_t n = 0;
    const int me = comm_->rank();
    for (std::size_t f = 0; f < model_.fibers.size(); ++f)
      n += layout_.owner(model_.fibers[f]) != me ? 1 : 0;
    return n;
  }

  double median() { return medianRadius(model_, comm_); }

  // Σ π ρ² · link length of the fibers of all ranks, the same bits for any split.
  double fiberVolume()
  {
    ExactSum sum;
    for (std::size_t f = 0; f < model_.fibers.size(); ++f)
    {
      const Fiber& fib = model_.fibers[f];
      for (std::size_t k = 0; k + 1 < fib.size(); ++k)
      {
        const double rho = fib.linkRadius(k);
        sum.add(M_PI * rho * rho * distance(fib.points[k], fib.points[k + 1]));
      }
    }
    return sum.total(comm_);
  }

  bool periodic() const { return o_.periodicCell.enabled(); }

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

  // Length then curvature per fiber; parallel over fibers, each fiber sequential (§5).
  bool shapeControl()
  {
    const std::int64_t nf = static_cast<std::int64_t>(model_.fibers.size());
    int changed = 0;
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
      bool c = controlSegmentLength(fib, st, st_.segmentLength, closed ? 3 : 2);
      c = controlCurvature(fib, o_.minCurvatureRadius, moveCap(), o_.endPoints, closure) || c;
      close(static_cast<std::size_t>(f));
      changed |= c ? 1 : 0;
    }
    return changed != 0;
  }

  // The state shape control would leave untouched (used after an abort, where it did not run).
  bool shapeWithinLimits() const
  {
    const bool ok = localShapeWithinLimits();
    return comm_ ? !anyRank(*comm_, !ok) : ok;
  }
  bool localShapeWithinLimits() const
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
      if (!curvatureOk(fib, o_.minCurvatureRadius, closed ? &st_.closure[f] : nullptr))
      {
        return false;
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

  // False when the pairs cannot be found: a periodic cell too small for the links, or more pairs
  // than their limit (the whole model's packingPairBound or this process's memory budget);
  // detectError_ says why. counts (if given): the global counts, with `changed` (shape control's)
  // or-ed over the ranks. boundFirst: distributed, the packing bound is also computed before the
  // search, so that a stack of fibers stops it early (the start; later steps check the count).
  bool detect(Counts* counts = nullptr, bool changed = false, bool boundFirst = false)
  {
    if (comm_)
    {
      migrate();
    }
    gatherLinks(&st_.active, periodic() ? &st_.closed : nullptr, st_.scale);
    const bool found = findBoundedPairs(boundFirst);
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

  // The packing bound of all links (of every rank: collective when distributed).
  PairBound wholeModelPairBound() const
  {
    return packingPairBound(comm_ ? ownLinks_ : links_, o_.minimumGap, comm_);
  }
  std::string packingMessage(const PairBound& bound) const
  {
    std::ostringstream msg;
    msg << "more than " << static_cast<std::size_t>(bound.pairs) << " capsule pairs of " << bound.links
        << " links collide (MinimumGap " << o_.minimumGap << "), more than any packing of fibers of capsule radius up to "
        << bound.rhoMax << " um can have: the fibers lie (nearly) on top of each other; spread them or lower the radii";
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
  bool findBoundedPairs(bool boundFirst)
  {
    PairBound bound;
    bound.pairs = HUGE_VAL; // not known yet
    if (comm_ && boundFirst)
    {
      bound = wholeModelPairBound();
    }
    const double budget = memoryBudgetBytes() - bytesPerPoint() * static_cast<double>(links_.size());
    const double affordable = std::max(0.0, budget) / bytesPerPair();
    const double belowBound = comm_ ? HUGE_VAL : kPairsPerLinkBelowBound * static_cast<double>(links_.size());
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
             bytesPerPoint() * static_cast<double>(links_.size()), "storing them beside the links")
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
  bool searchPairs(double limit, bool& overflow)
  {
    const auto maxPairs = static_cast<std::size_t>(limit);
    const std::vector<char>* tested = comm_ ? &held_.tested : nullptr;
    overflow = false;
    if (periodic())
    {
      detectError_ =
        periodic_.findPairs(links_, o_.periodicCell, o_.minimumGap, threads_, pairs_, maxPairs, &overflow, tested);
      pairWork_ += periodic_.work();
      return detectError_.empty();
    }
    overflow = !grid_.findPairs(links_, o_.minimumGap, threads_, pairs_, maxPairs, tested, testedPairs(layout_));
    pairWork_ += grid_.work();
    return true;
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

  // The smaller radius of the two points of link i of links_.
  double smallerPointRadius(std::size_t i) const
  {
    if (comm_)
    {
      return held_.pointRadius[i];
    }
    const CapsuleLink& l = links_[i];
    const Fiber& fib = model_.fibers[l.fiber];
    return std::min(fib.radii[l.k], fib.radii[l.k + 1]);
  }

  // Largest factor s <= 1 with δ >= s·(ρa + ρb) + g for every colliding pair.
  double overlapFreeScale() const
  {
    double f = 1.0;
    for (const CapsulePair& p : pairs_)
    {
      f = std::min(f, std::max(0.0, p.distance - o_.minimumGap) / (links_[p.a].rho + links_[p.b].rho));
    }
    return comm_ ? minOverRanks(*comm_, f) : f;
  }

  double maxOverlap() const
  {
    double m = 0.0;
    for (const CapsulePair& p : pairs_)
    {
      m = std::max(m, links_[p.a].rho + links_[p.b].rho + o_.minimumGap - p.distance);
    }
    return comm_ ? maxOverRanks(*comm_, m) : m;
  }

  // §4.4: pushes in parallel into their own slots, summed serially in pair order (distributed:
  // by the owners of the links, LinkExchange.h), then moved per fiber in parallel: no floating
  // result depends on the thread or the rank that computed it.
  void separate()
  {
    const std::int64_t np = static_cast<std::int64_t>(pairs_.size());
    push_.resize(pairs_.size());
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (std::int64_t pi = 0; pi < np; ++pi)
    {
      const CapsulePair& p = pairs_[static_cast<std::size_t>(pi)];
      const CapsuleLink& la = links_[p.a];
      const CapsuleLink& lb = links_[p.b];
      const double rMin = std::min(smallerPointRadius(p.a), smallerPointRadius(p.b));
      const double overlap = la.rho + lb.rho + o_.minimumGap - p.distance;
      const double sigma =
        boostedPush(std::max(o_.separationSpeed * rMin, o_.overlapPush * overlap), st_.pushScale, overlap);
      const Vec3 n = sigma * p.direction;
      LinkPairPush& out = push_[static_cast<std::size_t>(pi)];
      out.fiberA = la.fiber;
      out.kA = la.k;
      out.fiberB = lb.fiber;
      out.kB = lb.k;
      out.ownerA = comm_ ? held_.owner[p.a] : 0;
      out.ownerB = comm_ ? held_.owner[p.b] : 0;
      out.a0 = (1.0 - p.s) * n;
      out.a1 = p.s * n;
      out.b0 = -((1.0 - p.t) * n);
      out.b1 = -(p.t * n);
    }
    force_.assign(pointOffset_.back(), Vec3{});
    const double spread = o_.pushSpread;
    // One pair's pushes onto the points of its links that this rank owns (fa, fb: the links'
    // fibers in the model, SIZE_MAX: another rank's; that side is added there, in the same order).
    const auto apply = [this, spread](const LinkPairPush& p, std::size_t fa, std::size_t fb) {
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
        const auto add = [this, spread](std::size_t i, const Vec3& push) {
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
      // Per sender, the pushes others tested on this rank's links (not kept between steps: the
      // peak memory stays the pair search's).
      std::vector<std::vector<ReceivedPush>> received;
      returnPushes(push_, st_.global, *comm_, sent, received);
      haloBytes_ += sent.bytes;
      const auto own = [](std::uint32_t f) { return f == kNotOwned ? SIZE_MAX : static_cast<std::size_t>(f); };
      forPushesInPairOrder(push_, pairs_, held_.local, received,
        [&](const LinkPairPush& p, std::uint32_t fa, std::uint32_t fb) { apply(p, own(fa), own(fb)); });
    }
    const std::int64_t nf = static_cast<std::int64_t>(model_.fibers.size());
    const double drag = o_.drag;
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
      for (std::size_t i = 0; i < n; ++i)
      {
        fib.points[i] += vel[i];
      }
      close(static_cast<std::size_t>(f));
    }
  }
};

// Per fiber: source indices, repeated points removed (§9), fibers without 2 distinct points
// excluded from solving.
void prepareFibers(Solver& s, std::vector<std::string>& warnings)
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
    std::vector<std::int64_t> n{ static_cast<std::int64_t>(repeated), static_cast<std::int64_t>(tooShort) };
    s.comm_->sum(n);
    repeated = static_cast<std::size_t>(n[0]);
    tooShort = static_cast<std::size_t>(n[1]);
  }
  if (repeated > 0)
  {
    warnings.push_back(std::to_string(repeated) + " repeated consecutive points removed");
  }
  if (tooShort > 0)
  {
    warnings.push_back(std::to_string(tooShort) +
      " fibers with fewer than 2 distinct points are not solved (copied through)");
  }
}

// [ours] Periodic cell: which fibers are closed through it (snapped to the exact lattice vector).
void prepareClosures(Solver& s)
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

// [ours] Radius growth: the capsule size to start from (collision-solver option doc).
double initialScale(const CollisionSolverOptions& o)
{
  if (o.initialRadiusScale > 0.0)
  {
    return o.initialRadiusScale;
  }
  return 1.0; // growth measured slower than plain pushing so far (bench/README.md)
}

// Smallest surface gap over pairs closer than probe (µm); probe when no pair is that close.
// Distributed, the links are gathered again with the probe's reach (the pairs found before no
// longer index them), and each rank examines only the pairs it tests (the minimum over the ranks
// is the serial one). This search set a solve's peak memory (bench/README.md "Memory per rank"):
// the step's pair and push lists, no longer needed, are released before it.
double smallestGap(Solver& s, double probe)
{
  std::vector<CapsulePair>().swap(s.pairs_);
  std::vector<LinkPairPush>().swap(s.push_);
  if (s.comm_)
  {
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
      s.periodic_.findPairs(
        s.links_, s.o_.periodicCell, g, s.threads_, near, static_cast<std::size_t>(-1), nullptr, tested);
    }
    else
    {
      s.grid_.findPairs(s.links_, g, s.threads_, near, static_cast<std::size_t>(-1), tested, testedPairs(s.layout_));
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

// L̄ (§5.1): 0 = automatic, 2 × median radius (the fastPLI author's choice); < 0 = off.
double resolveSegmentLength(Solver& s, const CollisionSolverOptions& o)
{
  const double l = o.segmentLength == 0.0 ? 2.0 * s.median() : o.segmentLength;
  return l == 0.0 ? -1.0 : l; // no fibers to take a radius from
}

// v_max and the parameter sanity warnings of §4.2 / §5.2.
void configure(Solver& s, std::vector<std::string>& warnings)
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
    warnings.push_back("smallest radius " + std::to_string(rMin) +
      " is below 1/2 of the median radius " + std::to_string(rMedian) +
      ": every point moves at most MaxDisplacement " + std::to_string(s.o_.maxDisplacement) +
      " x this radius = " + std::to_string(s.o_.maxDisplacement * rMin) +
      " um per step (slow; dense targets of such radii may need MaxDisplacement 0.4)");
  }
  if (s.o_.maxDisplacement > 1.0)
  {
    warnings.push_back("MaxDisplacement " + std::to_string(s.o_.maxDisplacement) +
      " is above 1: a point may move farther than the thinnest fiber's radius per step, so fibers can "
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
    warnings.push_back("MinCurvatureRadius " + std::to_string(s.o_.minCurvatureRadius) +
      " is below the largest radius " + std::to_string(rMax) +
      ": a tube bent that tightly intersects itself on the inside");
  }
  if (s.st_.segmentLength > 0.0 && s.o_.minCurvatureRadius > 0.0 &&
    s.o_.minCurvatureRadius < s.st_.segmentLength / std::sqrt(3.0))
  {
    warnings.push_back("MinCurvatureRadius " + std::to_string(s.o_.minCurvatureRadius) +
      " is below SegmentLength/sqrt(3): only the 60 degree rule can act");
  }
  if (s.st_.segmentLength > 0.0 && s.st_.segmentLength < 0.25 * rMedian)
  {
    warnings.push_back("SegmentLength " + std::to_string(s.st_.segmentLength) +
      " is below 1/4 of the median radius: many points, slow and memory hungry");
  }
}

// §8: splitting makes up to (arc length / l_min) points per fiber; refuse sizes beyond the memory
// budget before any allocation instead of running out of memory in the middle of a step.
// Distributed: the fibers this rank owns (at most the serial run's), against its budget.
std::string checkMemory(const Solver& s)
{
  double length = 0.0;
  double points = 0.0;
  for (const Fiber& f : s.model_.fibers)
  {
    for (std::size_t i = 0; i + 1 < f.size(); ++i)
    {
      length += distance(f.points[i], f.points[i + 1]);
    }
    points += static_cast<double>(f.size());
  }
  const double estimate = s.st_.segmentLength > 0.0 ? points + length / (s.st_.segmentLength * (2.0 / 3.0)) : points;
  // Colliding pairs per link at the start of a dense run: a partner fiber crosses a link's reach
  // of ~4 radii with 1 + 4ρ/L̄ of its links; 2 partners per link at the paper's density (measured:
  // 5 pairs per link at L̄ = 2.5ρ, 40 at L̄ = ρ/8).
  const double meanLink = s.st_.segmentLength > 0.0 ? s.st_.segmentLength : length / std::max(1.0, points);
  const double pairsPerLink = meanLink > 0.0 ? 2.0 * (1.0 + 4.0 * medianRadius(s.model_) / meanLink) : 2.0;
  const double bytes = estimate * (bytesPerPoint() + pairsPerLink * bytesPerPair());
  std::ostringstream what;
  what << "SegmentLength " << s.st_.segmentLength << " with a total fiber length of " << length
       << " (up to " << estimate << " points)";
  if (s.comm_) // each rank's own memory against its own budget (§13)
  {
    what << " on rank " << s.comm_->rank() << " of " << s.comm_->size();
  }
  const std::string problem = checkMemoryBudget(bytes, what.str());
  return problem.empty() ? problem : problem + "; raise SegmentLength";
}

// Checks that need the fibers and no pairs: exact copies (duplicate streamlines) beyond
// kMaxExactCopies and a MinimumGap beyond kMaxGapRadii × the largest radius. Both would make
// the colliding pairs grow with the square of the copies or the gap.
std::string checkStacksAndGap(const FiberModel& model, const CollisionSolverOptions& o, SolverComm* comm)
{
  std::ostringstream msg;
  const DuplicateStacks d = findDuplicateStacks(model);
  if (d.largest > kMaxExactCopies)
  {
    msg << "fiber id " << d.largestId << " has " << d.largest << " exact copies (" << d.copies
        << " duplicate fibers in all; at most " << kMaxExactCopies
        << " copies of a fiber are separated): remove the duplicates";
    return msg.str();
  }
  double rhoMax = largestRadius(model);
  if (comm)
  {
    rhoMax = maxOverRanks(*comm, rhoMax);
  }
  if (o.minimumGap > kMaxGapRadii * rhoMax)
  {
    msg << "MinimumGap is " << o.minimumGap << ", more than " << kMaxGapRadii
        << " x the largest fiber radius " << rhoMax
        << ": the solver separates touching fibers, it does not spread them apart; lower it";
  }
  return msg.str();
}

} // namespace

std::string validateCollisionSolverOptions(const CollisionSolverOptions& o)
{
  std::ostringstream msg;
  if (!std::isfinite(o.segmentLength))
  {
    msg << "SegmentLength is " << o.segmentLength << ", must be finite (0 = auto, < 0 = off)";
  }
  else if (!std::isfinite(o.minCurvatureRadius) || o.minCurvatureRadius < 0.0)
  {
    msg << "MinCurvatureRadius is " << o.minCurvatureRadius << ", must be >= 0 (0 = off)";
  }
  else if (o.maxSteps < 0)
  {
    msg << "MaxSteps is " << o.maxSteps << ", must be >= 0";
  }
  else if (!std::isfinite(o.separationSpeed) || o.separationSpeed <= 0.0 || o.separationSpeed > 1.0)
  {
    msg << "SeparationSpeed is " << o.separationSpeed << ", must be in (0, 1]";
  }
  else if (!std::isfinite(o.overlapPush) || o.overlapPush < 0.0 || o.overlapPush > 1.0)
  {
    msg << "OverlapPush is " << o.overlapPush << ", must be in [0, 1]";
  }
  else if (!std::isfinite(o.pushSpread) || o.pushSpread < 0.0 || o.pushSpread > 1.0)
  {
    msg << "PushSpread is " << o.pushSpread << ", must be in [0, 1]";
  }
  else if (!std::isfinite(o.maxDisplacement) || o.maxDisplacement <= 0.0)
  {
    msg << "MaxDisplacement is " << o.maxDisplacement << ", must be > 0";
  }
  else if (!std::isfinite(o.pushBoost) || o.pushBoost < 1.0 || o.pushBoost > 4.0)
  {
    msg << "PushBoost is " << o.pushBoost << ", must be in [1, 4] (1 = off)";
  }
  else if (!std::isfinite(o.drag) || o.drag < 0.0 || o.drag >= 1.0)
  {
    msg << "Drag is " << o.drag << ", must be in [0, 1)";
  }
  else if (!validateThreadCount(o.numberOfThreads).empty())
  {
    msg << validateThreadCount(o.numberOfThreads);
  }
  else if (!std::isfinite(o.minimumGap) || o.minimumGap < 0.0)
  {
    msg << "MinimumGap is " << o.minimumGap << ", must be >= 0";
  }
  else if (o.stallSteps < 0)
  {
    msg << "StallSteps is " << o.stallSteps << ", must be >= 0 (0 = off)";
  }
  else if (!std::isfinite(o.initialRadiusScale) || o.initialRadiusScale < 0.0 || o.initialRadiusScale > 1.0)
  {
    msg << "InitialRadiusScale is " << o.initialRadiusScale << ", must be in [0, 1] (0 = automatic, 1 = off)";
  }
  else if (o.periodicCell.enabled() || !isFinite(o.periodicCell.lo) || !isFinite(o.periodicCell.hi))
  {
    msg << validatePeriodicCell(o.periodicCell); // Model/PeriodicCellRule.h: "" when usable
  }
  return msg.str();
}

namespace
{
// [ours] Radius growth per step while the deepest overlap is below 5 % of the median radius, and
// the move steps without growth after which growth gives up.
constexpr double kGrowth = 0.002;
constexpr int kGrowthStall = 2000;

// validateModel (short fibers allowed: they are copied through), the fiber named by its global
// index (global[i] of piece fiber i; none given: the piece index), so a distributed run's message
// is the serial one for any rank count.
std::string validatePiece(const FiberModel& piece, const std::vector<std::int64_t>& global)
{
  std::size_t bad = 0;
  std::string error = validateModel(piece, &bad, ShortFibers::Allowed);
  const std::string local = "fiber " + std::to_string(bad);
  if (!error.empty() && bad < global.size() && error.compare(0, local.size(), local) == 0)
  {
    error = "fiber " + std::to_string(global[bad]) + error.substr(local.size());
  }
  return error;
}
} // namespace

struct CollisionSolverRun::Impl
{
  Impl(FiberModel& m, const CollisionSolverOptions& o, const ProgressFn& p, const StepObserver& ob, SolverComm* c)
    : model(m), options(o), progress(p), observer(ob), s(m, options, 1)
  {
    s.comm_ = c;
  }

  enum class Phase
  {
    Created, ///< start() or resume() not called yet
    Running, ///< step() goes on
    Ended,   ///< the loop stopped: finish() makes the result
    Failed,  ///< result.error is set and final
    Finished ///< finish() made the result
  };

  FiberModel& model;
  const CollisionSolverOptions options;
  ProgressFn progress;
  StepObserver observer;
  Solver s;
  FiberModel input; // periodic or distributed runs: the model before preparation, restored on an error
  CollisionSolverResult result;
  Phase phase = Phase::Created;

  // The callback never sees progress go back. A stop on one rank stops all; distributed, the
  // same sum tells (with leaving non-null) whether any rank has fibers to migrate.
  bool report(double fraction, std::int64_t* leaving = nullptr)
  {
    s.st_.reported = std::max(s.st_.reported, fraction);
    const bool go = reportProgress(progress, s.st_.reported);
    if (!s.comm_)
    {
      return go;
    }
    std::vector<std::int64_t> v{ go ? 0 : 1, leaving ? *leaving : 0 };
    s.comm_->sum(v);
    if (leaving)
    {
      *leaving = v[1];
    }
    return v[0] == 0;
  }
  // Errors of one rank reach all (distributed runs restore the input piece).
  bool fail(const std::string& error)
  {
    return failAgreed(s.comm_ ? agreeOnError(*s.comm_, error) : error);
  }
  // The same for an error the ranks have agreed on already.
  bool failAgreed(const std::string& error)
  {
    if (error.empty())
    {
      return false;
    }
    if (s.comm_)
    {
      model = input;
    }
    result = CollisionSolverResult{};
    result.error = error;
    phase = Phase::Failed;
    return true;
  }
  std::string misfit(const CollisionSolverState& saved) const;
  double stepShareAfter(int steps) const
  {
    return options.maxSteps > 0 ? std::min(1.0, static_cast<double>(steps) / options.maxSteps) : 1.0;
  }
  // The pair limit (or a periodic cell too small for the links) met in the middle of a run.
  void failDetection(const std::string& where)
  {
    if (s.periodic() || s.comm_)
    {
      model = input; // the cell is too small for the links, or distributed: keep the input
      result = CollisionSolverResult{};
      result.error = s.detectError_ + (s.periodic() ? std::string() : where); // the serial text
    }
    else // the model is in this step's state
    {
      takeState();
      result.error = s.detectError_ + where;
    }
    phase = Phase::Failed;
  }
  // Distributed: every fiber back to the rank whose input piece held it; this rank's figures.
  void goHome()
  {
    RankFibers fibers = s.rankFibers();
    result.rankFibers = fibers.size();
    redistribute(fibers, s.st_.home, *s.comm_);
    result.migrations = static_cast<std::size_t>(sumOverRanks(static_cast<std::int64_t>(s.migrations_)));
    result.haloBytesPerStep = s.haloExchanges_ > 0 ? static_cast<double>(s.haloBytes_) / s.haloExchanges_ : 0.0;
    result.peakHaloLinks = s.peakHaloLinks_;
    result.peakRankPoints = s.peakRankPoints_;
    result.peakHeldLinks = s.peakHeldLinks_;
    result.testerRecuts = s.testerRecuts_;
    result.testerCutMove = s.testerCutMove_;
  }
  std::int64_t sumOverRanks(std::int64_t v)
  {
    std::vector<std::int64_t> x{ v };
    s.comm_->sum(x);
    return x[0];
  }
  // The result fields that are the state's (also on an error in the middle of a run).
  void takeState()
  {
    const CollisionSolverState& st = s.st_;
    result.steps = st.steps;
    result.segmentLength = st.segmentLength;
    result.bestCollisions = st.bestCollisions;
    result.bestStep = st.bestStep;
    result.warnings = st.warnings;
  }
};

CollisionSolverRun::CollisionSolverRun(FiberModel& model, const CollisionSolverOptions& options,
  const ProgressFn& progress, const StepObserver& observer, SolverComm* comm)
  : impl_(std::make_unique<Impl>(model, options, progress, observer, comm))
{
}

CollisionSolverRun::~CollisionSolverRun() = default;

const CollisionSolverState& CollisionSolverRun::state() const
{
  return impl_->s.st_;
}

bool CollisionSolverRun::start()
{
  Impl& r = *impl_;
  Solver& s = r.s;
  const CollisionSolverOptions& o = r.options;
  FiberModel& model = r.model;
  CollisionSolverState& st = s.st_;
  const std::size_t nf = model.fibers.size();
  std::int64_t first = 0; // global index of this piece's first fiber: pieces in rank order
  if (s.comm_)
  {
    r.input = model; // before any failure path: fail() restores it
    std::vector<std::int64_t> counts(static_cast<std::size_t>(s.comm_->size()), 0);
    counts[static_cast<std::size_t>(s.comm_->rank())] = static_cast<std::int64_t>(nf);
    s.comm_->sum(counts);
    first = std::accumulate(counts.begin(), counts.begin() + s.comm_->rank(), std::int64_t{ 0 });
  }
  st.global.resize(nf);
  std::iota(st.global.begin(), st.global.end(), first);
  std::string error = validateCollisionSolverOptions(o);
  if (error.empty())
  {
    error = validatePiece(model, st.global);
  }
  if (r.fail(error))
  {
    return false;
  }
  s.threads_ = resolveThreadCount(o.numberOfThreads);
  st.points.assign(nf, FiberPointState{});
  st.active.assign(nf, 1);
  st.closed.assign(nf, 0);
  st.closure.assign(nf, Vec3{});
  st.home.assign(nf, s.comm_ ? s.comm_->rank() : 0);
  if (s.comm_)
  {
    s.startDistribution();
  }
  // Before anything touches the model: a refused run leaves it unchanged.
  st.segmentLength = resolveSegmentLength(s, o);
  error = checkMemory(s);
  if (error.empty())
  {
    error = checkStacksAndGap(model, o, s.comm_);
  }
  if (error.empty())
  {
    error = checkCoordinateResolution(model, st.segmentLength); // Solver/ShapeControl.h
  }
  if (r.fail(error))
  {
    return false;
  }
  if (!s.periodic())
  {
    // Stacks of nearly identical fibers are refused on the input as it came, before the model
    // changes (the limit is checked again at every step; periodic runs restore the input).
    const bool found = s.detect(nullptr, false, true);
    if (r.failAgreed(found ? std::string() : s.detectError_)) // detect() agrees on it over the ranks
    {
      return false;
    }
  }
  // A periodic cell too small for the links is only known once they are built: keep the input.
  if (s.periodic() && !s.comm_)
  {
    r.input = model;
  }
  prepareFibers(s, st.warnings);
  prepareClosures(s);
  configure(s, st.warnings);
  st.scale = initialScale(o);
  st.growthTolerance = 0.05 * s.median();
  s.resetTraffic();
  r.phase = Impl::Phase::Running;
  return true;
}

// What resume(saved) refuses, on this rank alone (not collective).
std::string CollisionSolverRun::Impl::misfit(const CollisionSolverState& saved) const
{
  const Impl& r = *this;
  std::string error = validateCollisionSolverOptions(r.options);
  const std::size_t nf = r.model.fibers.size();
  const bool serialState = saved.global.size() != nf || saved.home.size() != nf;
  if (error.empty() && serialState && r.s.comm_ && r.s.comm_->size() > 1)
  {
    // Every rank would number its fibers 0..n-1: the global indices would collide.
    error = "the saved solver state has no global fiber indices (a serial state): it cannot "
            "resume a run over " + std::to_string(r.s.comm_->size()) + " ranks";
  }
  if (error.empty() && (saved.points.size() != nf || saved.active.size() != nf ||
    saved.closed.size() != nf || saved.closure.size() != nf))
  {
    error = "the saved solver state is for " + std::to_string(saved.points.size()) +
      " fibers, the model has " + std::to_string(nf);
  }
  for (std::size_t f = 0; error.empty() && f < nf; ++f)
  {
    const std::size_t n = r.model.fibers[f].size();
    if (saved.points[f].velocity.size() != n || saved.points[f].source.size() != n)
    {
      error = "the saved solver state of fiber " + std::to_string(f) + " has " +
        std::to_string(saved.points[f].velocity.size()) + " points, the model " + std::to_string(n);
    }
  }
  if (error.empty())
  {
    error = validatePiece(r.model, serialState ? std::vector<std::int64_t>{} : saved.global);
  }
  return error;
}

std::string CollisionSolverRun::resume(const CollisionSolverState& saved, const ResumeAgreement& agree)
{
  Impl& r = *impl_;
  r.phase = Impl::Phase::Failed;
  if (r.s.periodic() || r.s.comm_)
  {
    r.input = r.model; // before any failure path: fail() restores it
  }
  // Agreed over the ranks before any other collective: a rank refusing its state alone must not
  // leave the others waiting in the distribution below.
  const std::string misfit = r.misfit(saved);
  if (agree ? r.failAgreed(agree(misfit)) : r.fail(misfit))
  {
    return r.result.error;
  }
  const std::size_t nf = r.model.fibers.size();
  const bool serialState = saved.global.size() != nf || saved.home.size() != nf;
  r.s.threads_ = resolveThreadCount(r.options.numberOfThreads);
  r.s.st_ = saved;
  if (serialState) // one rank only (refused above otherwise)
  {
    r.s.st_.global.resize(nf);
    std::iota(r.s.st_.global.begin(), r.s.st_.global.end(), std::int64_t{ 0 });
    r.s.st_.home.assign(nf, 0);
  }
  if (r.s.comm_)
  {
    r.s.startDistribution(); // any slabs do: the result does not depend on who owns what
  }
  r.phase = Impl::Phase::Running;
  return {};
}

bool CollisionSolverRun::step()
{
  Impl& r = *impl_;
  if (r.phase != Impl::Phase::Running)
  {
    return false;
  }
  Solver& s = r.s;
  CollisionSolverState& st = s.st_;
  const CollisionSolverOptions& o = r.options;
  const bool changed = s.shapeControl();
  if (s.comm_)
  {
    s.balanceTesters();
  }
  Solver::Counts counts;
  if (!s.detect(&counts, changed))
  {
    r.failDetection(" (at step " + std::to_string(st.steps) + ")");
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
  const double resolved = st.firstCount > 0 ? 1.0 - std::log1p(static_cast<double>(count)) /
      std::log1p(static_cast<double>(st.firstCount)) : 1.0;
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
  const auto end = [&r]() {
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
    st.warnings.push_back("stopped after " + std::to_string(st.sinceImprovement) +
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
      s.detectError_ += " (at step " + std::to_string(st.steps) + ")";
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
      r.failDetection(" (at step " + std::to_string(r.s.st_.steps) + ")");
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
  Solver& s = r.s;
  CollisionSolverState& st = s.st_;
  const CollisionSolverOptions& o = r.options;
  FiberModel& model = r.model;
  CollisionSolverResult& result = r.result;
  result.radiusScale = st.scale;
  if (st.scale < 1.0)
  {
    // The output has the input radii: count what is left at full size.
    const double reached = s.periodic() ? s.fiberVolume() / o.periodicCell.volume() * st.scale * st.scale : -1.0;
    st.scale = 1.0;
    if (!s.detect())
    {
      r.takeState();
      result.error = s.detectError_ + " (at full radius after step " + std::to_string(st.steps) + ")";
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
  const ProgressFn& progress, const StepObserver& observer, SolverComm* comm)
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

std::size_t countCollisions(const FiberModel& model, double minimumGap, int numberOfThreads,
  const PeriodicCell& cell)
{
  std::vector<CapsuleLink> links;
  std::vector<CapsulePair> pairs;
  if (cell.enabled())
  {
    std::vector<char> closed(model.fibers.size(), 0);
    for (std::size_t f = 0; f < model.fibers.size(); ++f)
    {
      Vec3 t;
      closed[f] = isClosedFiber(model.fibers[f], cell, t);
    }
    buildLinks(model, nullptr, resolveThreadCount(numberOfThreads), links, nullptr, &closed);
  }
  else
  {
    buildLinks(model, nullptr, resolveThreadCount(numberOfThreads), links, nullptr);
  }
  const double limit = std::min(packingPairBound(links, minimumGap).pairs,
    std::max(0.0, memoryBudgetBytes()) / CollisionGrid::bytesPerPair());
  const auto maxPairs = static_cast<std::size_t>(limit);
  bool overflow = false;
  if (cell.enabled())
  {
    PeriodicPairs finder;
    if (!finder.findPairs(links, cell, minimumGap, numberOfThreads, pairs, maxPairs, &overflow).empty())
    {
      return std::numeric_limits<std::size_t>::max(); // cell too small for its links: no count
    }
  }
  else
  {
    CollisionGrid grid;
    overflow = !grid.findPairs(links, minimumGap, numberOfThreads, pairs, maxPairs);
  }
  return overflow ? maxPairs + 1 : pairs.size();
}

double cellVolumeFraction(const FiberModel& model, const PeriodicCell& cell, SolverComm* comm)
{
  ExactSum sum; // the same bits for any order and split of the fibers
  for (const Fiber& f : model.fibers)
  {
    for (std::size_t k = 0; k + 1 < f.size(); ++k)
    {
      const double rho = f.linkRadius(k);
      sum.add(M_PI * rho * rho * distance(f.points[k], f.points[k + 1]));
    }
  }
  const double volume = sum.total(comm);
  if (cell.enabled())
  {
    return volume / cell.volume();
  }
  Vec3 lo, hi;
  const bool any = modelBounds(model, true, lo, hi);
  if (comm)
  {
    std::vector<double> m(6, -HUGE_VAL);
    for (int d = 0; any && d < 3; ++d)
    {
      m[static_cast<std::size_t>(d)] = -lo[d];
      m[static_cast<std::size_t>(3 + d)] = hi[d];
    }
    comm->max(m);
    for (int d = 0; d < 3; ++d)
    {
      lo[d] = -m[static_cast<std::size_t>(d)];
      hi[d] = m[static_cast<std::size_t>(3 + d)];
    }
    if (!(m[3] > -HUGE_VAL))
    {
      return 0.0;
    }
  }
  else if (!any)
  {
    return 0.0;
  }
  const Vec3 e = hi - lo;
  return e.x * e.y * e.z > 0.0 ? volume / (e.x * e.y * e.z) : 0.0;
}

} // namespace fiberpli
