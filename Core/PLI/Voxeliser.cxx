#include "PLI/Voxeliser.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace fiberpli
{
namespace pli
{

void TissueBlock::axis(std::int64_t i, std::int64_t j, std::int64_t k, float out[3]) const
{
  std::memcpy(out, &words[4 * index(i, j, k)], 3 * sizeof(float));
}

void TissueBlock::setVoxel(std::int64_t i, std::int64_t j, std::int64_t k, std::int32_t lab, const float ax[3])
{
  const std::size_t w = 4 * index(i, j, k);
  std::memcpy(&words[w], ax, 3 * sizeof(float));
  words[w + 3] = static_cast<std::uint32_t>(lab);
}

void TissueBlock::reset(const ColumnRange& c, std::int64_t nzIn)
{
  cols = c;
  nz = nzIn;
  const std::size_t n = static_cast<std::size_t>(c.nx() * c.ny() * nz);
  words.resize(4 * n);
  // Unowned: d2 = +inf, link 0, label 0.
  const double inf = std::numeric_limits<double>::infinity();
  std::uint32_t pattern[4];
  std::memcpy(pattern, &inf, sizeof(double));
  pattern[2] = 0;
  pattern[3] = 0;
  for (std::size_t v = 0; v < n; ++v)
  {
    std::memcpy(&words[4 * v], pattern, sizeof(pattern));
  }
}

void buildLinkTable(const FiberModel& model, const TissueSpec& spec, const Lattice& lat,
  const ColumnRange& region, std::int64_t binSize, LinkTable& t)
{
  t = LinkTable();
  t.binSize = std::max<std::int64_t>(1, binSize);
  t.maxScale.resize(spec.bundleIds.size(), 0.0);
  for (std::size_t b = 0; b < spec.layers.size(); ++b)
  {
    for (const Layer& l : spec.layers[b])
      t.maxScale[b] = std::max(t.maxScale[b], l.scale);
  }
  t.bx0 = region.i0;
  t.by0 = region.j0;
  t.nbx = std::max<std::int64_t>(1, (region.nx() + t.binSize - 1) / t.binSize);
  t.nby = std::max<std::int64_t>(1, (region.ny() + t.binSize - 1) / t.binSize);
  t.bins.assign(static_cast<std::size_t>(t.nbx * t.nby), {});

  // Global order g: bundle slot, then fiber index, then link index (§3.3 tie rule).
  std::vector<std::vector<int>> fibersOfSlot(spec.bundleIds.size());
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const int slot = spec.slotOf(model.fibers[f].bundle);
    if (slot < 0)
      ++t.unknownBundleFibers;
    else
      fibersOfSlot[static_cast<std::size_t>(slot)].push_back(static_cast<int>(f));
  }
  const double inv = 1.0 / lat.voxel;
  const Vec3 o{ lat.origin[0], lat.origin[1], lat.origin[2] };
  for (std::size_t slot = 0; slot < fibersOfSlot.size(); ++slot)
  {
    const double S = t.maxScale[slot];
    for (int f : fibersOfSlot[slot])
    {
      const Fiber& fib = model.fibers[static_cast<std::size_t>(f)];
      for (std::size_t k = 0; k + 1 < fib.points.size(); ++k)
      {
        LinkTable::Link L;
        L.p = (fib.points[k] - o) * inv;
        L.q = (fib.points[k + 1] - o) * inv;
        L.rp = fib.radii[k] * inv;
        L.rq = fib.radii[k + 1] * inv;
        L.slot = static_cast<std::int32_t>(slot);
        L.fiber = f;
        if (norm2(L.q - L.p) == 0.0)
        {
          ++t.zeroLengthLinks;
          continue;
        }
        const double grow = S * std::max(L.rp, L.rq);
        double lo[3], hi[3];
        for (int a = 0; a < 3; ++a)
        {
          lo[a] = std::min(L.p[a], L.q[a]) - grow;
          hi[a] = std::max(L.p[a], L.q[a]) + grow;
        }
        // Voxel centres c = i + 1/2 inside [lo, hi].
        const double fi0 = std::ceil(lo[0] - 0.5), fi1 = std::floor(hi[0] - 0.5);
        const double fj0 = std::ceil(lo[1] - 0.5), fj1 = std::floor(hi[1] - 0.5);
        if (hi[2] < 0.5 || lo[2] > static_cast<double>(lat.n[2]) - 0.5)
          continue;
        if (fi1 < static_cast<double>(region.i0) || fi0 > static_cast<double>(region.i1 - 1) ||
          fj1 < static_cast<double>(region.j0) || fj0 > static_cast<double>(region.j1 - 1))
          continue;
        const std::uint32_t g = static_cast<std::uint32_t>(t.links.size());
        t.links.push_back(L);
        const std::int64_t i0 = std::max<std::int64_t>(region.i0, static_cast<std::int64_t>(fi0));
        const std::int64_t i1 = std::min<std::int64_t>(region.i1 - 1, static_cast<std::int64_t>(fi1));
        const std::int64_t j0 = std::max<std::int64_t>(region.j0, static_cast<std::int64_t>(fj0));
        const std::int64_t j1 = std::min<std::int64_t>(region.j1 - 1, static_cast<std::int64_t>(fj1));
        for (std::int64_t by = (j0 - t.by0) / t.binSize; by <= (j1 - t.by0) / t.binSize; ++by)
          for (std::int64_t bx = (i0 - t.bx0) / t.binSize; bx <= (i1 - t.bx0) / t.binSize; ++bx)
            t.bins[static_cast<std::size_t>(by * t.nbx + bx)].push_back(g);
      }
    }
  }
}

namespace
{
inline double radiusAt(const LinkTable::Link& L, double tt, RadiusModel m)
{
  return m == RadiusModel::Linear ? (1.0 - tt) * L.rp + tt * L.rq : std::max(L.rp, L.rq);
}
} // namespace

void voxeliseBlock(const LinkTable& t, const TissueSpec& spec, const Lattice& lat,
  LateralOutside lateral, TissueBlock& block, VoxeliseStats& stats, const HaloShape* shape)
{
  stats = VoxeliseStats();
  ColumnRange fill = block.cols;
  if (lateral == LateralOutside::Background)
  {
    fill.i0 = std::max<std::int64_t>(fill.i0, 0);
    fill.j0 = std::max<std::int64_t>(fill.j0, 0);
    fill.i1 = std::min<std::int64_t>(fill.i1, lat.n[0]);
    fill.j1 = std::min<std::int64_t>(fill.j1, lat.n[1]);
  }
  const bool anything = fill.nx() > 0 && fill.ny() > 0 && !t.links.empty();

  // Candidates from the bins the block touches; sorted so that the visit order is fixed.
  std::vector<std::uint32_t> cand;
  if (anything)
  {
    const std::int64_t bxa = std::max<std::int64_t>(0, (fill.i0 - t.bx0) / t.binSize);
    const std::int64_t bxb = std::min<std::int64_t>(t.nbx - 1, (fill.i1 - 1 - t.bx0) / t.binSize);
    const std::int64_t bya = std::max<std::int64_t>(0, (fill.j0 - t.by0) / t.binSize);
    const std::int64_t byb = std::min<std::int64_t>(t.nby - 1, (fill.j1 - 1 - t.by0) / t.binSize);
    for (std::int64_t by = bya; by <= byb; ++by)
      for (std::int64_t bx = bxa; bx <= bxb; ++bx)
      {
        const auto& bin = t.bins[static_cast<std::size_t>(by * t.nbx + bx)];
        cand.insert(cand.end(), bin.begin(), bin.end());
      }
    std::sort(cand.begin(), cand.end());
    cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
  }

  const int L = spec.maxLayers();
  const RadiusModel rm = spec.radius;
  const std::int64_t nz = lat.n[2];
  std::uint32_t* w = block.words.data();

  for (const std::uint32_t g : cand)
  {
    const LinkTable::Link& lk = t.links[g];
    const std::vector<Layer>& layers = spec.layers[static_cast<std::size_t>(lk.slot)];
    const double S = t.maxScale[static_cast<std::size_t>(lk.slot)];
    const Vec3 ax = lk.q - lk.p;
    const double L2 = norm2(ax);
    const double grow = S * std::max(lk.rp, lk.rq);
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a)
    {
      lo[a] = static_cast<std::int64_t>(std::ceil(std::min(lk.p[a], lk.q[a]) - grow - 0.5));
      hi[a] = static_cast<std::int64_t>(std::floor(std::max(lk.p[a], lk.q[a]) + grow - 0.5));
    }
    lo[0] = std::max(lo[0], fill.i0);
    hi[0] = std::min(hi[0], fill.i1 - 1);
    lo[1] = std::max(lo[1], fill.j0);
    hi[1] = std::min(hi[1], fill.j1 - 1);
    lo[2] = std::max<std::int64_t>(lo[2], 0);
    hi[2] = std::min<std::int64_t>(hi[2], nz - 1);
    const Vec3 u = ax / std::sqrt(L2);
    const double qa = 1.0 - u.z * u.z;
    for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
      for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
      {
        // Only a cheap superset: the k where the centre is within `grow` of the infinite axis
        // line (a quadratic in z), widened by a voxel; the exact test below decides.
        const double wx = static_cast<double>(i) + 0.5 - lk.p.x, wy = static_cast<double>(j) + 0.5 - lk.p.y;
        const double e = wx * u.x + wy * u.y;
        const double qc = wx * wx + wy * wy - e * e - grow * grow;
        std::int64_t k0 = lo[2], k1 = hi[2];
        if (qa > 1e-9)
        {
          const double qb = -2.0 * e * u.z;
          const double disc = qb * qb - 4.0 * qa * qc;
          if (disc < 0.0)
            continue;
          const double sq = std::sqrt(disc);
          const double z1 = lk.p.z + (-qb - sq) / (2.0 * qa), z2 = lk.p.z + (-qb + sq) / (2.0 * qa);
          k0 = std::max(k0, static_cast<std::int64_t>(std::floor(z1 - 0.5)) - 1);
          k1 = std::min(k1, static_cast<std::int64_t>(std::ceil(z2 - 0.5)) + 1);
        }
        else if (qc > 1e-9 * grow * grow + 1e-9)
        {
          continue;
        }
        std::uint32_t* col = w + 4 * block.index(i, j, 0);
        const double cx = static_cast<double>(i) + 0.5, cy = static_cast<double>(j) + 0.5;
        std::int64_t out = 0;
        if (shape)
        {
          const ColumnRange& c = shape->core;
          out = std::max({ c.i0 - i, i - (c.i1 - 1), c.j0 - j, j - (c.j1 - 1), std::int64_t(0) });
        }
        for (std::int64_t k = k0; k <= k1; ++k)
        {
          if (out > 0 && out > shape->reach[static_cast<std::size_t>(k)])
            continue;
          const Vec3 c{ cx, cy, static_cast<double>(k) + 0.5 };
          double tt = dot(c - lk.p, ax) / L2;
          tt = tt < 0.0 ? 0.0 : (tt > 1.0 ? 1.0 : tt);
          const Vec3 X = lk.p + tt * ax;
          const double r = radiusAt(lk, tt, rm);
          const double d2 = norm2(c - X);
          if (d2 > S * S * r * r)
            continue;
          std::uint32_t* cell = col + 4 * k;
          double stored;
          std::memcpy(&stored, cell, sizeof(double));
          if (stored != std::numeric_limits<double>::infinity() &&
            t.links[cell[2]].fiber != lk.fiber)
            stats.overlap = true;
          if (d2 < stored || (d2 == stored && g > cell[2]))
          {
            int l = 0;
            while (l + 1 < static_cast<int>(layers.size()) && d2 > layers[l].scale * layers[l].scale * r * r)
              ++l;
            std::memcpy(cell, &d2, sizeof(double));
            cell[2] = g;
            cell[3] = static_cast<std::uint32_t>(1 + lk.slot * L + l);
          }
        }
      }
  }

  // Second pass: the owner key is replaced in place by the optic axis.
  const ColumnRange& all = block.cols;
  for (std::int64_t j = all.j0; j < all.j1; ++j)
    for (std::int64_t i = all.i0; i < all.i1; ++i)
    {
      std::uint32_t* col = w + 4 * block.index(i, j, 0);
      for (std::int64_t k = 0; k < nz; ++k)
      {
        std::uint32_t* cell = col + 4 * k;
        const std::int32_t lab = static_cast<std::int32_t>(cell[3]);
        float out[3] = { 0.0f, 0.0f, 0.0f };
        if (lab > 0)
        {
          ++stats.labelled;
          const LinkTable::Link& lk = t.links[cell[2]];
          const Layer& layer = spec.layers[static_cast<std::size_t>(lk.slot)][static_cast<std::size_t>((lab - 1) % L)];
          const Vec3 ax = lk.q - lk.p;
          if (layer.model == AxisModel::Parallel)
          {
            const Vec3 u = normalized(ax);
            out[0] = static_cast<float>(u.x);
            out[1] = static_cast<float>(u.y);
            out[2] = static_cast<float>(u.z);
          }
          else if (layer.model == AxisModel::Radial)
          {
            const Vec3 c{ static_cast<double>(i) + 0.5, static_cast<double>(j) + 0.5, static_cast<double>(k) + 0.5 };
            double tt = dot(c - lk.p, ax) / norm2(ax);
            tt = tt < 0.0 ? 0.0 : (tt > 1.0 ? 1.0 : tt);
            const Vec3 d = c - (lk.p + tt * ax);
            const double dn = norm(d);
            if (dn >= 1e-9 * radiusAt(lk, tt, spec.radius) && dn > 0.0)
            {
              out[0] = static_cast<float>(d.x / dn);
              out[1] = static_cast<float>(d.y / dn);
              out[2] = static_cast<float>(d.z / dn);
            }
          }
        }
        std::memcpy(cell, out, sizeof(out));
      }
    }
}

VoxeliseStats voxelise(const FiberModel& model, const TissueSpec& spec, const Lattice& lattice,
  const ColumnRange& cols, TissueBlock& block, LateralOutside lateral)
{
  LinkTable table;
  buildLinkTable(model, spec, lattice, cols, 64, table);
  block.reset(cols, lattice.n[2]);
  VoxeliseStats st;
  voxeliseBlock(table, spec, lattice, lateral, block, st);
  return st;
}

} // namespace pli
} // namespace fiberpli
