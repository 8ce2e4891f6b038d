#include "Tissue/LatticeSeeding.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

namespace fiberpli
{

namespace
{
struct Vec2
{
  double x, y;
};

// Length of the shortest non-zero vector of the 2-D lattice spanned by u and v (Lagrange–Gauss
// reduction: afterwards |u| <= |v| and |u·v| <= |u|²/2, so u is a shortest vector).
double shortestVector(Vec2 u, Vec2 v)
{
  for (;;)
  {
    if (v.x * v.x + v.y * v.y < u.x * u.x + u.y * u.y)
      std::swap(u, v);
    const double uu = u.x * u.x + u.y * u.y;
    const double ratio = (u.x * v.x + u.y * v.y) / uu;
    // Reduced; the tolerance stops ties (hexagonal lattices: |u| = |v|, ratio ½) from cycling.
    if (std::fabs(ratio) <= 0.5 + 1e-9)
      return std::sqrt(uu);
    const double m = std::round(ratio);
    v = { v.x - m * u.x, v.y - m * u.y };
  }
}

// A lattice of `populations` empty site lists at the given spacing, for a builder to fill.
PeriodicLattice emptyLattice(double spacing, int populations)
{
  PeriodicLattice lattice;
  lattice.spacing = spacing;
  lattice.sites.resize(static_cast<std::size_t>(populations));
  return lattice;
}

// The centre of the k-th of n equal intervals of [−L/2, L/2].
double intervalCentre(double L, double k, double n)
{
  return L * (k + 0.5) / n - 0.5 * L;
}

// One population: every lattice containing the cell's period lattice L·Z² with N sites is, in
// Hermite normal form, `rows` rows of N/rows sites (spacing L·rows/N) with row j shifted by
// j·shift·L/N (0 <= shift < rows). Of all N in [count, count + 2 %], the largest spacing wins;
// above 20 000 sites only shifts near rows/2 are tried (near-hexagonal with rows along t1).
PeriodicLattice triangular(double L, int count)
{
  const std::int64_t extra = std::max<std::int64_t>(2, (count + 49) / 50);
  double best = -1.0;
  std::int64_t bestN = 0, bestRows = 0, bestShift = 0;
  for (std::int64_t n = std::max(1, count); n <= count + extra; ++n)
  {
    for (std::int64_t divisor = 1; divisor * divisor <= n; ++divisor)
    {
      if (n % divisor != 0)
        continue;
      for (const std::int64_t rows : { divisor, n / divisor })
      {
        const bool all = n <= 20000;
        const std::int64_t lo = all ? 0 : rows / 2 - 3;
        const std::int64_t hi = all ? rows - 1 : rows / 2 + 3;
        for (std::int64_t shift = lo; shift <= hi; ++shift)
        {
          const double d = shortestVector({ L * double(rows) / double(n), 0.0 },
            { L * double(shift) / double(n), L / double(rows) });
          if (d > best * (1.0 + 1e-12))
          {
            best = d;
            bestN = n;
            bestRows = rows;
            bestShift = shift;
          }
        }
      }
    }
  }
  PeriodicLattice lattice = emptyLattice(best, 1);
  const std::int64_t perRow = bestN / bestRows;
  for (std::int64_t j = 0; j < bestRows; ++j)
  {
    for (std::int64_t i = 0; i < perRow; ++i)
    {
      const std::int64_t u = (i * bestRows + j * bestShift) % bestN;
      lattice.sites[0].push_back({ intervalCentre(L, double(u), double(bestN)),
        intervalCentre(L, double(j), double(bestRows)) });
    }
  }
  return lattice;
}

// Two populations: 2m layers along z (x-fibers in even layers, y-fibers in odd ones), n fibers per
// layer. Axes of crossing fibers in adjacent layers are L/2m apart, parallel ones in a layer L/n.
PeriodicLattice layers(double L, int count)
{
  double best = -1.0;
  int bestM = 1, bestN = std::max(1, count);
  for (int m = 1; m <= std::max(1, count); ++m)
  {
    const int n = std::max(1, (count + m - 1) / m);
    const double d = std::min(L / (2.0 * m), L / double(n));
    if (d > best * (1.0 + 1e-12) ||
      (d > best * (1.0 - 1e-12) && std::int64_t(m) * n < std::int64_t(bestM) * bestN))
    {
      best = d;
      bestM = m;
      bestN = n;
    }
  }
  PeriodicLattice lattice = emptyLattice(best, 2);
  const double h = L / (2.0 * bestM);
  for (int l = 0; l < bestM; ++l)
  {
    for (int i = 0; i < bestN; ++i)
    {
      const double across = intervalCentre(L, i, bestN);
      // Population 0 (x): (t1, t2) = (y, z); population 1 (y): (t1, t2) = (z, x).
      lattice.sites[0].push_back({ across, (2 * l + 0.5) * h - 0.5 * L });
      lattice.sites[1].push_back({ (2 * l + 1.5) * h - 0.5 * L, across });
    }
  }
  return lattice;
}

// Three populations: n×n cells of edge a = L/n, each with one x-, one y- and one z-rod; any two
// perpendicular rods are a/2 apart in the third coordinate (x at (y, z) = (0, 0), y at
// (x, z) = (a/2, a/2), z at (x, y) = (0, a/2), plus an offset a/4).
PeriodicLattice cubicRods(double L, int count)
{
  int n = 1;
  while (std::int64_t(n) * n < count)
    ++n;
  const double a = L / n;
  const double o = 0.25 * a - 0.5 * L;
  PeriodicLattice lattice = emptyLattice(0.5 * a, 3);
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      lattice.sites[0].push_back({ o + i * a, o + j * a });                     // (y, z)
      lattice.sites[1].push_back({ o + j * a + 0.5 * a, o + i * a + 0.5 * a }); // (z, x)
      lattice.sites[2].push_back({ o + i * a, o + j * a + 0.5 * a });           // (x, y)
    }
  }
  return lattice;
}
// Three populations, bundled: each population fills one rectangular block of the cross-section
// with hexagonal rows, x-fibers (y, z) in [0, w0] × [0, h0], y-fibers (z, x) in [h0, h0 + w1] ×
// [0, h1], z-fibers (x, y) in [h1, h1 + w2] × [w0, w0 + h2]: blocks of different populations
// never share a coordinate range they both need, so no two of them cross (a quarter of the cell
// stays empty). Straight-fiber limit 3/4 × the hexagonal 0.907 for large blocks, above the
// finely interleaved 3π/16 once blocks hold a few dozen fibers.
struct Block
{
  double w = 0.0, h = 0.0; // extent along t1 and t2, walls included (half a spacing each side)
  int perRow = 0, rows = 0;
  double shift = 0.0;   // odd rows shifted along the row by this much
  bool shorter = false; // odd rows hold perRow − 1 sites (shift = d/2)
  bool rotated = false; // rows run along t2
};

