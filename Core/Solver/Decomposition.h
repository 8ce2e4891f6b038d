/// Decomposition: how the distributed collision solver splits the fibers over its ranks
/// (docs/solver.md §13). Whole fibers are owned by the rank whose slab (one axis, fixed for the
/// run, the one with room for the most fiber-and-halo widths) holds the fiber's reference point,
/// the middle of its extent along that axis (in a periodic cell wrapped into the cell). Every rank
/// keeps its owned fibers, in global fiber order; fibers travel between ranks as byte records
/// through Comm::exchange. The pair work goes by region (links, not fibers:
/// Solver/LinkExchange.h).
#pragma once

#include "Geometry/PeriodicCell.h"
#include "Model/FiberModel.h"
#include "Parallel/Comm.h"
#include "Solver/SolverState.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fiberpli
{

/// The fibers a rank owns (model) and what the solver keeps per fiber (state: parallel vectors,
/// global order).
struct RankFibers
{
  FiberModel& model;
  CollisionSolverState& state;
  std::size_t size() const { return model.fibers.size(); }
};

/// Slabs along one axis: of the periodic cell, else of the bounds of every rank's points.
class SlabLayout
{
public:
  /// Collective: slabs along the axis with room for the most whole slabs that each own fibers
  /// and are wider than a fiber and its halo, floor(room_a / (e_a + 2·reach)) (room_a: the cell's
  /// edge, or else the width over which the fibers' middles spread; e_a: all ranks' mean fiber
  /// extent along a; reach: 2·ρmax), equal counts to the axis of least summed fiber extent, then
  /// the lower axis; cutting the cell, or else the global bounds of all points. In an equal-sided
  /// cell, the axis of the shortest fibers.
  static SlabLayout make(const FiberModel& local, const PeriodicCell& cell, Comm& comm);
  /// Rank that owns the fiber (0 for a fiber without points).
  int owner(const Fiber& f) const;
  /// Slab (rank) holding coordinate x along the axis (in a periodic cell after wrapping x into it).
  int slabOf(double x) const;
  /// Rank testing the pairs of a link whose centre is at x along the axis (Solver/LinkExchange.h):
  /// slabs cut so that each holds as many link centres of the start model as the others (the pair
  /// search is ~90 % of a step; equal widths left one of two ranks of the 1000-fiber cube with 54 %
  /// of it), then re-cut during the run at equal measured work (balanceTesterSlabs). Ownership
  /// (owner, slabOf) keeps equal widths: it decides only shape control and moves.
  int testerOf(double x) const;
  /// Collective: re-cuts the tester slabs at equal pair work. work: this rank's pair-search work
  /// since the last cut (CollisionGrid::work). A slab's current links each weigh its work per link
  /// (a histogram of all ranks' link centres), so the slabs of costly links get narrower. Who
  /// tests a pair never changes a result, only the balance; the cuts stay when a slab with links
  /// reported no work.
  void balanceTesterSlabs(const FiberModel& local, std::int64_t work, Comm& comm);
  /// Lower bound along the axis of tester slab q (q = R: the upper bound of the last one).
  double testerLo(int q) const;
  /// What wrapping x into the cell adds to it along the axis (PeriodicCell::wrapShift; 0 without a
  /// cell).
  double wrapShift(double x) const;
  int axis() const { return axis_; }
  /// The cell's edge along the axis (0 without a cell).
  double period() const { return periodic_ ? hi_ - lo_ : 0.0; }

private:
  int axis_ = 0;
  double lo_ = 0.0, hi_ = 0.0;
  int ranks_ = 1;
  bool periodic_ = false;
  PeriodicCell cell_; // wrapShift: the cell's own rule along axis_
  std::vector<double>
    testCuts_; // the R − 1 inner cuts of the tester slabs, as fractions of [lo, hi]
  double fraction(double x) const; // x as a fraction of [lo, hi], wrapped into [0, 1) in a cell
  // Collective: the tester cuts from all ranks' link centres, each link weighing 1 (work < 0 on
  // every rank) or its slab's measured work per link (every rank passes its work >= 0).
  void cutTesterSlabs(const FiberModel& local, Comm& comm, std::int64_t work);
};

/// What a redistribution moved (this rank's share).
struct TrafficCount
{
  std::size_t fibers = 0; ///< fibers sent to other ranks
  std::size_t bytes = 0;  ///< bytes sent to other ranks
};

/// Sends every fiber whose destination (dest(index), a rank) is another rank there, receives the
/// fibers others send here, keeps global order. Collective.
TrafficCount redistribute(RankFibers& fibers, const std::vector<int>& dest, Comm& comm);

} // namespace fiberpli
