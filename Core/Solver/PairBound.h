/// PairBound: the packing bound on the colliding pairs the solver stores (docs/solver.md §8),
/// summed so that it is a property of the whole model: the same bits for any order of the links
/// and any split of them over ranks (docs/solver.md §13).
#pragma once

#include "Index/CollisionGrid.h"
#include "Parallel/Comm.h"

#include <cstddef>
#include <vector>

namespace fiberpli
{

/// The bound and what it was taken from (all links, of every rank).
struct PairBound
{
  double pairs = 0.0; ///< Σ_a n_a / 2 (Index/CollisionGrid.h, packingPartnerBound); 0 without links
  std::size_t links = 0; ///< links it was taken over
  double rhoMax = 0.0;   ///< their largest capsule radius (µm)
};

/// The packing bound of `links` with gap `minimumGap`: ρ_min and ρ_max exact, the mean link length
/// and Σ n_a in fixed point (Parallel/Collectives.h ExactSum), each n_a capped at 1e18. comm: each
/// rank passes the links it owns, and every rank gets the bound of all of them (collective: one
/// maximum, three sums).
PairBound packingPairBound(
  const std::vector<CapsuleLink>& links, double minimumGap, Comm* comm = nullptr);

} // namespace fiberpli
