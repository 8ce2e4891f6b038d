#include "Index/CollisionGrid.h"

#include "Geometry/SegmentDistance.h"
#include "Util/Refill.h"
#include "Util/Threads.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>

namespace fiberpli
{

bool skipSameFiberPair(const CapsuleLink& a, const CapsuleLink& b)
{
  if (a.fiber != b.fiber)
  {
    return false;
  }
  const CapsuleLink& first = a.k < b.k ? a : b;
  const CapsuleLink& second = a.k < b.k ? b : a;
  if (second.k - first.k <= 1)
  {
    return true;
  }
  // Arc length instead of fastPLI's |Δk|·mean length: a fold-back (u ≈ −v) is still detected.
  double gap = second.arc0 - first.arc1;
  if (a.closedLength > 0.0)
  {
    gap = std::min(gap, a.closedLength - second.arc1 + first.arc0); // the way through the closure
  }
  return gap < 2.0 * (a.rho + b.rho);
}

namespace
{

// float rounding moves a value by at most 2^-24 relative; widen by 2^-22 relative (plus a tiny
// absolute amount for values near 0) so the float box always contains the double box.
inline float floatBelow(double x)
{
  const float f = static_cast<float>(x);
  return f - (std::fabs(f) * 2.4e-7f + 1e-30f);
}

inline float floatAbove(double x)
{
  const float f = static_cast<float>(x);
  return f + (std::fabs(f) * 2.4e-7f + 1e-30f);
}

inline bool boxesOverlap(const Vec3& alo, const Vec3& ahi, const Vec3& blo, const Vec3& bhi)
{
  return ahi.x > blo.x && bhi.x > alo.x && ahi.y > blo.y && bhi.y > alo.y && ahi.z > blo.z &&
    bhi.z > alo.z;
}

// Narrow phase on an AABB-overlapping candidate: links la, lb with ids a < b, always evaluated
// in that order so the result does not depend on which cell found the pair.
inline void testOrderedPair(const CapsuleLink& la, const CapsuleLink& lb, std::uint32_t a,
  std::uint32_t b, double gap, std::vector<CapsulePair>& out, std::uint64_t& exactTests)
{
  if (la.fiber == lb.fiber && skipSameFiberPair(la, lb))
  {
    return;
  }
  // Bounding spheres around the link centres: a cheap reject before the exact distance (every
  // point of a segment lies within half its length of its centre).
  const Vec3 dc = (la.p0 + la.p1) - (lb.p0 + lb.p1); // twice the centre distance
  const double reach = (la.arc1 - la.arc0) + (lb.arc1 - lb.arc0) + 2.0 * (la.rho + lb.rho + gap);
  if (norm2(dc) >= reach * reach)
  {
    return;
  }
  ++exactTests;
  const SegmentClosest c = closestPoints(la.p0, la.p1, lb.p0, lb.p1);
  if (c.distance < la.rho + lb.rho + gap)
  {
    CapsulePair p;
    p.a = a;
    p.b = b;
    p.s = c.s;
    p.t = c.t;
    p.distance = c.distance;
    p.direction = separationDirection(c, la.p1 - la.p0, lb.p1 - lb.p0);
    out.push_back(p);
  }
}

// The same for links i, j of `links` in either order; tested, rule, loud: see findPairs.
inline void testPair(const std::vector<CapsuleLink>& links, const char* tested, TestedPairs rule,
  const char* loud, std::uint32_t i, std::uint32_t j, double gap, std::vector<CapsulePair>& out,
  std::uint64_t& exactTests)
{
  const std::uint32_t a = i < j ? i : j;
  const std::uint32_t b = i < j ? j : i;
  if (tested && !tested[a] && (rule == TestedPairs::LowerLink || !tested[b]))
  {
    return;
  }
  if (loud && !loud[a] && !loud[b])
  {
    return;
  }
  testOrderedPair(links[a], links[b], a, b, gap, out, exactTests);
}
} // namespace

double packingPartnerBound(const CapsuleLink& a, const PackingScale& scale)
{
  const double g = scale.minimumGap;
  const double b = scale.rhoMin + 0.5 * g;
  const double c = a.rho + scale.rhoMax + g + b;
  const double len = a.arc1 - a.arc0;
  // passes: V(capsule of radius c and length len) / V(ball b) = (0.75·c²·len + c³) / b³
  const double passes = (0.75 * c * c * len + c * c * c) / (b * b * b);
  const double linksPerPass = (len + 2.0 * c) / scale.shortLink + 2.0;
  return passes * linksPerPass;
}

double CollisionGrid::bytesPerLink()
{
  // boxes_, edges_, order_ and its reordering by flags, the six float bound arrays, the sorted
  // copy of the link and its tested and loud flags, 3 words for the sort: the keys (2) and last
  // order of a sparse grid, or the cells and counters (at most 2 per link) of a dense one, and the
  // end of its pairs (mergePairs); per occupied cell (at most one per link) the cells to visit
  // and to fill and the fill mark; the first row of every cell of a dense grid (at most 2 per
  // link).
  return static_cast<double>(sizeof(Box) + sizeof(double) + sizeof(std::uint64_t) +
    7 * sizeof(std::uint32_t) + 6 * sizeof(float) + sizeof(CapsuleLink) + 3 * sizeof(char) +
    sizeof(std::size_t));
}

double CollisionGrid::bytesPerPair()
{
  return static_cast<double>(2 * sizeof(CapsulePair)); // per-thread lists, then the merged one
}

bool CollisionGrid::findPairs(const std::vector<CapsuleLink>& links, double minimumGap, int threads,
  std::vector<CapsulePair>& pairs, std::size_t maxPairs, const std::vector<char>* tested,
  TestedPairs rule, const std::vector<char>* loud)
{
  pairs.clear();
  work_ = 0;
  if (links.size() < 2)
  {
    return true;
  }
  const int nThreads = resolveThreadCount(threads);
  const Layout grid = chooseCells(links.size(), boundLinks(links, 0.5 * minimumGap, nThreads));
  collectOversize(grid);
  sortByCell(grid, nThreads);
  const char* flags = tested ? tested->data() : nullptr;
  const char* loudFlags = loud ? loud->data() : nullptr;
  // A pair to test has a loud link (if loud is given) and a tested one: the cells put the loud
  // links first when there are loud flags (the tested rule is then checked per candidate).
  flaggedFirst(loudFlags ? loudFlags : flags);
  buildCellArrays(links, flags, loudFlags, grid, nThreads);
  if (!collectPairs(links, flags, rule, loudFlags, minimumGap, grid, nThreads, maxPairs))
  {
    return false;
  }
  mergePairs(links.size(), nThreads, pairs);
  return true;
}

// Phase 1: every link's box, grown by rho + gap/2, its largest edge, and the bounds of all boxes.
CollisionGrid::Layout CollisionGrid::boundLinks(
  const std::vector<CapsuleLink>& links, double halfGap, int nThreads)
{
  const std::size_t n = links.size();
  boxes_.resize(n);
  edges_.resize(n);
  double ox = HUGE_VAL, oy = HUGE_VAL, oz = HUGE_VAL;
  double tx = -HUGE_VAL, ty = -HUGE_VAL, tz = -HUGE_VAL;
  double ex = 0.0, ey = 0.0, ez = 0.0; // the largest box edge along each axis
  const std::int64_t nn = static_cast<std::int64_t>(n);
  // min/max are exact, so the reduction gives the same bits for any thread count.
#pragma omp parallel for num_threads(nThreads) schedule(static) reduction(min                      \
                                                                          : ox, oy, oz)            \
  reduction(max                                                                                    \
            : tx, ty, tz, ex, ey, ez)
  for (std::int64_t ii = 0; ii < nn; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const CapsuleLink& l = links[i];
    const double g = l.rho + halfGap;
    Box& bx = boxes_[i];
    for (int d = 0; d < 3; ++d)
    {
      bx.lo[d] = std::min(l.p0[d], l.p1[d]) - g;
      bx.hi[d] = std::max(l.p0[d], l.p1[d]) + g;
    }
    ox = std::min(ox, bx.lo.x);
    oy = std::min(oy, bx.lo.y);
    oz = std::min(oz, bx.lo.z);
    tx = std::max(tx, bx.hi.x);
    ty = std::max(ty, bx.hi.y);
    tz = std::max(tz, bx.hi.z);
    ex = std::max(ex, bx.hi.x - bx.lo.x);
    ey = std::max(ey, bx.hi.y - bx.lo.y);
    ez = std::max(ez, bx.hi.z - bx.lo.z);
    edges_[i] = std::max(bx.hi.x - bx.lo.x, std::max(bx.hi.y - bx.lo.y, bx.hi.z - bx.lo.z));
  }
  Layout layout;
  layout.origin = { ox, oy, oz };
  layout.top = { tx, ty, tz };
  layout.h[0] = ex;
  layout.h[1] = ey;
  layout.h[2] = ez;
  return layout;
}

