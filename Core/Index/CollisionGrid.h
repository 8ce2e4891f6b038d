/// CollisionGrid: broad + narrow phase collision detection of capsule links on a uniform grid
/// (docs/solver.md §3). Memory is linear in the number of links plus the pairs found, and the
/// caller bounds the pairs (maxPairs); the pair list is sorted by (a, b) and therefore identical
/// for any thread count or schedule.
#pragma once

#include "Geometry/Vec3.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fiberpli
{

/// One link of a fiber as the detector sees it (docs/solver.md §1). Its index in the link
/// array is its global link id (fibers in input order, links in fiber order).
struct CapsuleLink
{
  Vec3 p0;
  Vec3 p1;
  double rho = 0.0;        ///< capsule radius max(r_k, r_k+1)
  std::uint32_t fiber = 0; ///< fiber index (same-fiber skip rule)
  std::uint32_t k = 0;     ///< link index inside the fiber
  double arc0 = 0.0;       ///< arc length from the fiber's first point to p0 (S[k])
  double arc1 =
    0.0; ///< arc length to p1 (S[k+1]); arc1 − arc0 = |p1 − p0|, the detector relies on it
  /// > 0: the fiber is closed through a periodic cell and this is its total arc length (its first
  /// and last links are neighbours, arc lengths wrap); 0 = open fiber.
  double closedLength = 0.0;
};

/// A colliding pair, a < b (global link ids), with the closest points of §2 evaluated as
/// closestPoints(link a, link b).
struct CapsulePair
{
  std::uint32_t a = 0;
  std::uint32_t b = 0;
  double s = 0.0;        ///< parameter on a
  double t = 0.0;        ///< parameter on b
  double distance = 0.0; ///< axis distance δ
  Vec3 direction;        ///< unit push direction of a (b moves opposite), §2.4 when δ ≈ 0
};

/// Same-fiber rule of docs/solver.md §3.1 [ours]: true when the pair is never tested
/// (other fiber: false; adjacent links; arc length strictly between them < 2·(ρa + ρb); on a
/// closed fiber the shorter way round counts, so its first and last links are adjacent).
bool skipSameFiberPair(const CapsuleLink& a, const CapsuleLink& b);

/// The packing bound of the colliding pairs among a set of links in any state the solver can
/// separate is Σ_a n_a / 2 over its links a, with n_a = passes_a × linksPerPass_a. A partner fiber
/// that passes link a (radius ρ_a, length ℓ_a) has its axis within R_a = ρ_a + ρ_max + g of a's
/// axis; when fibers keep a gap g, balls of radius b = ρ_min + g/2 around one closest point per
/// pass are disjoint and lie in the capsule of radius R_a + b around a, so passes_a <= V(that
/// capsule) / V(ball b). A pass meets at most (ℓ_a + 2(R_a + b)) / ℓ_short + 2 links, ℓ_short = 2/3
/// of the mean link length (what split/merge keeps links above). The starting states the solver
/// gets are denser than any packing, and the bound leaves room for that: random straight fibers at
/// 4× the paper's density use 13 % of it. Stacks of (nearly) identical fibers exceed it: 1000
/// copies of a 10-point fiber 9×. (A gap much wider than the radii is no packing argument's
/// business: the solver refuses it.) The sum itself is Solver/PairBound.h's packingPairBound
/// (exact, over any split of the links); these are its parts.
struct PackingScale
{
  double rhoMin = 0.0;    ///< smallest capsule radius of all links
  double rhoMax = 0.0;    ///< largest capsule radius of all links
  double shortLink = 0.0; ///< ℓ_short: 2/3 of the mean link length of all links
  double minimumGap = 0.0;
};
/// n_a of link a (Σ_a n_a / 2 is the bound); every n_a >= 54, so the bound is >= 27 × the links.
double packingPartnerBound(const CapsuleLink& a, const PackingScale& scale);

/// Which pairs a rank of the distributed solver tests, given a flag per link (docs/solver.md §13).
enum class TestedPairs
{
  LowerLink, ///< the pairs whose lower link (smaller id) is flagged
  EitherLink ///< the pairs with at least one flagged link
};

/// Uniform grid (§3.3). Reuse one object across solver steps: its buffers are kept.
class CollisionGrid
{
public:
  /// All pairs with δ < ρa + ρb + minimumGap (strict), skip rules of §3.1 applied, sorted by
  /// (a, b). threads: 0 = all cores. Links must have finite coordinates. Stops as soon as more
  /// than maxPairs pairs are found: returns false and leaves `pairs` empty (whether it stops
  /// does not depend on the thread count: it is "the true count exceeds maxPairs").
  /// tested (one entry per link, or null): only the pairs that `rule` picks by these flags are
  /// tested, kept and counted (a rank of the distributed solver finds only the pairs it tests,
  /// docs/solver.md §13); a pair of two unflagged links is not even box-tested, the others are
  /// skipped before the exact test.
  /// loud (one entry per link, or null = all): a pair of two links without the flag is neither
  /// box- nor exact-tested (the caller knows it does not collide: Solver/QuietLinks.h), and a
  /// pair of cells holding no flagged link is not visited; applied on top of `tested`.
  bool findPairs(const std::vector<CapsuleLink>& links, double minimumGap, int threads,
    std::vector<CapsulePair>& pairs, std::size_t maxPairs = static_cast<std::size_t>(-1),
    const std::vector<char>* tested = nullptr, TestedPairs rule = TestedPairs::LowerLink,
    const std::vector<char>* loud = nullptr);

  /// The work of the last findPairs (broad-phase box tests + kExactTestWork × exact segment
  /// tests; the same for any thread count): what the distributed solver balances its ranks by.
  std::uint64_t work() const { return work_; }
  /// An exact test costs about as much as this many box tests (1000-fiber cube profile).
  static constexpr std::uint64_t kExactTestWork = 10;

  /// Bytes the grid keeps per link (its buffers), for memory estimates.
  static double bytesPerLink();
  /// Bytes one found pair takes while findPairs runs and in its result.
  static double bytesPerPair();

private:
  struct Box
  {
    Vec3 lo;
    Vec3 hi;
  };
  /// Where the grid lies and how it is cut (phases 1 and 2).
  struct Layout
  {
    Vec3 origin;                     ///< lower corner of all boxes
    Vec3 top;                        ///< upper corner of all boxes
    double h[3] = { 0.0, 0.0, 0.0 }; ///< cell edge along each axis (boundLinks: largest box edge)
    std::int64_t nx = 0, ny = 0, nz = 0;
    double limit = 0.0;        ///< a box edge above this makes a link oversize
    std::size_t nOversize = 0; ///< 0: no link is oversize (limit is then not used)
  };
  // The phases of findPairs, in order; each fills the buffers below that the next one reads.
  Layout boundLinks(const std::vector<CapsuleLink>& links, double halfGap, int nThreads);
  Layout chooseCells(std::size_t n, const Layout& bounds) const;
  void collectOversize(const Layout& grid);
  void sortByCell(const Layout& grid, int nThreads);
  void countByCell(const Layout& grid, std::size_t nCells, int nThreads);
  void sortKeysByCell(const Layout& grid, int nThreads);
  static std::uint32_t cellOf(const Box& bx, const Layout& grid);
  static void reachedCells(
    const Box& bx, const Layout& grid, std::int64_t c0[3], std::int64_t c1[3]);
  static void cellCoordinates(
    std::uint64_t cell, const Layout& grid, std::int64_t& cx, std::int64_t& cy, std::int64_t& cz);
  void flaggedFirst(const char* head);
  void buildCellArrays(const std::vector<CapsuleLink>& links, const char* tested, const char* loud,
    const Layout& grid, int nThreads);
  // The rows of only the visited cells and their neighbours are filled when fewer than one cell
  // in this many is visited.
  static constexpr std::size_t kFillAllBelow = 8;
  bool collectPairs(const std::vector<CapsuleLink>& links, const char* tested, TestedPairs rule,
    const char* loud, double minimumGap, const Layout& grid, int nThreads, std::size_t maxPairs);
  void mergePairs(std::size_t nLinks, int nThreads, std::vector<CapsulePair>& pairs);

  std::vector<Box> boxes_; // per link, grown by rho + gap/2
  std::vector<std::uint32_t>
    order_; // regular link ids sorted by (cell, flagged first, id); flagged: loud, else tested
  std::vector<std::uint32_t> scratch_; // flaggedFirst's reordering
  // Dense grids: per link its cell, per chunk of links and cell a counter (counting sort).
  std::vector<std::uint32_t> cellOf_;
  std::vector<std::uint32_t> count_;
  std::vector<std::uint32_t> rowOfCell_; // per cell (+ end), its first row in order_; dense only
  // Sparse grids: (linear cell index << 32) | link id of the regular links, and last call's
  // order (a nearly sorted start for this call).
  std::vector<std::uint64_t> sortKeys_;
  std::vector<std::uint32_t> prevOrder_;
  std::vector<double> edges_; // per link largest box edge
  // Boxes in 'order_' order as float SoA, rounded outwards: contiguous per cell so the broad
  // phase runs branch-free over plain arrays; rounding only adds candidates, never loses one.
  std::vector<float> lo_[3];
  std::vector<float> hi_[3];
  std::vector<CapsuleLink>
    sorted_; // the regular links in 'order_' order (the exact tests read them)
  std::vector<char> sortedTested_;       // the tested flags in 'order_' order
  std::vector<char> sortedLoud_;         // the loud flags in 'order_' order
  std::vector<std::uint64_t> cellKeys_;  // occupied cells, ascending
  std::vector<std::uint32_t> cellStart_; // cellKeys_.size() + 1 offsets into order_
  std::vector<std::uint32_t>
    cellUnflagged_;                     // per occupied cell, the offset of its first unflagged link
  std::vector<std::uint32_t> visit_;    // the occupied cells holding a flagged link, ascending
  std::vector<char> need_;              // per occupied cell: its rows are read (buildCellArrays)
  std::vector<std::uint32_t> fill_;     // the cells whose rows are filled, ascending
  std::vector<std::uint32_t> oversize_; // links queried against all links
  std::vector<std::vector<CapsulePair>> perThread_;
  std::vector<std::size_t> pairEnd_; // per link, the end of the merged pairs with a <= it
  std::uint64_t work_ = 0;
};

} // namespace fiberpli
