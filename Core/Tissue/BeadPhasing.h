/// BeadPhasing: beads of neighbouring fibers placed out of phase (docs/tissue-models.md §10.3).
/// Beaded fibers packed side by side at their mean radii overlap wherever two beads meet; a
/// closed fiber's radius profile may start at any of its points, so each fiber's profile is turned
/// (a cyclic shift by whole points) to where its beads meet its neighbours' least.
#pragma once

#include "Tissue/Seeds.h"

#include <cstddef>
#include <vector>

namespace fiberpli
{

/// radii[j]: the point radii of closed fiber j over one period (the repeated last point left
/// out); centres[j]: its position across the axis in a periodic square of edge `period`. In order
/// j = 0, 1, …, fiber j takes the shift s (its point p gets radii[j][(p + s) mod m]) that minimises
/// Σ_i Σ_p max(0, ρ_j(p) + ρ_i(p) − d_ij)² over the fibers i < j of the same point count m whose
/// centres are d_ij < max ρ_j + max ρ_i apart (minimum image), ρ_i with its own chosen shift;
/// ties to the smallest s, so a fiber without such neighbours keeps s = 0. Returns the shifts.
std::vector<std::size_t> beadPhases(
  const std::vector<std::vector<double>>& radii, const std::vector<Seed2D>& centres, double period);

} // namespace fiberpli
