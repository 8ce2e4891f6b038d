// QuietLinks: the loud flags of a detection (docs/solver.md §3.4).
//
// Why skipping a pair of two quiet links never changes the pair list. The grid reports exactly
// the pairs (a, b) for which P(a, b) = ¬skipSameFiberPair(a, b) ∧ sphere(a, b) ∧ exact(a, b)
// holds (§3.3: the candidate search is complete, the float boxes are rounded outwards). The
// inputs of P are, per link, its points p0, p1, its radius ρ and its computed length
// arc1 − arc0 (the bounding-sphere test), the gap g; for two links of one fiber also their link
// indices k, arc lengths and the closure length (§3.1). In a periodic cell P is that of the
// nearest images, a function of the same inputs and the cell (at most one image can touch,
// §11), whichever ghosts the grid makes.
//
// Link i (fiber f, index k) is quiet when f has as many links as at the last detection, whose
// link (f, k) had bitwise the same p0, p1, ρ and arc1 − arc0 and was in no colliding pair. By
// induction the last detection reported every colliding pair (the first detection, and any
// detection after one whose pairs were not recorded, tests everything). For quiet a, b of
// different fibers, P(a, b) = P(a', b') at the last detection (a', b' their links then), false.
// For one fiber, sphere and exact are unchanged; if the same-fiber rule did not skip (a', b'),
// P(a', b') = sphere ∧ exact was false, so P(a, b) is false. If it skipped (a', b') and does not
// skip (a, b), the arc lengths between them changed (the pair became testable, e.g. the middle
// of a hairpin straightened): both links are made loud. These pairs are found per fiber: the
// rule skips only pairs closer along the fiber than 2·(ρa + ρb) ≤ 2·(ρa + ρmax of the fiber),
// and the arc gap to a later link only grows (prefix sums of non-negative lengths are monotone
// in floating point too), so a walk from each link forward (and through the closure backward)
// until that bound meets every pair the rule skipped before. A radius-scale change changes ρ:
// every link is loud. Loud links are tested against everything, so marking more links loud is
// always safe.

#include "Solver/QuietLinks.h"

