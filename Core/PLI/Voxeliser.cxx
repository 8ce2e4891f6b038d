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

void TissueBlock::setVoxel(
  std::int64_t i, std::int64_t j, std::int64_t k, std::int32_t lab, const float ax[3])
{
  const std::size_t w = 4 * index(i, j, k);
  std::memcpy(&words[w], ax, 3 * sizeof(float));
  words[w + 3] = static_cast<std::uint32_t>(lab);
}

void TissueBlock::reset(const GridRange& c, std::int64_t nzIn)
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

void tissueLinkTable(const FiberModel& model, const TissueSpec& spec, const SectionLattice& lat,
  const GridRange& region, std::int64_t binSize, LinkTable& t)
{
  std::vector<double> scale(spec.bundleIds.size(), 0.0);
  for (std::size_t b = 0; b < spec.layers.size() && b < scale.size(); ++b)
  {
    for (const Layer& l : spec.layers[b])
      scale[b] = std::max(scale[b], l.scale);
  }
  buildLinkTable(model, spec.bundleIds, scale, spec.radius, lat, region, binSize, t);
}

namespace
{
/// One voxel column of the block while filling: the owner key (d2, link id) and the label in
/// place, the layer of a new owner from its d² (§3.2), and the bow-tie of the halo (voxels no
/// ray reads are skipped).
struct BlockColumn
{
  std::uint32_t* col;
  const LinkTable* table;
  const std::vector<Layer>* layers;
  const std::vector<std::int64_t>* reach;
  std::int64_t out;
  std::uint32_t g;
  std::int32_t strand;
  std::int32_t labelBase;
  bool* overlap;
  double cx, cy; ///< the column's voxel centre (for the inner radius of an axon layer)
  RadiusModel radius;

  bool skip(std::int64_t k) const { return out > 0 && out > (*reach)[static_cast<std::size_t>(k)]; }
  /// Outer d² of a layer at voxel k: (scale·r)², or the local inner radius² of an axon layer.
  double layerBound(const Layer& layer, std::int64_t k, double r) const
  {
    if (!layer.innerRadius)
      return layer.scale * layer.scale * r * r;
    const SectionLink& lk = table->links[g];
    const Vec3 c{ cx, cy, static_cast<double>(k) + 0.5 };
    const Vec3 ax = lk.q - lk.p;
    double tt = dot(c - lk.p, ax) / norm2(ax);
    tt = tt < 0.0 ? 0.0 : (tt > 1.0 ? 1.0 : tt);
    const double ri = innerRadiusAt(lk, tt, radius);
    return ri * ri;
  }
  void cover(std::int64_t k, double d2, double r)
  {
    std::uint32_t* cell = col + 4 * k;
    double stored;
    std::memcpy(&stored, cell, sizeof(double));
    // Shared with another fiber: an overlap. Links of one fiber, or of the periodic translates
    // of one closed fiber (its strand), meet at their joints without overlapping.
    if (stored != std::numeric_limits<double>::infinity() && table->links[cell[2]].strand != strand)
      *overlap = true;
    if (ownerWins(d2, g, stored, cell[2]))
    {
      int l = 0;
      const std::vector<Layer>& ls = *layers;
      while (l + 1 < static_cast<int>(ls.size()) && d2 > layerBound(ls[l], k, r))
        ++l;
      std::memcpy(cell, &d2, sizeof(double));
      cell[2] = g;
      cell[3] = static_cast<std::uint32_t>(labelBase + l);
    }
  }
};
} // namespace

void voxeliseBlock(const LinkTable& t, const TissueSpec& spec, const SectionLattice& lat,
  LateralOutside lateral, TissueBlock& block, VoxeliseStats& stats, const HaloShape* shape)
{
  stats = VoxeliseStats();
  GridRange fill = block.cols;
  if (lateral == LateralOutside::Background)
  {
    fill.i0 = std::max<std::int64_t>(fill.i0, 0);
    fill.j0 = std::max<std::int64_t>(fill.j0, 0);
    fill.i1 = std::min<std::int64_t>(fill.i1, lat.n[0]);
    fill.j1 = std::min<std::int64_t>(fill.j1, lat.n[1]);
  }
  // Candidates from the bins the block touches; sorted so that the visit order is fixed.
  std::vector<std::uint32_t> cand;
  candidateLinks(t, fill, cand);

  const int L = spec.maxLayers();
  const std::int64_t nz = lat.n[2];
  std::uint32_t* w = block.words.data();
  const std::vector<std::int64_t> noReach;
  for (const std::uint32_t g : cand)
  {
    const SectionLink& lk = t.links[g];
    const std::vector<Layer>* layers = &spec.layers[static_cast<std::size_t>(lk.slot)];
    forEachCoveredVoxel(t, g, fill, nz,
      [&](std::int64_t i, std::int64_t j)
      {
        std::int64_t out = 0;
        if (shape)
        {
          const GridRange& c = shape->core;
          out = std::max({ c.i0 - i, i - (c.i1 - 1), c.j0 - j, j - (c.j1 - 1), std::int64_t(0) });
        }
        return BlockColumn{ w + 4 * block.index(i, j, 0), &t, layers,
          shape ? &shape->reach : &noReach, out, g, lk.strand, 1 + lk.slot * L, &stats.overlap,
          static_cast<double>(i) + 0.5, static_cast<double>(j) + 0.5, spec.radius };
      });
  }

  // Second pass: the owner key is replaced in place by the optic axis.
  const GridRange& all = block.cols;
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
          const SectionLink& lk = t.links[cell[2]];
          const Layer& layer =
            spec.layers[static_cast<std::size_t>(lk.slot)][static_cast<std::size_t>((lab - 1) % L)];
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
            const Vec3 c{ static_cast<double>(i) + 0.5, static_cast<double>(j) + 0.5,
              static_cast<double>(k) + 0.5 };
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

VoxeliseStats voxelise(const FiberModel& model, const TissueSpec& spec,
  const SectionLattice& lattice, const GridRange& cols, TissueBlock& block, LateralOutside lateral)
{
  LinkTable table;
  tissueLinkTable(model, spec, lattice, cols, 64, table);
  block.reset(cols, lattice.n[2]);
  VoxeliseStats st;
  voxeliseBlock(table, spec, lattice, lateral, block, st);
  return st;
}

} // namespace pli
} // namespace fiberpli
