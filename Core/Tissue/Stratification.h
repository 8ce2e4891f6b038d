/// Stratification: transverse positions that spread a population's fibers evenly over the
/// cross-section of a cell (docs/tissue-models.md §10, "Arrangement"). Uniform random positions
/// leave clumps and holes: in a (40 µm)³ cell with three populations of ~60 fibers some sub-cube of
/// edge L/3 held only 8 % of one population's fiber volume instead of a third. Jittered strata keep
/// the positions random inside small cells while every block of edge L/3 gets its share of the
/// fibers and, since radii differ by a factor of several, of their volume.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fiberpli
{

/// Strata per side of the cross-section for a population of `fibers` fibers: a multiple of 3 (the
/// 3 × 3 blocks of edge L/3 then hold whole strata), 3·max(1, floor(√(fibers / 9))), so that there
/// are at most as many strata as fibers (beyond the first 3 × 3).
int strataPerSide(std::size_t fibers);

/// The stratum (0 .. perSide² − 1, row-major: cell (stratum mod perSide, stratum / perSide)) of
/// each fiber, given the fibers' weights (their volumes). The fibers go to the nine blocks of
/// perSide/3 × perSide/3 strata from the heaviest down, nine at a time, one to each block in an
/// order drawn afresh for every nine, so each block gets one fiber of each weight class: its fiber
/// count is within one of every other block's and its weight close to a ninth of the total. Inside
/// a block the fibers fill its strata in rounds, each round a random order of all of them (every
/// stratum of a block holds ⌊c/s⌋ or ⌈c/s⌉ of its c fibers). Deterministic for (seed, key): the
/// draws come from the streams (seed, key, i). Empty for perSide < 3 or not a multiple of 3.
std::vector<int> assignStrata(
  const std::vector<double>& weights, int perSide, std::uint64_t seed, std::uint64_t key);

/// A coordinate in [−L/2, L/2) placed in cell `cell` (0 .. perSide − 1) of an edge of length L cut
/// into perSide cells: −L/2 + (cell + u)·L / perSide, where u = (coordinate + L/2) / L keeps the
/// drawn position's randomness inside the cell.
double intoStratum(double coordinate, int cell, int perSide, double edgeLength);

} // namespace fiberpli