// The blocks of at least `count` sites at spacing d (rows of m sites, every second one shifted by
// δ ∈ [0, d/2] and the rows sqrt(d² − δ²) apart, or alternating m and m − 1 sites), both ways.
std::vector<Block> blocks(double L, double d, int count)
{
  std::vector<Block> out;
  const int most = static_cast<int>(std::floor(L / d));
  for (int m = 1; m <= most; ++m)
  {
    const int rows = (count + m - 1) / m;
    for (int step = 0; step <= (rows > 1 ? 4 : 0); ++step)
    {
      const double delta = 0.125 * d * step;
      out.push_back({ m * d + delta, (rows - 1) * std::sqrt(d * d - delta * delta) + d, m, rows,
        delta, false });
    }
    if (m >= 2)
    {
      const int pairs = count / (2 * m - 1);
      const int alternating = count - pairs * (2 * m - 1) > 0
        ? 2 * pairs + (count - pairs * (2 * m - 1) > m ? 2 : 1)
        : 2 * pairs;
      out.push_back(
        { m * d, (alternating - 1) * 0.5 * std::sqrt(3.0) * d + d, m, alternating, 0.5 * d, true });
    }
  }
  const std::size_t n = out.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    Block b = out[i];
    std::swap(b.w, b.h);
    b.rotated = true;
    out.push_back(b);
  }
  out.erase(
    std::remove_if(out.begin(), out.end(), [L](const Block& b) { return b.w > L || b.h > L; }),
    out.end());
  return out;
}

