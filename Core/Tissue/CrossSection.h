/// CrossSection: the fibers of one bundle cross-section before they are laid along a trajectory
/// (docs/tissue-models.md §1, §5.3, §7): seed offset, radius, Ranvier phase and the fiber's own
/// random stream, positioned for the displacement draws.
#pragma once

#include "Tissue/BundleOptions.h"
#include "Tissue/Seeds.h"
#include "Util/Random.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fiberpli
{

struct CrossSectionFiber
{
  Seed2D seed;                    ///< offset in the cross-section plane, µm
  double radius = 0.0;            ///< r_j, clamped to <= BundleRadius
  double phase = 0.0;             ///< Ranvier phase φ_j in [0, Λ) (0 when Λ = 0)
  std::size_t key = 0;            ///< seed index: grid index before cropping, or random-seed index
  RandomStream rng;               ///< stream (Seed, crossSection, key) after the phase draw
  std::uint64_t crossSection = 0; ///< the cross-section index (the shape streams' group)
};

/// Fibers of cross-section `crossSection` (docs/tissue-models.md §7: one stream per fiber,
/// RandomStream(options.seed, crossSection, key), draw order position (2) → radius → Ranvier phase;
/// the displacements follow in the returned stream).
/// Grid (numberOfFibers = 0): the centred triangular grid (§1.1) over |x|, |y| <= R + d, key = its
/// index in that sorted grid; the two position numbers are drawn and unused so the order is the
/// same in both modes; a seed is kept when its disc of radius r_j lies inside R (§1.2). Random
/// (numberOfFibers = N > 0): key = 0..N−1, s = (R − r_j)·√u1·(cos 2πu2, sin 2πu2) (§1.3). A fiber's
/// draws depend only on (Seed, crossSection, key), never on other fibers or the order.
/// Precondition: validateBundleOptions(options) is empty.
std::vector<CrossSectionFiber> makeCrossSection(
  const BundleOptions& options, std::uint64_t crossSection);

} // namespace fiberpli
