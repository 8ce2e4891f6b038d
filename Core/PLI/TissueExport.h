/// TissueExport: the voxelised tissue of a sub-volume as whole arrays (label and optic axis per
/// voxel), for looking at what a simulation sees. It runs exactly the simulation's column code
/// (tissueLinkTable + voxeliseBlock of Voxeliser.h) on the columns of the box, so every voxel
/// equals the one the rays read; there is no second voxeliser.
#pragma once

#include "Model/FiberModel.h"
#include "PLI/PLIPipeline.h"
#include "Util/Progress.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{
namespace pli
{

/// Half-open voxel index box [i0,i1)×[j0,j1)×[k0,k1) of the plan's lattice.
struct VoxelBox
{
  std::int64_t lo[3] = { 0, 0, 0 };
  std::int64_t hi[3] = { 0, 0, 0 };
  std::int64_t count() const { return (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]); }
};

/// Voxels whose centres lie in the box (µm: xmin xmax ymin ymax zmin zmax); min > max on every
/// axis = the whole lattice. Errors: NaN, min > max on some axes only, no voxel centre inside.
Status tissueBox(const PLIPlan& plan, const double box[6], VoxelBox& out);

/// Bytes exportTissue allocates for the box (one tile buffer and the output arrays).
double tissueExportBytes(const PLIPlan& plan, const PLIOptions& options, const VoxelBox& box);

/// "" when the box fits the memory budget, else the message naming TissueVolume and the fix.
std::string checkTissueBudget(const PLIPlan& plan, const PLIOptions& options, const VoxelBox& box);

struct TissueVolume
{
  VoxelBox box;
  std::vector<std::int32_t> label; ///< per voxel, x fastest, then y, then z; 0 = embedding medium
  std::vector<float> axis;         ///< 3 per voxel, unit or (0, 0, 0) where there is no axis
};

/// Voxelises `box` of the plan (from planPLI) like the simulation. Refuses boxes above the memory
/// budget (checkMemoryBudget) before allocating. Labels are 1 + b·L + l for layer l of bundle
/// slot b (plan.tissue: sorted bundle ids, L = maxLayers()). progress is called between column
/// tiles of options.tileSize; when it returns false the export stops (the Status is aborted, the
/// arrays empty).
Status exportTissue(const FiberModel& model, const PLIPlan& plan, const PLIOptions& options,
  const VoxelBox& box, TissueVolume& out, const ProgressFn& progress = {});

} // namespace pli
} // namespace fiberpli
