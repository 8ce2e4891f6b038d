/// VolumeOfInterest: the section of PLISimulation and FiberOrientationGroundTruth (the same
/// property on both, checked by this one function so that both accept and refuse the same values):
/// xmin xmax ymin ymax zmin zmax in µm; min > max on every axis means the model's bounds (radii
/// included). Any other axis with min >= max, or a bound that is not finite, is an error.
#pragma once

#include "Model/FiberModel.h"

#include <cstdint>
#include <string>

namespace fiberpli
{

/// min > max on all three axes: "use the input's bounds".
bool isBoundsSentinel(const double voi[6]);

/// Resolves the sentinel to the model's bounds (radii included) and checks every axis: finite,
/// min < max, and round(extent / voxelSize) voxels in 1 .. 1e9. Fills `resolved` and the voxel
/// counts `n`; returns "" or an error naming VolumeOfInterest, the axis and the values. voxelSize
/// must be > 0 (checked by the caller, which names its own property).
std::string resolveVolumeOfInterest(const double voi[6], const FiberModel& model, double voxelSize,
  double resolved[6], std::int64_t n[3]);

} // namespace fiberpli
