/// PLIReach: the fibers one piece of PLISimulation reads (docs/pli-simulation.md §6.3), as a
/// TileReach: under MPI a rank receives only the fibers that reach its piece.
#pragma once

#include "Model/TileReach.h"
#include "PLI/PLIPipeline.h"
#include "PLI/TissueExport.h"

namespace fiberpli
{
namespace pli
{

/// The pixels `px` of the image: the link region of their voxel columns (blur halo, tilt halo,
/// the tilted sensor's stretch; Simulator.h linkRegion) over the section's depth, grown by one
/// voxel against rounding, with the largest layer scale of the plan's tissue.
TileReach imageReach(const PLIPlan& plan, const PLIOptions& options, const GridRange& px);

/// The voxels `box` of the tissue export (their own columns, all depths, grown by one voxel).
TileReach tissueReach(const PLIPlan& plan, const VoxelBox& box);

} // namespace pli
} // namespace fiberpli
