/// LinkTable and the one voxel-ownership rule of a section (docs/pli-simulation.md §3.3): which
/// fiber link owns a voxel centre. The simulation's voxeliser (Core/PLI/Voxeliser.h) and the ground
/// truth (Core/Analysis/GroundTruth.h) both build this table and visit voxels with
/// forEachCoveredVoxel and ownerWins, in voxel units, so the "true orientation" of a voxel is
/// exactly the one simulated.
///
/// The rule: links are numbered g in the order (bundle slot, fiber index, link index); a voxel
/// centre c is covered by link g when d² = |c − X|² <= S²·r², X the nearest point of the link's
/// axis, r the local radius there (RadiusModel) and S the scale of the link's slot; of the links
/// covering c, the one with the smallest d² owns it, ties going to the larger g. The owner does not
/// depend on the order the links are visited in, nor on how the lattice is split into blocks.
#pragma once

#include "Geometry/Vec3.h"
#include "Model/FiberModel.h"
#include "Section/PixelGrid.h"
#include "Section/SectionLattice.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace fiberpli
{

/// Local radius of a link (§3.3): Linear taper (fastPLI) or the collision capsule radius max(rP,
/// rQ).
enum class RadiusModel : std::uint8_t
{
  Linear,
  Max
};

/// One link of a fiber in voxel units of the lattice.
struct SectionLink
{
  Vec3 p, q; ///< voxel units: (point − origin)/voxel
  double rp = 0, rq = 0;
  double ip = 0,
         iq = 0; ///< inner radii (voxel units): Fiber::innerRadii, or rp, rq without a sheath
  std::int32_t slot = 0;  ///< bundle slot
  std::int32_t fiber = 0; ///< index in FiberModel::fibers
  std::int32_t strand =
    0; ///< fiberStrands: the same for the periodic translates of one closed fiber
};

/// All links that can reach a lateral region, in the order g of the rule, with a 2-D bin grid over
/// (x, y) for candidate look-up.
struct LinkTable
{
  std::vector<SectionLink> links;
  std::vector<double> scale; ///< S per bundle slot
  RadiusModel radius = RadiusModel::Linear;
  std::int64_t binSize = 64, bx0 = 0, by0 = 0, nbx = 0, nby = 0;
  std::vector<std::vector<std::uint32_t>> bins;
  int zeroLengthLinks = 0;
  int unknownBundleFibers = 0; ///< fibers whose bundle has no slot (skipped)
};

/// Collects the links whose grown bounding box meets the columns `region` (global voxel indices)
/// and the slab z ∈ [0, n_z). slotBundles are the bundle ids of the slots (sorted, distinct),
/// slotScale their S; fibers of other bundles are skipped and counted.
void buildLinkTable(const FiberModel& model, const std::vector<int>& slotBundles,
  const std::vector<double>& slotScale, RadiusModel radius, const SectionLattice& lattice,
  const GridRange& region, std::int64_t binSize, LinkTable& table);

/// Per fiber the index of the first fiber of its strand. A strand is a closed fiber of a periodic
/// cell and its translates by its closure T = last − first (PeriodicTiling.h makes them): fiber b
/// continues fiber a when b is a translated a (same bundle, point count and radii, every point
/// moved by the same t) and b starts where a ends (t = T), both within 1e-9 of the coordinates'
/// magnitude. Such copies are one infinite fiber: where they join, they share voxels without
/// overlapping (docs/pli-simulation.md §3.3). Every other fiber is a strand of its own.
std::vector<std::int32_t> fiberStrands(const FiberModel& model);

/// Sorted distinct bundle ids of the model's fibers (the slots of a table that skips no fiber).
std::vector<int> bundlesOf(const FiberModel& model);

/// The ids g of the links whose bins meet the columns `fill`, sorted and distinct.
void candidateLinks(const LinkTable& table, const GridRange& fill, std::vector<std::uint32_t>& out);

/// The tie-break of the rule: a link at d² with id g takes a voxel held at storedD2 by storedG.
inline bool ownerWins(double d2, std::uint32_t g, double storedD2, std::uint32_t storedG)
{
  return d2 < storedD2 || (d2 == storedD2 && g > storedG);
}

/// Local radius at the axis parameter t ∈ [0, 1] (the radius taper of the rule).
inline double radiusAt(const SectionLink& l, double t, RadiusModel m)
{
  return m == RadiusModel::Linear ? (1.0 - t) * l.rp + t * l.rq : std::max(l.rp, l.rq);
}

/// Local inner radius at t, tapered like the radius.
inline double innerRadiusAt(const SectionLink& l, double t, RadiusModel m)
{
  return m == RadiusModel::Linear ? (1.0 - t) * l.ip + t * l.iq : std::max(l.ip, l.iq);
}

/// Visits every voxel centre of the columns `fill` × [0, nz) that link g covers (the capsule test
/// of the rule). `column(i, j)` gives a visitor for column (i, j) with `bool skip(k)` (a voxel the
/// caller never reads: not even tested) and `void cover(k, d2, r)` (covered, at d² and local radius
/// r).
template <class Column>
void forEachCoveredVoxel(
  const LinkTable& t, std::uint32_t g, const GridRange& fill, std::int64_t nz, Column&& column)
{
  const SectionLink& lk = t.links[g];
  const double S = t.scale[static_cast<std::size_t>(lk.slot)];
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
      const double wx = static_cast<double>(i) + 0.5 - lk.p.x,
                   wy = static_cast<double>(j) + 0.5 - lk.p.y;
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
      auto visitor = column(i, j);
      const double cx = static_cast<double>(i) + 0.5, cy = static_cast<double>(j) + 0.5;
      for (std::int64_t k = k0; k <= k1; ++k)
      {
        if (visitor.skip(k))
          continue;
        const Vec3 c{ cx, cy, static_cast<double>(k) + 0.5 };
        double tt = dot(c - lk.p, ax) / L2;
        tt = tt < 0.0 ? 0.0 : (tt > 1.0 ? 1.0 : tt);
        const Vec3 X = lk.p + tt * ax;
        const double r = radiusAt(lk, tt, t.radius);
        const double d2 = norm2(c - X);
        if (d2 > S * S * r * r)
          continue;
        visitor.cover(k, d2, r);
      }
    }
}

} // namespace fiberpli
