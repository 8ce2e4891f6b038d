/// CapsulePairs: colliding capsule pairs and the smallest surface gap of a fiber model, through
/// this module's own spatial hash over capsule midpoints (minimum image in a periodic cell).
#pragma once

#include "Metrics/Capsules.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <cstdint>

namespace fiberpli
{

struct PairResult : Status
{
  std::int64_t collisions = 0; ///< pairs with surface gap < 0 (touching is no collision)
  double minGap = 0.0; ///< smallest |a − b| − r_a − r_b over compared pairs; NaN when none
};

/// Compares every pair of capsules except chain neighbours (chainNeighbours). Collisions are exact;
/// the smallest gap is exact too: the hash is rebuilt with a wider search margin until the
/// smallest gap found lies within the margin (then no unseen pair can be closer) or every pair has
/// been compared. Same result for any thread count.
PairResult compareCapsulePairs(
  const CapsuleSet& set, const PeriodicCell& cell, int numberOfThreads, const ProgressFn& progress);

} // namespace fiberpli