#include "Util/Refill.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace fiberpli
{

namespace
{
bool sameBits(double x, double y)
{
  std::uint64_t a = 0, b = 0;
  std::memcpy(&a, &x, sizeof a);
  std::memcpy(&b, &y, sizeof b);
  return a == b;
}

// Everything of a link that the pair predicate reads besides the same-fiber rule's arc lengths.
bool sameCapsule(const CapsuleLink& x, const CapsuleLink& y)
{
  for (int d = 0; d < 3; ++d)
  {
    if (!sameBits(x.p0[d], y.p0[d]) || !sameBits(x.p1[d], y.p1[d]))
      return false;
  }
  return sameBits(x.rho, y.rho) && sameBits(x.arc1 - x.arc0, y.arc1 - y.arc0);
}

constexpr std::size_t kNoMatch = static_cast<std::size_t>(-1);
} // namespace

void QuietLinks::keep(std::vector<CapsuleLink>& links)
{
  havePrev_ = recorded_;
  recorded_ = false;
  if (havePrev_)
  {
    prev_.swap(links); // links is rebuilt next, whatever it holds
  }
}

void QuietLinks::forget()
{
  havePrev_ = recorded_ = false;
}

void QuietLinks::remember(std::size_t links, const std::vector<CapsulePair>& pairs)
{
  refill(prevColliding_, links, char{ 0 });
  for (const CapsulePair& p : pairs)
  {
    prevColliding_[p.a] = 1;
    prevColliding_[p.b] = 1;
  }
  recorded_ = true;
}

const std::vector<char>* QuietLinks::mark(
  const std::vector<CapsuleLink>& links, int threads, const std::vector<std::size_t>* fiberRuns)
{
  const std::size_t n = links.size();
  if (!havePrev_ || prevColliding_.size() != prev_.size())
  {
    loudCount_ = n;
    return nullptr;
  }
  // The runs of one fiber's links (both lists come fiber by fiber, fibers and links ascending).
  const bool given = fiberRuns && !fiberRuns->empty() && fiberRuns->back() == n;
  if (!given)
  {
    runStart_.clear();
    for (std::size_t i = 0; i < n; ++i)
    {
      if (i == 0 || links[i].fiber != links[i - 1].fiber)
        runStart_.push_back(i);
    }
    runStart_.push_back(n);
  }
  const std::vector<std::size_t>& runStart = given ? *fiberRuns : runStart_;
  loud_.resize(n);
  match_.resize(n);
  const auto runs = static_cast<std::int64_t>(runStart.size()) - 1;
  std::int64_t loudTotal = 0;
#pragma omp parallel for num_threads(threads) schedule(dynamic, 64) reduction(+ : loudTotal)
  for (std::int64_t run = 0; run < runs; ++run)
  {
    const std::size_t cb = runStart[static_cast<std::size_t>(run)];
    const std::size_t ce = runStart[static_cast<std::size_t>(run) + 1];
    const std::uint32_t fiber = links[cb].fiber;
    const auto first = std::lower_bound(prev_.begin(), prev_.end(), fiber,
      [](const CapsuleLink& l, std::uint32_t f) { return l.fiber < f; });
    const auto pb = static_cast<std::size_t>(first - prev_.begin());
    // The fiber had as many links at the last detection exactly when its run there ends where
    // this run's length says: two links read instead of a pass over that run (the comparison
    // below reads it anyway when the counts agree).
    const std::size_t pSame = pb + (ce - cb);
    const bool sameCount = pSame <= prev_.size() && prev_[pSame - 1].fiber == fiber &&
      (pSame == prev_.size() || prev_[pSame].fiber != fiber);
    if (sameCount && std::memcmp(&links[cb], &prev_[pb], (ce - cb) * sizeof(CapsuleLink)) == 0)
    {
      // The fiber's links are bitwise those of the last detection, arc lengths and indices
      // included: every same-fiber decision is the same, only the colliding links are loud.
      for (std::size_t i = cb; i < ce; ++i)
      {
        loud_[i] = prevColliding_[pb + (i - cb)];
        loudTotal += loud_[i];
      }
      continue;
    }
    std::size_t pe = pb;
    double rhoMax = 0.0; // of the fiber's links at the last detection
    while (pe < prev_.size() && prev_[pe].fiber == fiber)
      rhoMax = std::max(rhoMax, prev_[pe++].rho);
    // Link (fiber, k) now against link (fiber, k) then: a split or merge shifts the indices
    // behind it, and those links then differ (loud).
    for (std::size_t i = cb, p = pb; i < ce; ++i)
    {
      while (p < pe && prev_[p].k < links[i].k)
        ++p;
      const bool same = p < pe && prev_[p].k == links[i].k;
      match_[i] = same ? p : kNoMatch;
      loud_[i] = !same || prevColliding_[p] || !sameCapsule(links[i], prev_[p]) ? 1 : 0;
    }
    // Pairs of two quiet links of this fiber that the same-fiber rule skipped and skips no more.
    const auto check = [&](std::size_t a, std::size_t b)
    {
      if (!loud_[b] && skipSameFiberPair(prev_[match_[a]], prev_[match_[b]]) &&
        !skipSameFiberPair(links[a], links[b]))
      {
        loud_[a] = loud_[b] = 1;
      }
    };
    for (std::size_t a = cb; a < ce; ++a)
    {
      if (loud_[a])
      {
        continue;
      }
      const CapsuleLink& pa = prev_[match_[a]];
      const double reach = 2.0 * (pa.rho + rhoMax);
      // Links without a match are loud; the walk stops at the first matched link that was out of
      // reach along the fiber (the arc lengths of the matched ones grow with k).
      for (std::size_t b = a + 1; b < ce; ++b)
      {
        if (match_[b] == kNoMatch)
          continue;
        if (prev_[match_[b]].arc0 - pa.arc1 >= reach)
          break;
        check(a, b);
      }
      if (pa.closedLength > 0.0) // the other way round, through the closure
      {
        for (std::size_t b = ce - 1; b > a; --b)
        {
          if (match_[b] == kNoMatch)
            continue;
          if (pa.closedLength - prev_[match_[b]].arc1 + pa.arc0 >= reach)
            break;
          check(a, b);
        }
      }
    }
    for (std::size_t i = cb; i < ce; ++i)
      loudTotal += loud_[i];
  }
  loudCount_ = static_cast<std::size_t>(loudTotal);
  return &loud_;
}

} // namespace fiberpli
