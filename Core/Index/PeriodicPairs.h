/// PeriodicPairs: collision detection in a periodic cell by the minimum-image convention. Every
/// link is wrapped into the cell (by the lattice vector that brings its centre inside), links near
/// a face get ghost copies shifted by one period, and the ordinary CollisionGrid runs on the union;
/// each physical pair is then kept exactly once, as (smaller real id, larger real id). The pair's
/// closest points and push direction are those of the nearest images, so the solver needs no other
/// change. The cell must exceed twice the largest link reach (box edge) on every axis, so that at
/// most one image of a link can touch another link.
#pragma once

#include "Geometry/PeriodicCell.h"
#include "Index/CollisionGrid.h"

#include <string>
#include <vector>

namespace fiberpli
{

class PeriodicPairs
{
public:
  /// Same contract as CollisionGrid::findPairs (pairs sorted by (a, b), identical for any thread
  /// count) with distances by minimum image. Returns an error (pairs empty) when the cell is too
  /// small for the links. More than maxPairs pairs: *overflow (if given) is set, pairs empty.
  /// tested: CollisionGrid::findPairs' `tested` with TestedPairs::LowerLink (per real link; a
  /// pair's lower link is its smaller real id). loud: CollisionGrid::findPairs' `loud` per real
  /// link (a ghost is as loud as its link).
  std::string findPairs(const std::vector<CapsuleLink>& links, const PeriodicCell& cell,
    double minimumGap, int threads, std::vector<CapsulePair>& pairs,
    std::size_t maxPairs = static_cast<std::size_t>(-1), bool* overflow = nullptr,
    const std::vector<char>* tested = nullptr, const std::vector<char>* loud = nullptr);

  /// The work of the last findPairs (CollisionGrid::work of its grid over the images; 0 when it
  /// returned before searching).
  std::uint64_t work() const { return work_; }

  /// The error findPairs gives when the cell is too small for the links at this gap, or "" (the
  /// reach grows with the gap: too small at a gap means too small at every larger one).
  static std::string cellTooSmall(
    const std::vector<CapsuleLink>& links, const PeriodicCell& cell, double minimumGap);

private:
  static double reach(const std::vector<CapsuleLink>& links, double minimumGap);
  static std::string cellTooSmall(double w, const PeriodicCell& cell);

  CollisionGrid grid_;
  std::uint64_t work_ = 0;
  std::vector<CapsuleLink> images_;     // wrapped real links (ids 0..n-1), then the ghosts
  std::vector<std::size_t> ghostStart_; // per real link, where its ghosts start in images_
  std::vector<std::uint32_t> source_;   // real id of every ghost
  std::vector<char> imageTested_; // the grid's tested: the real links' (1 serially), 0 for ghosts
  std::vector<char> imageLoud_;   // the grid's loud: every image's link's
  std::vector<CapsulePair> raw_;
};

} // namespace fiberpli
