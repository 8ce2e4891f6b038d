/// SectionReach: the box of the fibers that voxel columns of a section read (docs/pli-simulation.md
/// §6.3), the one rule behind the MPI tiles of the simulation (Core/PLI/PLIReach.h) and of the
/// ground truth (Core/Analysis/GroundTruth.h groundTruthReach).
#pragma once

#include "Model/TileReach.h"
#include "Section/PixelGrid.h"
#include "Section/SectionLattice.h"

namespace fiberpli
{

/// Columns `c` (global voxel indices, any sign) over every depth of the lattice, as µm, with the
/// radius scale S: buildLinkTable (Section/LinkTable.h) keeps a link when its bounding box grown by
/// S·r holds a voxel centre of the columns, so the box of those centres grown by one voxel holds
/// every link it keeps, whatever the rounding of either test. Empty columns read nothing.
TileReach columnsReach(const SectionLattice& lattice, const GridRange& c, double radiusScale);

} // namespace fiberpli