// Phase 2: the cell size and the grid dimensions; which links count as oversize.
CollisionGrid::Layout CollisionGrid::chooseCells(std::size_t n, const Layout& bounds) const
{
  Layout grid = bounds;
  // Cell size: the largest "regular" box edge (§3.3). A few oversize links are tested against
  // everything instead of blowing up the cell size for all.
  // The median only sets the cell size (performance, never the result): a strided sample of
  // at most ~4096 links is enough.
  const std::size_t stride = n / 4096 + 1;
  std::vector<double> sample;
  sample.reserve(n / stride + 1);
  for (std::size_t i = 0; i < n; i += stride)
  {
    sample.push_back(edges_[i]);
  }
  std::nth_element(
    sample.begin(), sample.begin() + static_cast<long>(sample.size() / 2), sample.end());
  grid.limit = 2.0 * sample[sample.size() / 2];
  double h = 0.0;
  double hAll = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    hAll = std::max(hAll, edges_[i]);
    if (edges_[i] <= grid.limit)
    {
      h = std::max(h, edges_[i]);
    }
    else
    {
      ++grid.nOversize;
    }
  }
  if (grid.nOversize * 64 > n)
  {
    h = hAll;
    grid.nOversize = 0;
  }
  // Without oversize links every link is regular, and along each axis the largest edge of all
  // links is enough (two boxes overlapping along an axis have centres closer than it there):
  // flat models, such as a section whose fibers lie in its plane, get flat cells with fewer
  // links around each one. With oversize links the cells stay cubes of the largest regular edge.
  double hd[3];
  for (int d = 0; d < 3; ++d)
  {
    // Margin: floor((c − origin)/h) is rounded, keep neighbours at most one cell apart.
    hd[d] = std::max(grid.nOversize == 0 ? std::min(bounds.h[d], h) : h, 1e-300) * (1.0 + 1e-9);
  }
  double dims[3];
  for (int d = 0; d < 3; ++d)
  {
    dims[d] = std::floor((grid.top[d] - grid.origin[d]) / hd[d]) + 1.0;
  }
  // The linear cell index must fit 32 bits (sort key = cell << 32 | id): coarser cells stay
  // correct, only slower.
  while (dims[0] * dims[1] * dims[2] >= 4.0e9)
  {
    for (int d = 0; d < 3; ++d)
    {
      hd[d] *= 2.0;
      dims[d] = std::floor((grid.top[d] - grid.origin[d]) / hd[d]) + 1.0;
    }
  }
  for (int d = 0; d < 3; ++d)
  {
    grid.h[d] = hd[d];
  }
  grid.nx = static_cast<std::int64_t>(dims[0]);
  grid.ny = static_cast<std::int64_t>(dims[1]);
  grid.nz = static_cast<std::int64_t>(dims[2]);
  return grid;
}

