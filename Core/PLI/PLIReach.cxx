#include "PLI/PLIReach.h"

#include "PLI/Simulator.h"

#include <algorithm>

namespace fiberpli
{
namespace pli
{

namespace
{
// Voxel columns [i0, i1) × [j0, j1) and every depth, as µm: buildLinkTable keeps a link when its
// grown box holds a voxel centre of the region, so the box of the centres grown by one voxel
// holds every link it keeps, whatever the rounding of either test.
TileReach columnsReach(const PLIPlan& plan, const ColumnRange& c)
{
  TileReach r;
  const Lattice& lat = plan.lattice;
  const std::int64_t lo[3] = { c.i0, c.j0, 0 }, hi[3] = { c.i1, c.j1, lat.n[2] };
  for (int a = 0; a < 3; ++a)
  {
    r.box[2 * a] = lat.origin[a] + (static_cast<double>(lo[a]) - 0.5) * lat.voxel;
    r.box[2 * a + 1] = lat.origin[a] + (static_cast<double>(hi[a]) + 0.5) * lat.voxel;
  }
  r.radiusScale = 0.0;
  for (const std::vector<Layer>& layers : plan.tissue.layers)
    for (const Layer& l : layers)
      r.radiusScale = std::max(r.radiusScale, l.scale);
  if (r.radiusScale == 0.0)
    r.radiusScale = 1.0;
  if (c.nx() < 1 || c.ny() < 1 || lat.n[2] < 1)
    r.box[0] = 1, r.box[1] = -1;
  return r;
}
} // namespace

TileReach imageReach(const PLIPlan& plan, const PLIOptions& options, const PixelRange& px)
{
  if (px.nx() < 1 || px.ny() < 1)
    return TileReach();
  const ColumnRange cols = voxelColumnsFor(plan, options, px);
  return columnsReach(plan, linkRegion(plan.lattice, simParams(plan, options), plan.views, cols));
}

TileReach tissueReach(const PLIPlan& plan, const VoxelBox& box)
{
  if (box.count() <= 0)
    return TileReach();
  return columnsReach(plan, ColumnRange{ box.lo[0], box.hi[0], box.lo[1], box.hi[1] });
}

} // namespace pli
} // namespace fiberpli
