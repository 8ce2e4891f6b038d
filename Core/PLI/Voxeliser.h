/// Voxeliser: capsule fibers → layered tissue on the voxel lattice, one lateral block at a time
/// (docs/pli-simulation.md §3.3, §3.5). A block holds 16 bytes per voxel: while filling, the owner
/// key (d2 double, link id) and the label; afterwards the optic axis (3 × float) and the label.
#pragma once

#include "Model/FiberModel.h"
#include "PLI/PLITypes.h"
#include "Section/LinkTable.h"

#include <cstdint>
#include <vector>

namespace fiberpli
{
namespace pli
{

/// The link table of the tissue (Section/LinkTable.h) for the columns `region`: the slots are the
/// bundles of spec (fibers of other bundles are skipped and counted), S of a slot its largest layer
/// scale (§3.3), the radius taper spec.radius.
void tissueLinkTable(const FiberModel& model, const TissueSpec& spec, const SectionLattice& lattice,
  const GridRange& region, std::int64_t binSize, LinkTable& table);

/// Voxel data of the columns `cols` × [0, n_z) (global indices), z fastest in memory.
struct TissueBlock
{
  GridRange cols;
  std::int64_t nz = 0;
  std::vector<std::uint32_t> words; ///< 4 per voxel

  std::size_t index(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return static_cast<std::size_t>(((j - cols.j0) * cols.nx() + (i - cols.i0)) * nz + k);
  }
  bool contains(std::int64_t i, std::int64_t j) const
  {
    return i >= cols.i0 && i < cols.i1 && j >= cols.j0 && j < cols.j1;
  }
  std::int32_t label(std::int64_t i, std::int64_t j, std::int64_t k) const
  {
    return static_cast<std::int32_t>(words[4 * index(i, j, k) + 3]);
  }
  /// Optic axis after finalisation; (0,0,0) = no axis.
  void axis(std::int64_t i, std::int64_t j, std::int64_t k, float out[3]) const;
  void setVoxel(
    std::int64_t i, std::int64_t j, std::int64_t k, std::int32_t label, const float axis[3]);
  /// Sizes the buffer (reusing its capacity) for cols × nz, all voxels unowned.
  void reset(const GridRange& c, std::int64_t nzIn);
};

struct VoxeliseStats
{
  bool overlap = false; ///< a voxel was reachable by two different fibers (strands, LinkTable.h)
  std::int64_t labelled = 0; ///< voxels with label > 0 in the block
};

/// Fills `block` (already reset to its columns) from the candidate links: ownership by the rule of
/// Section/LinkTable.h (§3.3), then the optic axes (p: link direction, r: from the axis
/// to the voxel centre, b: none). With LateralOutside::Background, voxels outside the lateral
/// lattice stay label 0. The result does not depend on the block split or the link order.
/// `reach`, when given, lists per depth k the largest lateral distance (voxels) outside `core`
/// at which a ray of the core columns can read voxel k; voxels farther out are skipped (they stay
/// label 0 and are never read). This trims the tilt halo of §3.5 to the "bow-tie" the rays use.
struct HaloShape
{
  GridRange core;
  std::vector<std::int64_t> reach;
};
void voxeliseBlock(const LinkTable& table, const TissueSpec& spec, const SectionLattice& lattice,
  LateralOutside lateral, TissueBlock& block, VoxeliseStats& stats,
  const HaloShape* shape = nullptr);

/// Convenience for tests and field export: links for `cols`, then voxeliseBlock.
VoxeliseStats voxelise(const FiberModel& model, const TissueSpec& spec,
  const SectionLattice& lattice, const GridRange& cols, TissueBlock& block,
  LateralOutside lateral = LateralOutside::SampleFibers);

} // namespace pli
} // namespace fiberpli
