#include "PLI/PLIReach.h"

#include "PLI/Simulator.h"
#include "Section/SectionReach.h"

#include <algorithm>

namespace fiberpli
{
namespace pli
{

namespace
{
// The largest layer scale of the tissue (1 without layers): the links' growth in buildLinkTable.
double largestScale(const PLIPlan& plan)
{
  double S = 0.0;
  for (const std::vector<Layer>& layers : plan.tissue.layers)
    for (const Layer& l : layers)
      S = std::max(S, l.scale);
  return S > 0.0 ? S : 1.0;
}
} // namespace

TileReach imageReach(const PLIPlan& plan, const PLIOptions& options, const GridRange& px)
{
  if (px.nx() < 1 || px.ny() < 1)
    return TileReach();
  const GridRange cols = voxelColumnsFor(plan, options, px);
  return columnsReach(plan.lattice,
    linkRegion(plan.lattice, simParams(plan, options), plan.views, cols), largestScale(plan));
}

TileReach tissueReach(const PLIPlan& plan, const VoxelBox& box)
{
  if (box.count() <= 0)
    return TileReach();
  return columnsReach(
    plan.lattice, GridRange{ box.lo[0], box.hi[0], box.lo[1], box.hi[1] }, largestScale(plan));
}

} // namespace pli
} // namespace fiberpli