// The first index i < end with value[i] <= limit, or `end` when there is none: a segment tree of
// minima, so that fitBlocks asks it in O(log n) instead of scanning.
class FirstAtMost
{
public:
  explicit FirstAtMost(const std::vector<double>& value)
    : n_(value.size())
  {
    size_ = 1;
    while (size_ < n_)
      size_ *= 2;
    tree_.assign(2 * size_, HUGE_VAL);
    std::copy(value.begin(), value.end(), tree_.begin() + static_cast<std::ptrdiff_t>(size_));
    for (std::size_t k = size_ - 1; k >= 1; --k)
      tree_[k] = std::min(tree_[2 * k], tree_[2 * k + 1]);
  }
  std::size_t find(std::size_t end, double limit) const
  {
    return end == 0 ? 0 : descend(1, 0, size_, end, limit);
  }

private:
  // In node k covering [lo, hi): the first index < end with a value <= limit, or `end`.
  std::size_t descend(
    std::size_t k, std::size_t lo, std::size_t hi, std::size_t end, double limit) const
  {
    if (lo >= end || !(tree_[k] <= limit))
      return end;
    if (hi - lo == 1)
      return lo;
    const std::size_t mid = (lo + hi) / 2;
    const std::size_t left = descend(2 * k, lo, mid, end, limit);
    return left < end ? left : descend(2 * k + 1, mid, hi, end, limit);
  }
  std::size_t n_ = 0;
  std::size_t size_ = 1;
  std::vector<double> tree_;
};

// Blocks k = 0, 1, 2 with h_k + w_{k+1} <= L (cyclic), the blocks sorted by w: the first b0 (in
// that order) for which a b1 fits, the first such b1, and for it the b2 of least h among those
// with w <= L − h1. For each b1 that b2 is fixed (the running minimum of h), so whether a b1 fits
// b0 is h0 + w1 <= L (a prefix of the order) and that b2's h <= L − w0: the first b1 is a query of
// FirstAtMost. O(n log n) in the n blocks (it was O(n²): a minute for 10⁶ fibers). False when
// none fit.
bool fitBlocks(double L, double d, int count, Block chosen[3])
{
  std::vector<Block> b = blocks(L, d, count);
  std::sort(b.begin(), b.end(), [](const Block& x, const Block& y) { return x.w < y.w; });
  std::vector<std::size_t> lowest(b.size());
  for (std::size_t i = 0; i < b.size(); ++i)
    lowest[i] = i > 0 && b[lowest[i - 1]].h <= b[i].h ? lowest[i - 1] : i;
  // For b1 = b[i]: the index of its b2 (b.size() when none) and that b2's h (inf when none).
  std::vector<std::size_t> third(b.size(), b.size());
  std::vector<double> thirdH(b.size(), HUGE_VAL);
  for (std::size_t i = 0; i < b.size(); ++i)
  {
    const auto end = std::upper_bound(
      b.begin(), b.end(), L - b[i].h, [](double x, const Block& y) { return x < y.w; });
    if (end != b.begin())
    {
      third[i] = lowest[static_cast<std::size_t>(end - b.begin()) - 1];
      thirdH[i] = b[third[i]].h;
    }
  }
  const FirstAtMost firstFit(thirdH);
  for (const Block& b0 : b)
  {
    // b1: h0 + w1 <= L (the same comparison as ever, so the same blocks are chosen), a prefix.
    const auto prefix = std::partition_point(
      b.begin(), b.end(), [&b0, L](const Block& y) { return b0.h + y.w <= L; });
    const std::size_t end = static_cast<std::size_t>(prefix - b.begin());
    const std::size_t i = firstFit.find(end, L - b0.w);
    if (i < end)
    {
      chosen[0] = b0;
      chosen[1] = b[i];
      chosen[2] = b[third[i]];
      return true;
    }
  }
  return false;
}

