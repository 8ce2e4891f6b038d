#include "PLI/TissueExport.h"

#include "PLI/Simulator.h"
#include "PLI/Voxeliser.h"
#include "Util/MemoryBudget.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fiberpli
{
namespace pli
{

Status tissueBox(const PLIPlan& plan, const double box[6], VoxelBox& out)
{
  Status st;
  out = VoxelBox();
  const SectionLattice& lat = plan.lattice;
  const bool whole = box[0] > box[1] && box[2] > box[3] && box[4] > box[5];
  const char* axisName[3] = { "x", "y", "z" };
  for (int a = 0; a < 3; ++a)
  {
    if (whole)
    {
      out.hi[a] = lat.n[a];
      continue;
    }
    std::ostringstream m;
    if (!std::isfinite(box[2 * a]) || !std::isfinite(box[2 * a + 1]) ||
      !(box[2 * a] <= box[2 * a + 1]))
    {
      m << "TissueVolume " << axisName[a] << " range [" << box[2 * a] << ", " << box[2 * a + 1]
        << "] must have min <= max (or min > max on every axis for the whole VolumeOfInterest)";
      st.error = m.str();
      return st;
    }
    // Voxel k has its centre at origin + (k + ½)·voxel.
    const double lo = std::ceil((box[2 * a] - lat.origin[a]) / lat.voxel - 0.5);
    const double hi = std::floor((box[2 * a + 1] - lat.origin[a]) / lat.voxel - 0.5) + 1.0;
    out.lo[a] = static_cast<std::int64_t>(std::clamp(lo, 0.0, static_cast<double>(lat.n[a])));
    out.hi[a] = static_cast<std::int64_t>(std::clamp(hi, 0.0, static_cast<double>(lat.n[a])));
    if (out.hi[a] <= out.lo[a])
    {
      m << "TissueVolume " << axisName[a] << " range [" << box[2 * a] << ", " << box[2 * a + 1]
        << "] holds no voxel centre of the VolumeOfInterest";
      st.error = m.str();
      return st;
    }
  }
  return st;
}

namespace
{
/// Columns of one export tile: the simulation's tile size, so a tile buffer is no larger than one
/// of the simulation's.
std::int64_t tileSide(const PLIOptions& options)
{
  return std::max(1, options.tileSize);
}
} // namespace

double tissueExportBytes(const PLIPlan& plan, const PLIOptions& options, const VoxelBox& box)
{
  const double B = static_cast<double>(tileSide(options));
  const double tile = std::min(B, static_cast<double>(box.hi[0] - box.lo[0])) *
    std::min(B, static_cast<double>(box.hi[1] - box.lo[1]));
  const double block = tile * static_cast<double>(plan.lattice.n[2]) * kTileBytesPerVoxel;
  const double arrays =
    static_cast<double>(box.count()) * (sizeof(std::int32_t) + 3 * sizeof(float));
  return block + arrays;
}

std::string checkTissueBudget(const PLIPlan& plan, const PLIOptions& options, const VoxelBox& box)
{
  std::ostringstream what;
  what << "TissueVolume of " << box.hi[0] - box.lo[0] << " x " << box.hi[1] - box.lo[1] << " x "
       << box.hi[2] - box.lo[2] << " voxels";
  const std::string err = checkMemoryBudget(tissueExportBytes(plan, options, box), what.str());
  return err.empty() ? err : err + ": choose a smaller TissueVolume or a larger VoxelSize";
}

Status exportTissue(const FiberModel& model, const PLIPlan& plan, const PLIOptions& options,
  const VoxelBox& box, TissueVolume& out, const ProgressFn& progress)
{
  Status st;
  out = TissueVolume();
  st.error = checkTissueBudget(plan, options, box);
  if (!st.ok())
    return st;
  out.box = box;
  if (box.count() <= 0)
    return st;
  // The same link table and block fill as a simulation tile, one tile of columns at a time (for
  // progress and abort); every tile spans all depths because a voxel's owner does not depend on
  // the block (Voxeliser.h), so the tiling and the crop in z are exact.
  const std::int64_t B = tileSide(options);
  const GridRange cols{ box.lo[0], box.hi[0], box.lo[1], box.hi[1] };
  LinkTable table;
  tissueLinkTable(model, plan.tissue, plan.lattice, cols, B, table);
  const std::size_t n = static_cast<std::size_t>(box.count());
  out.label.resize(n);
  out.axis.resize(3 * n);
  const std::int64_t nx = cols.nx(), ny = cols.ny();
  const std::int64_t tilesX = (nx + B - 1) / B, tilesY = (ny + B - 1) / B;
  TissueBlock block;
  for (std::int64_t t = 0; t < tilesX * tilesY; ++t)
  {
    if (!reportProgress(progress, static_cast<double>(t) / static_cast<double>(tilesX * tilesY)))
    {
      out = TissueVolume();
      st.aborted = true; // the arrays are empty
      return st;
    }
    const std::int64_t i0 = cols.i0 + (t % tilesX) * B, j0 = cols.j0 + (t / tilesX) * B;
    const GridRange tile{ i0, std::min(cols.i1, i0 + B), j0, std::min(cols.j1, j0 + B) };
    block.reset(tile, plan.lattice.n[2]);
    VoxeliseStats vs;
    voxeliseBlock(table, plan.tissue, plan.lattice, options.lateralOutside, block, vs);
    for (std::int64_t k = box.lo[2]; k < box.hi[2]; ++k)
      for (std::int64_t j = tile.j0; j < tile.j1; ++j)
        for (std::int64_t i = tile.i0; i < tile.i1; ++i)
        {
          const std::size_t p =
            static_cast<std::size_t>(((k - box.lo[2]) * ny + (j - cols.j0)) * nx + (i - cols.i0));
          out.label[p] = block.label(i, j, k);
          block.axis(i, j, k, &out.axis[3 * p]);
        }
  }
  reportProgress(progress, 1.0);
  return st;
}

} // namespace pli
} // namespace fiberpli
