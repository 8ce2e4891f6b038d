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
  const Lattice& lat = plan.lattice;
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
    if (!std::isfinite(box[2 * a]) || !std::isfinite(box[2 * a + 1]) || !(box[2 * a] <= box[2 * a + 1]))
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

double tissueExportBytes(const PLIPlan& plan, const VoxelBox& box)
{
  const double columns = static_cast<double>(box.hi[0] - box.lo[0]) * static_cast<double>(box.hi[1] - box.lo[1]);
  const double block = columns * static_cast<double>(plan.lattice.n[2]) * kTileBytesPerVoxel;
  const double arrays = static_cast<double>(box.count()) * (sizeof(std::int32_t) + 3 * sizeof(float));
  return block + arrays;
}

std::string checkTissueBudget(const PLIPlan& plan, const VoxelBox& box)
{
  std::ostringstream what;
  what << "TissueVolume of " << box.hi[0] - box.lo[0] << " x " << box.hi[1] - box.lo[1] << " x "
       << box.hi[2] - box.lo[2] << " voxels";
  const std::string err = checkMemoryBudget(tissueExportBytes(plan, box), what.str());
  return err.empty() ? err : err + ": choose a smaller TissueVolume or a larger VoxelSize";
}

Status exportTissue(const FiberModel& model, const PLIPlan& plan, const PLIOptions& options, const VoxelBox& box,
  TissueVolume& out)
{
  Status st;
  out = TissueVolume();
  st.error = checkTissueBudget(plan, box);
  if (!st.ok())
    return st;
  out.box = box;
  if (box.count() <= 0)
    return st;
  // The same link table and block fill as a simulation tile; the block spans all depths because
  // a voxel's owner does not depend on the block (Voxeliser.h), so the crop in z is exact.
  const ColumnRange cols{ box.lo[0], box.hi[0], box.lo[1], box.hi[1] };
  TissueBlock block;
  voxelise(model, plan.tissue, plan.lattice, cols, block, options.lateralOutside);
  const std::size_t n = static_cast<std::size_t>(box.count());
  out.label.resize(n);
  out.axis.resize(3 * n);
  std::size_t p = 0;
  for (std::int64_t k = box.lo[2]; k < box.hi[2]; ++k)
    for (std::int64_t j = box.lo[1]; j < box.hi[1]; ++j)
      for (std::int64_t i = box.lo[0]; i < box.hi[0]; ++i, ++p)
      {
        out.label[p] = block.label(i, j, k);
        block.axis(i, j, k, &out.axis[3 * p]);
      }
  return st;
}

} // namespace pli
} // namespace fiberpli