// The sites of one block with its lower corner at (o1, o2).
void placeBlock(
  const Block& b, double d, double o1, double o2, double L, std::vector<LatticeSite>& sites)
{
  const double pitch = b.shorter ? 0.5 * std::sqrt(3.0) * d : std::sqrt(d * d - b.shift * b.shift);
  for (int j = 0; j < b.rows; ++j)
  {
    const bool odd = j % 2 == 1;
    const int n = odd && b.shorter ? b.perRow - 1 : b.perRow;
    for (int i = 0; i < n; ++i)
    {
      const double along = 0.5 * d + i * d + (odd ? b.shift : 0.0);
      const double across = 0.5 * d + j * pitch;
      const double t1 = b.rotated ? across : along, t2 = b.rotated ? along : across;
      sites.push_back({ o1 + t1 - 0.5 * L, o2 + t2 - 0.5 * L });
    }
  }
}

// The largest spacing at which the three blocks fit (bisection; feasibility is monotone up to the
// steps of the site counts), the free room split evenly over the walls.
PeriodicLattice bundledBlocks(double L, int count)
{
  Block chosen[3];
  double lo = 0.0, hi = L;
  for (int it = 0; it < 60; ++it)
  {
    const double mid = 0.5 * (lo + hi);
    (fitBlocks(L, mid, count, chosen) ? lo : hi) = mid;
  }
  if (!(lo > 0.0) || !fitBlocks(L, lo, count, chosen))
    return {};
  PeriodicLattice lattice = emptyLattice(lo, 3);
  // Free room along the coordinate blocks k and k + 1 share (t2 of k = t1 of k + 1), a quarter of
  // it before each block.
  double room[3];
  for (int k = 0; k < 3; ++k)
    room[k] = L - chosen[k].h - chosen[(k + 1) % 3].w;
  // Block 0: t1 = y from room[2]/4, t2 = z from room[0]/4; block 1: t1 = z after block 0,
  // t2 = x from room[1]/4; block 2: t1 = x after block 1's t2, t2 = y after block 0's t1.
  const double y0 = 0.25 * room[2], z0 = 0.25 * room[0], x1 = 0.25 * room[1];
  const double z1 = z0 + chosen[0].h + 0.5 * room[0];
  const double x2 = x1 + chosen[1].h + 0.5 * room[1];
  const double y2 = y0 + chosen[0].w + 0.5 * room[2];
  placeBlock(chosen[0], lo, y0, z0, L, lattice.sites[0]);
  placeBlock(chosen[1], lo, z1, x1, L, lattice.sites[1]);
  placeBlock(chosen[2], lo, x2, y2, L, lattice.sites[2]);
  return lattice;
}
} // namespace

PeriodicLattice periodicLattice(double L, const std::vector<int>& counts)
{
  if (!(L > 0.0) || !std::isfinite(L) || counts.empty() || counts.size() > 3)
    return {};
  const int most = std::max(0, *std::max_element(counts.begin(), counts.end()));
  switch (counts.size())
  {
    case 1:
      return triangular(L, most);
    case 2:
      return layers(L, most);
    default:
    {
      // Whichever arrangement keeps the fibers farther apart.
      PeriodicLattice rods = cubicRods(L, most);
      PeriodicLattice bundled = bundledBlocks(L, most);
      return bundled.spacing > rods.spacing * (1.0 + 1e-9) ? bundled : rods;
    }
  }
}

} // namespace fiberpli
