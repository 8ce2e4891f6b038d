#include "Solver/SolverChecks.h"

#include "Model/PeriodicCellRule.h"
#include "Solver/SolverEngine.h"
#include "Util/Fnv1a.h"
#include "Util/MemoryBudget.h"
#include "Util/NumberFormat.h"
#include "Util/Threads.h"
#include "Util/ValueCheck.h"

#include <cmath>
#include <cstring>
#include <sstream>
#include <unordered_map>

namespace fiberpli
{

namespace
{
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
DuplicateStacks findDuplicateStacks(const FiberModel& model)
{
  DuplicateStacks d;
  std::unordered_multimap<std::size_t, std::size_t> seen;
  std::vector<std::size_t> count(model.fibers.size(), 0);
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fib = model.fibers[f];
    // The hash only buckets the fibers: a copy is confirmed byte by byte below.
    std::uint64_t hash = fnv1a(fib.points.data(), fib.points.size() * sizeof(Vec3));
    fnv1aAdd(hash, fib.radii.data(), fib.radii.size() * sizeof(double));
    const std::size_t h = static_cast<std::size_t>(hash);
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

} // namespace

std::string validateCollisionSolverOptions(const CollisionSolverOptions& o)
{
  const auto finite = [](double v) { return std::isfinite(v); };
  const bool checkCell =
    o.periodicCell.enabled() || !isFinite(o.periodicCell.lo) || !isFinite(o.periodicCell.hi);
  return ValueChecks()
    .require(
      finite(o.segmentLength), "SegmentLength", o.segmentLength, "finite (0 = auto, < 0 = off)")
    .require(finite(o.minCurvatureRadius) && o.minCurvatureRadius >= 0.0, "MinCurvatureRadius",
      o.minCurvatureRadius, ">= 0 (0 = off)")
    .require(o.maxSteps >= 0, "MaxSteps", o.maxSteps, ">= 0")
    .require(finite(o.separationSpeed) && o.separationSpeed > 0.0 && o.separationSpeed <= 1.0,
      "SeparationSpeed", o.separationSpeed, "in (0, 1]")
    .require(finite(o.overlapPush) && o.overlapPush >= 0.0 && o.overlapPush <= 1.0, "OverlapPush",
      o.overlapPush, "in [0, 1]")
    .require(finite(o.pushSpread) && o.pushSpread >= 0.0 && o.pushSpread <= 1.0, "PushSpread",
      o.pushSpread, "in [0, 1]")
    .require(finite(o.maxDisplacement) && o.maxDisplacement > 0.0, "MaxDisplacement",
      o.maxDisplacement, "> 0")
    .require(finite(o.pushBoost) && o.pushBoost >= 1.0 && o.pushBoost <= 4.0, "PushBoost",
      o.pushBoost, "in [1, 4] (1 = off)")
    .require(finite(o.drag) && o.drag >= 0.0 && o.drag < 1.0, "Drag", o.drag, "in [0, 1)")
    .require(o.dragSteps >= 0, "DragSteps", o.dragSteps, ">= 0 (0 = every step)")
    .then(validateThreadCount(o.numberOfThreads))
    .require(finite(o.minimumGap) && o.minimumGap >= 0.0, "MinimumGap", o.minimumGap, ">= 0")
    .require(o.stallSteps >= 0, "StallSteps", o.stallSteps, ">= 0 (0 = off)")
    .require(
      finite(o.initialRadiusScale) && o.initialRadiusScale >= 0.0 && o.initialRadiusScale <= 1.0,
      "InitialRadiusScale", o.initialRadiusScale, "in [0, 1] (0 = automatic, 1 = off)")
    .require(finite(o.tortuosity) && o.tortuosity >= 0.0 && o.tortuosity <= 3.0, "Tortuosity",
      o.tortuosity, "in [0, 3] (0 or 1 = off)")
    .require(finite(o.tortuosityWavelength) && o.tortuosityWavelength >= 0.0,
      "TortuosityWavelength", o.tortuosityWavelength, ">= 0 (0 = every wavelength)")
    .require(!o.holdTortuosity || o.tortuosity > 1.0, "Tortuosity", o.tortuosity,
      "above 1 with HoldTortuosity (the tortuosity to hold)")
    // Model/PeriodicCellRule.h: "" when usable
    .then(checkCell ? validatePeriodicCell(o.periodicCell) : std::string())
    .error();
}

// validateModel (short fibers allowed: they are copied through), the fiber named by its global
// index (global[i] of piece fiber i; none given: the piece index), so a distributed run's message
// is the serial one for any rank count.
std::string validatePiece(const FiberModel& piece, const std::vector<std::int64_t>& global)
{
  std::size_t bad = 0;
  std::string error = validateModel(piece, &bad, ShortFibers::Allowed);
  const std::string local = "fiber " + formatNumber(bad);
  if (!error.empty() && bad < global.size() && error.compare(0, local.size(), local) == 0)
  {
    error = "fiber " + formatNumber(global[bad]) + error.substr(local.size());
  }
  return error;
}

// §8: refuse sizes beyond the memory budget before any allocation instead of running out of
// memory in the middle of a step. Two terms: the points, at most max(n, arc length / l_min + 1)
// per fiber whatever splitting does later (links are kept at >= l_min = 2/3 SegmentLength), and
// the colliding pairs of the first steps, when they are most, on the links of the input once
// length control has brought them to about SegmentLength. (Charging the pairs to the worst-case
// point count as well refused a 1 mm x 1 mm x 60 um section at 60 % that needs 8.5 GB in all.)
// Distributed: the fibers this rank owns (at most the serial run's), against its budget.
std::string checkMemory(const SolverEngine& s)
{
  double length = 0.0;
  double points = 0.0;
  double estimate = 0.0;
  double startPoints = 0.0;
  const double l = s.st_.segmentLength;
  for (const Fiber& f : s.model_.fibers)
  {
    double arc = 0.0;
    for (std::size_t i = 0; i + 1 < f.size(); ++i)
    {
      arc += distance(f.points[i], f.points[i + 1]);
    }
    const double n = static_cast<double>(f.size());
    length += arc;
    points += n;
    estimate += l > 0.0 ? std::max(n, arc / (l * (2.0 / 3.0)) + 1.0) : n;
    startPoints += l > 0.0 ? std::max(n, arc / l + 1.0) : n;
  }
  // Colliding pairs per link at the start of a dense run: a partner fiber crosses a link's reach
  // of ~4 radii with 1 + 4ρ/L̄ of its links; 2 partners per link at the paper's density (measured:
  // 5 pairs per link at L̄ = 2.5ρ, 40 at L̄ = ρ/8).
  const double meanLink = l > 0.0 ? l : length / std::max(1.0, points);
  const double pairsPerLink =
    meanLink > 0.0 ? 2.0 * (1.0 + 4.0 * medianRadius(s.model_) / meanLink) : 2.0;
  const double bytes = estimate * bytesPerPoint() + startPoints * pairsPerLink * bytesPerPair();
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
std::string checkStacksAndGap(const FiberModel& model, const CollisionSolverOptions& o, Comm* comm)
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

} // namespace fiberpli