// Phase 3: the oversize links, in id order (tested against all links instead of cell neighbours).
void CollisionGrid::collectOversize(const Layout& grid)
{
  const std::size_t n = edges_.size();
  oversize_.clear();
  for (std::size_t i = 0; grid.nOversize > 0 && i < n; ++i)
  {
    if (edges_[i] > grid.limit)
    {
      oversize_.push_back(static_cast<std::uint32_t>(i));
    }
  }
}

// Linear index of the grid cell holding the centre of box bx.
std::uint32_t CollisionGrid::cellOf(const Box& bx, const Layout& grid)
{
  std::int64_t c[3];
  for (int d = 0; d < 3; ++d)
  {
    const double centre = 0.5 * (bx.lo[d] + bx.hi[d]);
    c[d] = static_cast<std::int64_t>(std::floor((centre - grid.origin[d]) / grid.h[d]));
  }
  c[0] = std::min(std::max<std::int64_t>(c[0], 0), grid.nx - 1);
  c[1] = std::min(std::max<std::int64_t>(c[1], 0), grid.ny - 1);
  c[2] = std::min(std::max<std::int64_t>(c[2], 0), grid.nz - 1);
  return static_cast<std::uint32_t>(c[0] + grid.nx * (c[1] + grid.ny * c[2]));
}

// Phase 4: the regular links' ids sorted by (cell, id) into order_, the occupied cells ascending
// into cellKeys_ and their starts into cellStart_. Both ways give exactly this order.
void CollisionGrid::sortByCell(const Layout& grid, int nThreads)
{
  const double cells =
    static_cast<double>(grid.nx) * static_cast<double>(grid.ny) * static_cast<double>(grid.nz);
  if (cells <= 2.0 * static_cast<double>(edges_.size()))
  {
    countByCell(grid, static_cast<std::size_t>(cells), nThreads);
  }
  else
  {
    sortKeysByCell(grid, nThreads);
  }
}

// Dense grids (at most 2 cells per link, the usual case): a stable counting sort, O(links +
// cells) and parallel. Each of C chunks of consecutive ids counts its links per cell; a cell's
// links then go chunk after chunk, each chunk's in id order, which is id order.
void CollisionGrid::countByCell(const Layout& grid, std::size_t nCells, int nThreads)
{
  const std::size_t n = edges_.size();
  const std::int64_t nn = static_cast<std::int64_t>(n);
  constexpr std::uint32_t kOversizeCell = ~std::uint32_t(0);
  cellOf_.resize(n);
#pragma omp parallel for num_threads(nThreads) schedule(static)
  for (std::int64_t ii = 0; ii < nn; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    cellOf_[i] =
      grid.nOversize > 0 && edges_[i] > grid.limit ? kOversizeCell : cellOf(boxes_[i], grid);
  }
  // The counters take at most one 32-bit word per link (chunks × cells <= links, or one chunk).
  const std::size_t chunks = std::max<std::size_t>(1,
    std::min<std::size_t>(
      static_cast<std::size_t>(nThreads), n / std::max<std::size_t>(1, nCells)));
  refill(count_, chunks * nCells, std::uint32_t{ 0 });
  const auto chunkBegin = [n, chunks](std::size_t c) { return n * c / chunks; };
  const std::int64_t nChunks = static_cast<std::int64_t>(chunks);
#pragma omp parallel for num_threads(nThreads) schedule(static, 1)
  for (std::int64_t cc = 0; cc < nChunks; ++cc)
  {
    const std::size_t c = static_cast<std::size_t>(cc);
    std::uint32_t* count = count_.data() + c * nCells;
    for (std::size_t i = chunkBegin(c); i < chunkBegin(c + 1); ++i)
    {
      if (cellOf_[i] != kOversizeCell)
        ++count[cellOf_[i]];
    }
  }
  // Counts to starts (cell by cell, chunk by chunk), and the occupied cells.
  cellKeys_.clear();
  cellStart_.clear();
  rowOfCell_.resize(nCells + 1);
  std::uint32_t at = 0;
  for (std::size_t cell = 0; cell < nCells; ++cell)
  {
    const std::uint32_t first = at;
    rowOfCell_[cell] = first;
    for (std::size_t c = 0; c < chunks; ++c)
    {
      const std::uint32_t k = count_[c * nCells + cell];
      count_[c * nCells + cell] = at;
      at += k;
    }
    if (at > first)
    {
      cellKeys_.push_back(cell);
      cellStart_.push_back(first);
    }
  }
  cellStart_.push_back(at);
  rowOfCell_[nCells] = at;
  order_.resize(at);
#pragma omp parallel for num_threads(nThreads) schedule(static, 1)
  for (std::int64_t cc = 0; cc < nChunks; ++cc)
  {
    const std::size_t c = static_cast<std::size_t>(cc);
    std::uint32_t* next = count_.data() + c * nCells;
    for (std::size_t i = chunkBegin(c); i < chunkBegin(c + 1); ++i)
    {
      if (cellOf_[i] != kOversizeCell)
        order_[next[cellOf_[i]]++] = static_cast<std::uint32_t>(i);
    }
  }
  std::vector<std::uint64_t>().swap(sortKeys_); // the other way's buffers are not kept beside
  std::vector<std::uint32_t>().swap(prevOrder_);
}

