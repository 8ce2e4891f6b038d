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
  PeriodicLattice lattice;
  lattice.spacing = best;
  lattice.sites.resize(1);
  const std::int64_t perRow = bestN / bestRows;
  for (std::int64_t j = 0; j < bestRows; ++j)
  {
    for (std::int64_t i = 0; i < perRow; ++i)
    {
      const std::int64_t u = (i * bestRows + j * bestShift) % bestN;
      lattice.sites[0].push_back({ L * (double(u) + 0.5) / double(bestN) - 0.5 * L,
        L * (double(j) + 0.5) / double(bestRows) - 0.5 * L });
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
  PeriodicLattice lattice;
  lattice.spacing = best;
  lattice.sites.resize(2);
  const double h = L / (2.0 * bestM);
  for (int l = 0; l < bestM; ++l)
  {
    for (int i = 0; i < bestN; ++i)
    {
      const double across = L * (i + 0.5) / bestN - 0.5 * L;
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
  PeriodicLattice lattice;
  lattice.spacing = 0.5 * a;
  lattice.sites.resize(3);
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
      return cubicRods(L, most);
  }
}

} // namespace fiberpli
