#include "Solver/PushBoost.h"

#include <algorithm>

namespace fiberpli
{

namespace
{
// Colliding pairs per link at the first detection from which pushes grow, and from which they
// get the full PushBoost (docs/solver.md §4.1: the paper's cube has 4–5, q ≈ 6 × the fibers'
// nominal volume fraction).
constexpr double kCrowdedPairsPerLink = 6.0;
constexpr double kFullBoostPairsPerLink = 9.0;
// Largest boosted push of a pair as a fraction of its overlap (per link: the pair's two links
// get at most the whole overlap together).
constexpr double kOverlapShare = 0.5;
} // namespace

double pushScaleFor(std::size_t pairs, std::size_t links, double pushBoost)
{
  if (links == 0)
  {
    return 1.0;
  }
  const double q = static_cast<double>(pairs) / static_cast<double>(links);
  const double ramp = (q - kCrowdedPairsPerLink) / (kFullBoostPairsPerLink - kCrowdedPairsPerLink);
  return 1.0 + (pushBoost - 1.0) * std::min(1.0, std::max(0.0, ramp));
}

double boostedPush(double sigma0, double scale, double overlap)
{
  if (scale <= 1.0)
  {
    return sigma0;
  }
  return std::max(sigma0, std::min(scale * sigma0, kOverlapShare * overlap));
}

} // namespace fiberpli
