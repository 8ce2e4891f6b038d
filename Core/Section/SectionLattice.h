/// SectionLattice: the voxel lattice of a simulated section (docs/pli-simulation.md §3.1), shared
/// by the simulation (Core/PLI) and the ground truth (Core/Analysis) so that both see the same
/// voxels.
#pragma once

#include <cstdint>

namespace fiberpli
{

/// Voxel (i, j, k) is [i, i+1) × [j, j+1) × [k, k+1) in voxel units from `origin` (µm); its
/// centre is origin + (i + ½, j + ½, k + ½)·voxel.
struct SectionLattice
{
  double origin[3] = { 0.0, 0.0, 0.0 }; ///< µm, lower corner of voxel (0, 0, 0)
  double voxel = 1.0;                   ///< µm, edge of a voxel
  std::int64_t n[3] = { 0, 0, 0 };      ///< voxels along x, y, z
};

} // namespace fiberpli
