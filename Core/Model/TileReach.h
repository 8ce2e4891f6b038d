/// TileReach: which fibers one tile of an image reads (docs/pli-simulation.md §6.3). Under MPI
/// every rank computes one tile; it receives exactly the fibers that reach the tile's box, in the
/// model's order, instead of the whole model. The rule is conservative (a fiber that reaches the
/// box may still own no voxel of the tile), never the other way round: a fiber that is left out
/// cannot own a voxel the tile reads, so the tile equals the crop of the one-process result.
#pragma once

#include "Geometry/PeriodicCell.h"
#include "Model/FiberModel.h"

namespace fiberpli
{

struct TileReach
{
  /// µm, xmin xmax ymin ymax zmin zmax; min > max on an axis = the tile reads no fiber.
  double box[6] = { 1, -1, 1, -1, 1, -1 };
  /// A link reaches the box when its bounding box, grown by radiusScale × its larger radius,
  /// overlaps it (radiusScale = the largest layer scale of the tissue, §3.2).
  double radiusScale = 1.0;
  /// A periodic cell (PeriodicTiling.h): the fiber stands for its lattice translates that
  /// tileModel puts into `tiling`, and it reaches when one of them does.
  bool periodic = false;
  PeriodicCell cell;
  double tiling[6] = { 1, -1, 1, -1, 1, -1 };

  bool empty() const { return !(box[0] <= box[1] && box[2] <= box[3] && box[4] <= box[5]); }
};

/// The smallest box holding both (the larger radius scale); the periodic fields of `a` are kept.
TileReach unite(const TileReach& a, const TileReach& b);

/// Whether some link of `fiber`, translated by `shift`, reaches the box (periodic is ignored).
bool linkReaches(const Fiber& fiber, const TileReach& reach, const Vec3& shift = Vec3{ 0, 0, 0 });

/// The exchange rule: linkReaches, or for a periodic reach whether one translate of the tiling
/// does (an interval test per link, not a loop over the translates).
bool fiberReaches(const Fiber& fiber, const TileReach& reach);

} // namespace fiberpli
