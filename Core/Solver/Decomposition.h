/// Decomposition: how the distributed collision solver splits the fibers over its ranks
/// (docs/solver.md §13). The domain is cut into a 3-D grid of boxes, one per rank (BoxLayout, the
/// grid fixed for the run). Whole fibers are owned by the rank whose owner box holds the fiber's
/// reference point, the middle of its extent (in a periodic cell wrapped into the cell). Every
/// rank keeps its owned fibers, in global fiber order; fibers travel between ranks as byte records
/// through Comm::exchange. The pair work goes by tester box (links, not fibers:
/// Solver/LinkExchange.h).
#pragma once

#include "Geometry/PeriodicCell.h"
#include "Model/FiberModel.h"
#include "Parallel/Comm.h"
#include "Solver/SolverState.h"

#include <algorithm>
#include <cmath>
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

/// An axis-aligned box; open models give the outermost boxes infinite outer faces (a point beyond
/// the start bounds belongs to them).
struct LayoutBox
{
  Vec3 lo, hi;
};

/// The boxes of a distributed solve: the periodic cell, else the bounds of every rank's points at
/// the start, cut into nx × ny × nz boxes, box (i, j, k) being rank (i·ny + j)·nz + k. Two cuts
/// of the same grid: *owner boxes* of equal widths (a fiber belongs to the box holding the middle
/// of its extent, wrapped into the cell) and *tester boxes*, cut along each axis so that each
/// layer holds the same number of link centres, later the same pair work (a link's pairs are
/// tested by the tester box holding its centre, Solver/LinkExchange.h).
class BoxLayout
{
public:
  /// Collective: the factorisation nx·ny·nz = R of least held volume per rank, Π_d (w_d + 2·h_d)
  /// (w_d: the room along d over n_d, the room being the cell's edge or the spread of the link
  /// centres; h_d: the halo, the mean link extent along d + 2·ρmax), among those that cut no axis
  /// into boxes thinner than their halo nor an axis the model does not span (if none does, the
  /// least volume of those that cut spanned axes only); equal volumes to the more cuts along
  /// the lower axis. From exact sums and maxima: every rank picks the same grid.
  static BoxLayout make(const FiberModel& local, const PeriodicCell& cell, Comm& comm);
  /// Boxes along axis d.
  int boxes(int d) const { return n_[d]; }
  /// Rank of box (i, j, k).
  int rankOf(int i, int j, int k) const { return (i * n_[1] + j) * n_[2] + k; }
  /// The box indices of rank r.
  void indicesOf(int r, int idx[3]) const;
  /// Rank that owns the fiber: the owner box of the middle of its extent along each axis
  /// (0 for a fiber without points).
  int owner(const Fiber& f) const;
  /// Middle of a fiber's extent along each axis (the point its owner box holds).
  static Vec3 middle(const Fiber& f);
  /// The middle of an extent [lo, hi] (middle() of a fiber whose points span it).
  static Vec3 middleOf(const Vec3& lo, const Vec3& hi) { return 0.5 * (lo + hi); }
  /// Owner box (rank) of point x (in a periodic cell after wrapping x into it).
  int ownerOf(const Vec3& x) const
  {
    return rankOf(layerOf(0, x[0], true), layerOf(1, x[1], true), layerOf(2, x[2], true));
  }
  /// Tester box (rank) of point x (in a periodic cell after wrapping x into it).
  int testerOf(const Vec3& x) const
  {
    return rankOf(layerOf(0, x[0]), layerOf(1, x[1]), layerOf(2, x[2]));
  }
  /// Index along axis d of the tester (owner: owners = true) layer holding coordinate x. Inline:
  /// the link exchange asks it for most links of every step.
  int layerOf(int d, double x, bool owners = false) const
  {
    if (n_[d] == 1 || !(hi_[d] > lo_[d]))
    {
      return 0;
    }
    const double t = fraction(d, x);
    if (owners)
    {
      const double layer = std::floor(t * n_[d]);
      return layer < 0.0 ? 0 : layer >= n_[d] ? n_[d] - 1 : static_cast<int>(layer);
    }
    return static_cast<int>(
      std::upper_bound(cuts_[d].begin(), cuts_[d].end(), t) - cuts_[d].begin());
  }
  /// Lower bound along d of tester (owner) layer i (i = boxes(d): the upper bound of the last).
  double cut(int d, int i, bool owners = false) const;
  /// Tester (owner) box of rank r; open models: the outermost faces are infinite.
  LayoutBox box(int r, bool owners = false) const;
  /// Collective: re-cuts the tester layers at equal pair work. work: this rank's (its tester
  /// box's) pair-search work since the last cut (CollisionGrid::work). A box's current links each
  /// weigh its work per link (histograms of all ranks' link centres along each axis), so layers
  /// of costly links get thinner. Who tests a pair never changes a result, only the balance; the
  /// cuts stay when a box with links reported no work.
  void balanceTesterBoxes(const FiberModel& local, std::int64_t work, Comm& comm);
  /// Largest move of a tester cut since `before`, as a fraction of its axis' span.
  double largestCutMove(const BoxLayout& before) const;
  /// What wrapping x into the cell adds to it (PeriodicCell::wrapShift; 0 without a cell).
  Vec3 wrapShift(const Vec3& x) const { return periodic_ ? cell_.wrapShift(x) : Vec3{}; }
  bool periodic() const { return periodic_; }
  /// The cell's edge along d (0 without a cell).
  double period(int d) const { return periodic_ ? hi_[d] - lo_[d] : 0.0; }
  /// The domain's extent along d.
  double span(int d) const { return hi_[d] - lo_[d]; }

private:
  int n_[3] = { 1, 1, 1 };
  Vec3 lo_, hi_;
  int ranks_ = 1;
  bool periodic_ = false;
  PeriodicCell cell_; // wrapShift: the cell's own rule
  // Per axis the n_d − 1 inner cuts of the tester layers, as fractions of [lo, hi].
  std::vector<double> cuts_[3];
  // x as a fraction of [lo, hi] along d, wrapped into [0, 1) in a cell.
  double fraction(int d, double x) const
  {
    const double t = (x - lo_[d]) / (hi_[d] - lo_[d]);
    return periodic_ ? t - std::floor(t) : t;
  }
  // Collective: the tester cuts from all ranks' link centres, each link weighing 1 (work < 0 on
  // every rank) or its box's measured work per link (every rank passes its work >= 0).
  void cutTesterBoxes(const FiberModel& local, Comm& comm, std::int64_t work);
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
