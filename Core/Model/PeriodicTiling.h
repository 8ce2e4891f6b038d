/// PeriodicTiling: the copies of a periodic cell's fibers that a box larger than the cell needs
/// (a solved periodic cell tiles space: its fibers continue through the faces).
#pragma once

#include "Geometry/PeriodicCell.h"
#include "Model/FiberModel.h"
#include "Model/TileReach.h"

#include <string>

namespace fiberpli
{

/// Replaces model by every lattice translate (integer multiples of the cell's edges) of every
/// fiber whose bounds, grown by its radii, overlap box (xmin xmax ymin ymax zmin zmax). Translates
/// keep bundle and order (fiber by fiber, translates in x, then y, then z order); the untranslated
/// fiber keeps its id, a translate gets id + copy · (largest id + 1). Returns an error and leaves
/// the model unchanged when the copies would exceed the memory budget.
/// With `reach` (one MPI tile, TileReach.h) only the translates whose links reach it are made,
/// in the same order: the part of the whole tiling that the tile reads (their ids are unique but
/// not those of the whole tiling; the image does not depend on ids).
std::string tileModel(FiberModel& model, const PeriodicCell& cell, const double box[6],
  const TileReach* reach = nullptr);

/// The one rule by which a section honours a periodic cell, shared by PLISimulation and
/// FiberOrientationGroundTruth so that their pixels see the same tissue: the section's volume of
/// interest `volume` is filled with the lattice translates of the cell's fibers (tileModel into
/// `volume`; under MPI with the tile's `reach`, which sectionTiling made periodic first).
/// Returns tileModel's error.
std::string tileSection(FiberModel& model, const PeriodicCell& cell, const double volume[6],
  const TileReach* reach = nullptr);

/// Makes a tile's reach periodic for tileSection(…, cell, volume, &reach): the fiber stands for
/// its translates into `volume`, and reaches the tile when one of them does.
void sectionTiling(TileReach& reach, const PeriodicCell& cell, const double volume[6]);

/// Whether one translate that tileModel(…, reach.cell, reach.tiling) makes of `fiber` has a link
/// reaching reach.box: per link an interval of lattice shifts per axis, intersected with the
/// tiling's, so the cost does not grow with the number of translates.
bool periodicTranslateReaches(const Fiber& fiber, const TileReach& reach);

} // namespace fiberpli
