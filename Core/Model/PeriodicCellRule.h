/// PeriodicCellRule: the one rule for which periodic cells FiberPLI accepts (docs/data-contract.md
/// §2, field `periodic_cell`). Every place that takes a cell from outside — the field data of
/// the reader, writer, solver, PLISimulation, ground truth and metrics, the .h5 attribute, the
/// Core solver options — checks it with these functions, so all of them accept and refuse the
/// same cells with the same words.
#pragma once

#include "Geometry/PeriodicCell.h"

#include <cstddef>
#include <string>
#include <vector>

namespace fiberpli
{

/// Largest edge of a periodic cell (µm): a metre. Larger edges are typing errors or overflows
/// (the edge of [-1e308, 1e308] is inf), and the lattice arithmetic (wrapping, tiling, the pair
/// grid) needs edges it can divide and multiply without overflowing.
constexpr double kMaxPeriodicEdge = 1e9;

/// Smallest edge relative to the magnitude of the cell's bounds: the bounds of a smaller cell
/// differ by fewer than about 4.5e6 steps of double precision, too coarse to wrap points into it.
constexpr double kMinPeriodicEdgeRatio = 1e-9;

/// "" when the cell is usable: every bound finite, max > min, every edge finite and
/// <= kMaxPeriodicEdge and >= kMinPeriodicEdgeRatio × the largest |bound| of its axis. Else a
/// message starting with "periodic_cell" naming the axis and the values (short number form).
std::string validatePeriodicCell(const PeriodicCell& cell);

/// The cell from the six values of the `periodic_cell` field (xmin xmax ymin ymax zmin zmax):
/// "" and `cell` filled when validatePeriodicCell accepts it, else why not (count or the rule).
std::string periodicCellFromBounds(const double* b, std::size_t count, PeriodicCell& cell);

/// The field `periodic_cell` of one rank's piece in a parallel update.
struct RankCell
{
  bool present = false;       ///< the piece carries the field
  std::size_t count = 0;      ///< its number of values
  std::vector<double> values; ///< its values when count is 6 (a malformed count needs none)
};

/// The one rule for `periodic_cell` across the ranks of a parallel update, the same for every
/// filter that reads it there: every piece that carries the field must carry a usable cell
/// (Model/PeriodicCellRule.h) and all of them the same one (pieces without fibers may lack it).
/// "" when so, else a message naming the first rank that breaks the rule; computed from the
/// same gathered values on every rank, it is the same on every rank.
std::string compareRankCells(const std::vector<RankCell>& ranks);

} // namespace fiberpli
