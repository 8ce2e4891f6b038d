#include "Solver/PairBound.h"

#include "Parallel/Collectives.h"
#include "Solver/Decomposition.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace fiberpli
{

PairBound packingPairBound(const std::vector<CapsuleLink>& links, double minimumGap, Comm* comm)
{
  std::vector<double> extremes{ -HUGE_VAL, 0.0 }; // −ρ_min, ρ_max: one maximum
  ExactSum length;
  for (const CapsuleLink& l : links)
  {
    extremes[0] = std::max(extremes[0], -l.rho);
    extremes[1] = std::max(extremes[1], l.rho);
    length.add(l.arc1 - l.arc0);
  }
  std::vector<std::int64_t> count{ static_cast<std::int64_t>(links.size()) };
  if (comm)
  {
    comm->max(extremes);
    comm->sum(count);
  }
  const double total = length.total(comm);
  PairBound bound;
  bound.links = static_cast<std::size_t>(count[0]);
  bound.rhoMax = extremes[1];
  PackingScale scale;
  scale.rhoMin = -extremes[0];
  scale.rhoMax = extremes[1];
  scale.minimumGap = minimumGap;
  if (count[0] == 0 || !(scale.rhoMin > 0.0) || !(total > 0.0)) // decided alike on every rank
  {
    return bound;
  }
  scale.shortLink = (2.0 / 3.0) * total / static_cast<double>(count[0]);
  // Fixed point takes terms below 2^64; a bound of 1e18 pairs limits nothing anyway.
  constexpr double kLargestTerm = 1e18;
  ExactSum sum;
  for (const CapsuleLink& l : links)
  {
    sum.add(std::min(kLargestTerm, packingPartnerBound(l, scale)));
  }
  bound.pairs = 0.5 * sum.total(comm);
  return bound;
}

} // namespace fiberpli