// Sparse grids: keys (cell << 32) | id sorted. Links keep their ids between solver steps unless
// shape control changed a fiber, and move little: visiting them in last call's order
// (prevOrder_) makes the key array nearly sorted, and an insertion sort then costs O(N) instead
// of O(N log N). Any order gives the same sorted result.
void CollisionGrid::sortKeysByCell(const Layout& grid, int nThreads)
{
  const std::size_t n = edges_.size();
  const std::int64_t nn = static_cast<std::int64_t>(n);
  std::vector<std::uint32_t>().swap(cellOf_);
  std::vector<std::uint32_t>().swap(count_);
  std::vector<std::uint32_t>().swap(rowOfCell_);
  const bool reuse = prevOrder_.size() == n && grid.nOversize == 0;
  if (!reuse)
  {
    prevOrder_.resize(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      prevOrder_[i] = static_cast<std::uint32_t>(i);
    }
  }
  sortKeys_.resize(n);
  constexpr std::uint64_t kOversizeKey = ~std::uint64_t(0);
#pragma omp parallel for num_threads(nThreads) schedule(static)
  for (std::int64_t jj = 0; jj < nn; ++jj)
  {
    const std::uint32_t i = prevOrder_[static_cast<std::size_t>(jj)];
    if (grid.nOversize > 0 && edges_[i] > grid.limit)
    {
      sortKeys_[static_cast<std::size_t>(jj)] = kOversizeKey; // sorts last, then dropped
      continue;
    }
    const std::uint64_t cell = cellOf(boxes_[i], grid);
    sortKeys_[static_cast<std::size_t>(jj)] = (cell << 32) | static_cast<std::uint64_t>(i);
  }
  bool inOrder = false;
  if (reuse)
  {
    // Insertion sort with a work budget; fall back to std::sort when the order changed a lot.
    std::size_t work = 0;
    const std::size_t budget = 16 * n;
    inOrder = true;
    for (std::size_t i = 1; i < n && inOrder; ++i)
    {
      const std::uint64_t v = sortKeys_[i];
      std::size_t j = i;
      while (j > 0 && sortKeys_[j - 1] > v)
      {
        sortKeys_[j] = sortKeys_[j - 1];
        --j;
        if (++work > budget)
        {
          inOrder = false;
          break;
        }
      }
      sortKeys_[j] = v;
    }
  }
  if (!inOrder)
  {
    std::sort(sortKeys_.begin(), sortKeys_.end());
  }
  const std::size_t nRegular = n - oversize_.size();
  order_.resize(nRegular);
  cellKeys_.clear();
  cellStart_.clear();
  for (std::size_t r = 0; r < nRegular; ++r)
  {
    order_[r] = static_cast<std::uint32_t>(sortKeys_[r] & 0xFFFFFFFFu);
    prevOrder_[r] = order_[r];
    const std::uint64_t cell = sortKeys_[r] >> 32;
    if (cellKeys_.empty() || cellKeys_.back() != cell)
    {
      cellKeys_.push_back(cell);
      cellStart_.push_back(static_cast<std::uint32_t>(r));
    }
  }
  cellStart_.push_back(static_cast<std::uint32_t>(nRegular));
  if (!oversize_.empty())
  {
    prevOrder_.clear(); // no reuse next time
  }
}

// The (x, y, z) indices of a linear cell index.
void CollisionGrid::cellCoordinates(
  std::uint64_t cell, const Layout& grid, std::int64_t& cx, std::int64_t& cy, std::int64_t& cz)
{
  const auto c = static_cast<std::int64_t>(cell);
  cx = c % grid.nx;
  cy = (c / grid.nx) % grid.ny;
  cz = c / (grid.nx * grid.ny);
}

// The cell ranges [c0, c1] (per axis, clamped to the grid) holding the centres of all regular
// links whose boxes can overlap box bx: its extent widened by half a cell edge (a regular box is
// at most one edge wide), plus a margin for the rounding of the centres.
void CollisionGrid::reachedCells(
  const Box& bx, const Layout& grid, std::int64_t c0[3], std::int64_t c1[3])
{
  const std::int64_t n[3] = { grid.nx, grid.ny, grid.nz };
  for (int d = 0; d < 3; ++d)
  {
    const double margin = 0.5 * grid.h[d] + 1e-9 * (std::fabs(bx.lo[d]) + std::fabs(bx.hi[d]));
    const double lo = std::floor((bx.lo[d] - margin - grid.origin[d]) / grid.h[d]);
    const double hi = std::floor((bx.hi[d] + margin - grid.origin[d]) / grid.h[d]);
    c0[d] = static_cast<std::int64_t>(std::max(lo, 0.0));
    c1[d] = static_cast<std::int64_t>(std::min(hi, static_cast<double>(n[d] - 1)));
  }
}

