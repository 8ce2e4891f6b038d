/// PeriodicTiling: the copies of a periodic cell's fibers that a box larger than the cell needs
/// (a solved periodic cell tiles space: its fibers continue through the faces).
#pragma once

#include "Geometry/PeriodicCell.h"
#include "Model/FiberModel.h"

#include <string>

namespace fiberpli
{

/// Replaces model by every lattice translate (integer multiples of the cell's edges) of every
/// fiber whose bounds, grown by its radii, overlap box (xmin xmax ymin ymax zmin zmax). Translates
/// keep bundle and order (fiber by fiber, translates in x, then y, then z order); the untranslated
/// fiber keeps its id, a translate gets id + copy · (largest id + 1). Returns an error and leaves
/// the model unchanged when the copies would exceed the memory budget.
std::string tileModel(FiberModel& model, const PeriodicCell& cell, const double box[6]);

} // namespace fiberpli
