/// QuietLinks: which links a detection of the collision solver must test (docs/solver.md §3.4).
/// A link is *quiet* when nothing that decides whether one of its pairs collides has changed since
/// the last detection and it was in no colliding pair then; a pair of two quiet links cannot
/// collide now, so the grid skips it. The other links are *loud*. Skipping never changes the pair
/// list: the proof is in QuietLinks.cxx and docs/solver.md §3.4.
#pragma once

#include "Index/CollisionGrid.h"

#include <cstddef>
#include <vector>

namespace fiberpli
{

class QuietLinks
{
public:
  /// Before a detection whose links are about to be rebuilt into `links`: keeps the last
  /// detection's links (swapped out of `links`, no copy) when their colliding pairs were recorded
  /// (remember()); otherwise everything will be loud.
  void keep(std::vector<CapsuleLink>& links);
  /// The loud flag of every link of `links` (1 = test its pairs), null when every link is loud
  /// (no usable last detection). Call once per detection, after keep() and the rebuild.
  /// fiberRuns (optional): the first link of each fiber's links in `links` (+ the total), as the
  /// builder of the links knows them; without it they are found by a pass over the links.
  const std::vector<char>* mark(const std::vector<CapsuleLink>& links, int threads,
    const std::vector<std::size_t>* fiberRuns = nullptr);
  /// After mark() returned flags: makes loud every quiet link i for which alsoLoud(i) holds (the
  /// distributed solver's links whose tester box moved, docs/solver.md §13). Loud links stay loud.
  template <class AlsoLoud>
  void makeLoud(AlsoLoud alsoLoud)
  {
    for (std::size_t i = 0; i < loud_.size(); ++i)
    {
      if (!loud_[i] && alsoLoud(i))
      {
        loud_[i] = 1;
        ++loudCount_;
      }
    }
  }
  /// After a detection that found every colliding pair among `links`: which links collided, for
  /// the next detection. Without it (a failed detection, a partial search) the next one is loud.
  void remember(std::size_t links, const std::vector<CapsulePair>& pairs);
  /// The next detection tests everything.
  void forget();

  /// Loud links of the last mark() (all links when it returned null).
  std::size_t loudLinks() const { return loudCount_; }

private:
  std::vector<CapsuleLink> prev_;   // the last detection's links
  std::vector<char> prevColliding_; // per link of prev_: in a colliding pair
  bool havePrev_ = false;           // prev_ and prevColliding_ describe the last detection
  bool recorded_ = false;           // remember() followed the last mark()
  std::vector<char> loud_;
  std::vector<std::size_t> runStart_; // mark() without the builder's runs: each fiber's first link
                                      // in the links (+ end)
  std::vector<std::size_t> match_;    // per link, the same (fiber, k) in prev_, or none
  std::size_t loudCount_ = 0;
};

} // namespace fiberpli