// Phase 5: in each cell the flagged links first (each part in id order), and where its unflagged
// ones begin (all flagged, or no flags: the cell's end). A pair of two unflagged links is never
// tested, so only the cells with a flagged link are listed for the pair search (visit_).
void CollisionGrid::flaggedFirst(const char* tested)
{
  const std::size_t nCells = cellKeys_.size();
  cellUnflagged_.resize(nCells);
  visit_.clear();
  if (!tested)
  {
    std::copy(cellStart_.begin() + 1, cellStart_.end(), cellUnflagged_.begin());
    visit_.resize(nCells);
    for (std::size_t c = 0; c < nCells; ++c)
      visit_[c] = static_cast<std::uint32_t>(c);
    return;
  }
  scratch_.resize(order_.size());
  for (std::size_t c = 0; c < nCells; ++c)
  {
    std::uint32_t at = cellStart_[c];
    for (std::uint32_t r = cellStart_[c]; r < cellStart_[c + 1]; ++r)
    {
      if (tested[order_[r]])
        scratch_[at++] = order_[r];
    }
    cellUnflagged_[c] = at;
    if (at > cellStart_[c])
    {
      visit_.push_back(static_cast<std::uint32_t>(c));
    }
    for (std::uint32_t r = cellStart_[c]; r < cellStart_[c + 1]; ++r)
    {
      if (!tested[order_[r]])
        scratch_[at++] = order_[r];
    }
  }
  order_.swap(scratch_);
}

// Phase 6: the boxes as float SoA, the links and their tested flags in order_'s order. Only the
// rows the pair search reads are filled: those of the cells it visits (visit_) and of their
// neighbours, and all rows when there are oversize links (tested against every row). Late in a
// solve that is a small part of the links (QuietLinks); the other rows are never read.
void CollisionGrid::buildCellArrays(const std::vector<CapsuleLink>& links, const char* tested,
  const char* loud, const Layout& grid, int nThreads)
{
  const std::size_t nRegular = order_.size();
  const std::size_t nCells = cellKeys_.size();
  for (int d = 0; d < 3; ++d)
  {
    lo_[d].resize(nRegular);
    hi_[d].resize(nRegular);
  }
  sorted_.resize(nRegular);
  sortedTested_.resize(tested ? nRegular : 0);
  sortedLoud_.resize(loud ? nRegular : 0);
  const auto fillRows = [&](std::uint32_t rb, std::uint32_t re)
  {
    for (std::uint32_t r = rb; r < re; ++r)
    {
      const std::uint32_t id = order_[r];
      for (int d = 0; d < 3; ++d)
      {
        lo_[d][r] = floatBelow(boxes_[id].lo[d]);
        hi_[d][r] = floatAbove(boxes_[id].hi[d]);
      }
      sorted_[r] = links[id];
      if (tested)
      {
        sortedTested_[r] = tested[id];
      }
      if (loud)
      {
        sortedLoud_[r] = loud[id];
      }
    }
  };
  // Marking the neighbours costs 26 look-ups per visited cell: worth it only when few are.
  const bool all = !oversize_.empty() || visit_.size() * kFillAllBelow > nCells;
  fill_.clear();
  if (!all)
  {
    refill(need_, nCells, char{ 0 });
    for (const std::uint32_t ci : visit_)
    {
      need_[ci] = 1;
      std::int64_t cx = 0, cy = 0, cz = 0;
      cellCoordinates(cellKeys_[ci], grid, cx, cy, cz);
      for (std::int64_t z = std::max<std::int64_t>(cz - 1, 0); z <= std::min(cz + 1, grid.nz - 1);
           ++z)
        for (std::int64_t y = std::max<std::int64_t>(cy - 1, 0); y <= std::min(cy + 1, grid.ny - 1);
             ++y)
          for (std::int64_t x = std::max<std::int64_t>(cx - 1, 0);
               x <= std::min(cx + 1, grid.nx - 1); ++x)
          {
            const std::uint64_t key = static_cast<std::uint64_t>(x + grid.nx * (y + grid.ny * z));
            const auto it = std::lower_bound(cellKeys_.begin(), cellKeys_.end(), key);
            if (it != cellKeys_.end() && *it == key)
            {
              need_[static_cast<std::size_t>(it - cellKeys_.begin())] = 1;
            }
          }
    }
    for (std::size_t c = 0; c < nCells; ++c)
    {
      if (need_[c])
        fill_.push_back(static_cast<std::uint32_t>(c));
    }
  }
  const std::int64_t nf =
    all ? static_cast<std::int64_t>(nCells) : static_cast<std::int64_t>(fill_.size());
#pragma omp parallel for num_threads(nThreads) schedule(dynamic, 64)
  for (std::int64_t ff = 0; ff < nf; ++ff)
  {
    const std::size_t c = all ? static_cast<std::size_t>(ff) : fill_[static_cast<std::size_t>(ff)];
    fillRows(cellStart_[c], cellStart_[c + 1]);
  }
}

// Phase 6: broad and narrow phase over the cells and the oversize links, into perThread_; false
// (lists emptied) as soon as more than maxPairs pairs exist.
bool CollisionGrid::collectPairs(const std::vector<CapsuleLink>& links, const char* tested,
  TestedPairs rule, const char* loud, double minimumGap, const Layout& grid, int nThreads,
  std::size_t maxPairs)
{
  perThread_.resize(static_cast<std::size_t>(nThreads));
  for (auto& v : perThread_)
  {
    v.clear();
  }

  // Pairs found so far by all threads, published in chunks; once above maxPairs every thread
  // stops. Each pair is found once, so "stopped" means exactly "more than maxPairs pairs exist".
  std::atomic<std::size_t> found{ 0 };
  std::atomic<std::uint64_t> work{ 0 };
  // A pair of two unflagged links is never tested (either rule): a cell's unflagged rows (its
  // tail, from cellUnflagged_) are box-tested against the flagged head of a cell only.
  std::atomic<bool> overflow{ false };
  constexpr std::size_t kPublishChunk = 4096;

  // The 13 forward neighbours, then their mirror images: a pair of neighbouring cells with a
  // flagged link each is visited once, from the one below (forward); a flagged cell beside one
  // without a flagged link is visited from the flagged one (either direction).
  static const int kNeighbour[26][3] = { { 1, 0, 0 }, { -1, 1, 0 }, { 0, 1, 0 }, { 1, 1, 0 },
    { -1, -1, 1 }, { 0, -1, 1 }, { 1, -1, 1 }, { -1, 0, 1 }, { 0, 0, 1 }, { 1, 0, 1 }, { -1, 1, 1 },
    { 0, 1, 1 }, { 1, 1, 1 }, { -1, 0, 0 }, { 1, -1, 0 }, { 0, -1, 0 }, { -1, -1, 0 }, { 1, 1, -1 },
    { 0, 1, -1 }, { -1, 1, -1 }, { 1, 0, -1 }, { 0, 0, -1 }, { -1, 0, -1 }, { 1, -1, -1 },
    { 0, -1, -1 }, { -1, -1, -1 } };
  constexpr int kForwardNeighbours = 13;
  // Only the cells holding a flagged link are visited: late in a solve a few percent of the
  // cells (QuietLinks), and the others cost nothing (not even the neighbour look-ups). The pairs,
  // and the box and exact tests made, are those of visiting every cell with its forward
  // neighbours: a flagged cell's pairs with an unflagged neighbour are its flagged rows against
  // all of the neighbour's, whichever side the pair of cells is visited from.
  const std::int64_t nVisit = static_cast<std::int64_t>(visit_.size());

#pragma omp parallel num_threads(nThreads)
  {
#ifdef _OPENMP
    std::vector<CapsulePair>& out = perThread_[static_cast<std::size_t>(omp_get_thread_num())];
#else
    std::vector<CapsulePair>& out = perThread_[0];
#endif
    std::vector<std::uint32_t> cand;
    std::vector<std::uint8_t> mask;
    std::size_t published = out.size();
    std::uint64_t boxTests = 0, exactTests = 0;
    // Adds this thread's new pairs to the shared count; true when the limit is exceeded.
    auto publish = [&](bool force)
    {
      if (force || out.size() - published >= kPublishChunk)
      {
        const std::size_t total =
          found.fetch_add(out.size() - published) + (out.size() - published);
        published = out.size();
        if (total > maxPairs)
        {
          overflow.store(true, std::memory_order_relaxed);
        }
      }
      return overflow.load(std::memory_order_relaxed);
    };
    const float* lx = lo_[0].data();
    const float* ly = lo_[1].data();
    const float* lz = lo_[2].data();
    const float* hx = hi_[0].data();
    const float* hy = hi_[1].data();
    const float* hz = hi_[2].data();
    // Box r against boxes [qb, qe): branch-free compaction of the overlapping ones first (the
    // loop the broad phase spends its time in), then the exact test on the few candidates.
    // around: r is a loud row scanning its whole neighbourhood, itself included; a pair with
    // another loud row is tested from the one of smaller id only.
    auto scan = [&](std::uint32_t r, std::uint32_t qb, std::uint32_t qe,
                  std::vector<std::uint32_t>& c, bool around = false)
    {
      if (qe <= qb)
      {
        return;
      }
      const std::uint32_t len = qe - qb;
      boxTests += len;
      if (mask.size() < len)
      {
        mask.resize(len);
      }
      std::uint8_t* mk = mask.data();
      const float rlx = lx[r], rly = ly[r], rlz = lz[r], rhx = hx[r], rhy = hy[r], rhz = hz[r];
      const float* qlx = lx + qb;
      const float* qly = ly + qb;
      const float* qlz = lz + qb;
      const float* qhx = hx + qb;
      const float* qhy = hy + qb;
      const float* qhz = hz + qb;
      // Plain mask loop: the compiler vectorises it (SSE2 is enough).
      for (std::uint32_t j = 0; j < len; ++j)
      {
        mk[j] = static_cast<std::uint8_t>((rhx > qlx[j]) & (qhx[j] > rlx) & (rhy > qly[j]) &
          (qhy[j] > rly) & (rhz > qlz[j]) & (qhz[j] > rlz));
      }
      // Grown only, like the mask: resize() to a smaller length would shrink the size, and the
      // next longer row would zero the elements in between again (millions of rows a step).
      if (c.size() < len)
      {
        c.resize(len);
      }
      std::uint32_t* cp = c.data();
      std::size_t nc = 0;
      // Few boxes overlap (about one in twenty in a dense model): eight mask bytes at a time,
      // skipped at once when all are zero. The same candidates in the same order.
      std::uint32_t j = 0;
      for (; j + 8 <= len; j += 8)
      {
        std::uint64_t word = 0;
        std::memcpy(&word, mk + j, sizeof word);
        if (word == 0)
        {
          continue;
        }
        for (std::uint32_t k = j; k < j + 8; ++k)
        {
          cp[nc] = qb + k;
          nc += mk[k];
        }
      }
      for (; j < len; ++j)
      {
        cp[nc] = qb + j;
        nc += mk[j];
      }
      // The links in sorted order: the candidates of a row lie in its and the neighbouring
      // cells, near each other in memory (the model's order scatters them).
      const std::uint32_t ir = order_[r];
      const CapsuleLink& lr = sorted_[r];
      const bool rTested = !tested || sortedTested_[r];
      const bool rLoud = !loud || sortedLoud_[r];
      const bool either = rule == TestedPairs::EitherLink;
      for (std::size_t i = 0; i < nc; ++i)
      {
        const std::uint32_t q = cp[i];
        const std::uint32_t iq = order_[q];
        const bool qTested = !tested || sortedTested_[q];
        if (!rLoud && !sortedLoud_[q])
        {
          // two quiet links: known not to collide
        }
        else if (around && sortedLoud_[q] && iq <= ir)
        {
          // r itself, or a loud pair that the row of the smaller id tests
        }
        else if (ir < iq)
        {
          if (rTested || (either && qTested))
            testOrderedPair(lr, sorted_[q], ir, iq, minimumGap, out, exactTests);
        }
        else if (qTested || (either && rTested))
        {
          testOrderedPair(sorted_[q], lr, iq, ir, minimumGap, out, exactTests);
        }
        if ((i & 1023) == 1023 && publish(false))
        {
          return;
        }
      }
    };
    if (loud)
    {
      // Loud flags (QuietLinks): every loud row scans the 27 cells around it at once, as 9 runs
      // of 3 cells along x (consecutive keys, so consecutive rows); quiet rows scan nothing.
      // Per pair of cells this is the same pair set as the forward visits below, in a third of
      // the scans and with none from quiet rows (each scan costs about as much as its boxes).
#pragma omp for schedule(dynamic, 8)
      for (std::int64_t vi = 0; vi < nVisit; ++vi)
      {
        if (publish(false))
        {
          continue;
        }
        const std::size_t ci = visit_[static_cast<std::size_t>(vi)];
        std::int64_t cx = 0, cy = 0, cz = 0;
        cellCoordinates(cellKeys_[ci], grid, cx, cy, cz);
        std::uint32_t runBegin[9], runEnd[9];
        int runs = 0;
        for (std::int64_t z = std::max<std::int64_t>(cz - 1, 0); z <= std::min(cz + 1, grid.nz - 1);
             ++z)
        {
          for (std::int64_t y = std::max<std::int64_t>(cy - 1, 0);
               y <= std::min(cy + 1, grid.ny - 1); ++y)
          {
            const std::int64_t x0 = std::max<std::int64_t>(cx - 1, 0);
            const std::int64_t x1 = std::min(cx + 1, grid.nx - 1);
            const std::uint64_t k0 = static_cast<std::uint64_t>(x0 + grid.nx * (y + grid.ny * z));
            const std::uint64_t k1 = static_cast<std::uint64_t>(x1 + grid.nx * (y + grid.ny * z));
            if (!rowOfCell_.empty()) // dense grid: every cell's first row, no search
            {
              runBegin[runs] = rowOfCell_[k0];
              runEnd[runs] = rowOfCell_[k1 + 1];
              runs += runEnd[runs] > runBegin[runs] ? 1 : 0;
              continue;
            }
            const auto i0 = std::lower_bound(cellKeys_.begin(), cellKeys_.end(), k0);
            const auto i1 = std::upper_bound(i0, cellKeys_.end(), k1);
            if (i0 != i1)
            {
              runBegin[runs] = cellStart_[static_cast<std::size_t>(i0 - cellKeys_.begin())];
              runEnd[runs] = cellStart_[static_cast<std::size_t>(i1 - cellKeys_.begin())];
              ++runs;
            }
          }
        }
        for (std::uint32_t r = cellStart_[ci]; r < cellUnflagged_[ci] && !publish(false); ++r)
        {
          for (int k = 0; k < runs; ++k)
          {
            scan(r, runBegin[k], runEnd[k], cand, true);
          }
        }
      }
    }
    else
    {
#pragma omp for schedule(dynamic, 8)
      for (std::int64_t vi = 0; vi < nVisit; ++vi)
      {
        if (publish(false))
        {
          continue; // an omp for cannot break: skip the remaining cells
        }
        const std::size_t ci = visit_[static_cast<std::size_t>(vi)];
        std::int64_t cx = 0, cy = 0, cz = 0;
        cellCoordinates(cellKeys_[ci], grid, cx, cy, cz);
        const std::uint32_t begin = cellStart_[ci];
        const std::uint32_t end = cellStart_[ci + 1];
        const std::uint32_t split = cellUnflagged_[ci];
        for (std::uint32_t r = begin; r < split && !publish(false); ++r)
        {
          scan(
            r, r + 1, end, cand); // the unflagged rows after split would meet only unflagged ones
        }
        for (int o = 0; o < 26; ++o)
        {
          const std::int64_t x = cx + kNeighbour[o][0];
          const std::int64_t y = cy + kNeighbour[o][1];
          const std::int64_t z = cz + kNeighbour[o][2];
          if (x < 0 || y < 0 || z < 0 || x >= grid.nx || y >= grid.ny || z >= grid.nz)
          {
            continue;
          }
          const std::uint64_t key = static_cast<std::uint64_t>(x + grid.nx * (y + grid.ny * z));
          // Forward cells have larger keys, backward ones smaller: search only that side.
          const auto first = o < kForwardNeighbours
            ? cellKeys_.begin() + static_cast<std::ptrdiff_t>(ci) + 1
            : cellKeys_.begin();
          const auto last = o < kForwardNeighbours
            ? cellKeys_.end()
            : cellKeys_.begin() + static_cast<std::ptrdiff_t>(ci);
          const auto it = std::lower_bound(first, last, key);
          if (it == last || *it != key)
          {
            continue;
          }
          const std::size_t cj = static_cast<std::size_t>(it - cellKeys_.begin());
          const std::uint32_t b2 = cellStart_[cj];
          const std::uint32_t e2 = cellStart_[cj + 1];
          const std::uint32_t split2 = cellUnflagged_[cj];
          if (split2 == b2) // no flagged link there: this cell's flagged rows against all of it
          {
            for (std::uint32_t r = begin; r < split && !publish(false); ++r)
            {
              scan(r, b2, e2, cand);
            }
          }
          else if (o < kForwardNeighbours) // both flagged: visited from the lower cell only
          {
            for (std::uint32_t r = begin; r < end && !publish(false); ++r)
            {
              scan(r, b2, r < split ? e2 : split2, cand);
            }
          }
        }
      }
    }
    // Oversize links: against the regular links of the cells their box can reach, and against
    // later oversize links. A regular box is at most one cell edge wide, so a regular link whose
    // box overlaps the oversize one has its centre (which picks its cell) within half a cell
    // edge of that box: the cells of that widened box hold all its partners.
    const std::int64_t nOver = static_cast<std::int64_t>(oversize_.size());
    const char* headFlags = loud ? loud : tested; // what flaggedFirst put first in each cell
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t oi = 0; oi < nOver; ++oi)
    {
      if (publish(false))
      {
        continue;
      }
      const std::uint32_t o = oversize_[static_cast<std::size_t>(oi)];
      const Box& bo = boxes_[o];
      // An unflagged oversize link only meets the flagged heads of the cells (a pair of two
      // unflagged links is never tested).
      const bool headsOnly = headFlags && !headFlags[o];
      std::int64_t c0[3], c1[3];
      reachedCells(bo, grid, c0, c1);
      boxTests += static_cast<std::uint64_t>(nOver - oi - 1);
      for (std::int64_t z = c0[2]; z <= c1[2]; ++z)
        for (std::int64_t y = c0[1]; y <= c1[1]; ++y)
        {
          const std::uint64_t k0 = static_cast<std::uint64_t>(c0[0] + grid.nx * (y + grid.ny * z));
          const std::uint64_t k1 = static_cast<std::uint64_t>(c1[0] + grid.nx * (y + grid.ny * z));
          const auto i0 = std::lower_bound(cellKeys_.begin(), cellKeys_.end(), k0);
          const auto i1 = std::upper_bound(i0, cellKeys_.end(), k1);
          for (auto it = i0; it != i1; ++it)
          {
            const std::size_t c = static_cast<std::size_t>(it - cellKeys_.begin());
            const std::uint32_t rEnd = headsOnly ? cellUnflagged_[c] : cellStart_[c + 1];
            boxTests += rEnd - cellStart_[c];
            for (std::uint32_t r = cellStart_[c]; r < rEnd; ++r)
            {
              const Box br{ { lx[r], ly[r], lz[r] }, { hx[r], hy[r], hz[r] } };
              if (boxesOverlap(bo.lo, bo.hi, br.lo, br.hi))
              {
                testPair(links, tested, rule, loud, o, order_[r], minimumGap, out, exactTests);
              }
            }
          }
        }
      for (std::int64_t oj = oi + 1; oj < nOver; ++oj)
      {
        const std::uint32_t p = oversize_[static_cast<std::size_t>(oj)];
        if (boxesOverlap(bo.lo, bo.hi, boxes_[p].lo, boxes_[p].hi))
        {
          testPair(links, tested, rule, loud, o, p, minimumGap, out, exactTests);
        }
      }
    }
    publish(true);
    work += boxTests + kExactTestWork * exactTests;
  }
  work_ = work.load();
  if (overflow.load())
  {
    for (auto& v : perThread_)
    {
      std::vector<CapsulePair>().swap(v); // give the memory back: the caller reports the failure
    }
    return false;
  }
  return true;
}

// Phase 7: the per-thread lists merged into one sorted by (a, b). Each pair is found exactly
// once, so the order is independent of the schedule. A counting sort by a, O(pairs + links),
// then each link's few partners sorted by b: a comparison sort of the whole lists cost about
// 6 % of a distributed solver step on the 1000-fiber cube.
void CollisionGrid::mergePairs(std::size_t nLinks, int nThreads, std::vector<CapsulePair>& pairs)
{
  refill(pairEnd_, nLinks + 1, std::size_t{ 0 });
  std::size_t total = 0;
  for (const auto& v : perThread_)
  {
    total += v.size();
    for (const CapsulePair& p : v)
      ++pairEnd_[p.a + 1];
  }
  for (std::size_t i = 0; i < nLinks; ++i)
    pairEnd_[i + 1] += pairEnd_[i]; // now the start of link i's pairs
  pairs.resize(total);
  for (const auto& v : perThread_)
  {
    for (const CapsulePair& p : v)
      pairs[pairEnd_[p.a]++] = p; // afterwards pairEnd_[i] is the end of link i's pairs
  }
  const std::int64_t nn = static_cast<std::int64_t>(nLinks);
#pragma omp parallel for num_threads(nThreads) schedule(static)
  for (std::int64_t ii = 0; ii < nn; ++ii)
  {
    const std::size_t i = static_cast<std::size_t>(ii);
    const auto first = pairs.begin() + static_cast<std::ptrdiff_t>(i == 0 ? 0 : pairEnd_[i - 1]);
    const auto last = pairs.begin() + static_cast<std::ptrdiff_t>(pairEnd_[i]);
    std::sort(first, last, [](const CapsulePair& x, const CapsulePair& y) { return x.b < y.b; });
  }
}

} // namespace fiberpli
