/// SectionPlan: the one planning of a simulated section (docs/pli-simulation.md §3.1, §5.2) from
/// the properties VolumeOfInterest, VoxelSize and PixelSize that PLISimulation and
/// FiberOrientationGroundTruth share: the voxel lattice, the pixel grid and the image geometry.
/// Both filters call planSection, so their images always have the same pixels.
#pragma once

#include "Geometry/Vec3.h"
#include "Model/FiberModel.h"
#include "Section/PixelGrid.h"

#include <cstdint>
#include <string>

namespace fiberpli
{

struct SectionPlan : PixelGrid
{
  std::int64_t pixels[2] = { 0, 0 };   ///< whole image n_px × n_py
  double imageOrigin[3] = { 0, 0, 0 }; ///< centre of pixel (0, 0) at the section's mid-plane, µm
  double thickness = 0.0;              ///< n_z·VoxelSize, µm
};

/// "" when VoxelSize > 0 and PixelSize >= VoxelSize (both finite), else the error naming the
/// property.
std::string checkSectionSizes(double voxelSize, double pixelSize);

/// Plans the section of the properties (sizes in µm): checks the sizes, resolves
/// the volume of interest (min > max on every axis = the model's bounds, Model/VolumeOfInterest.h)
/// into the lattice, and derives the pixel grid and image geometry. Returns "" or the error naming
/// the property (also when PixelSize leaves no pixel).
std::string planSection(const FiberModel& model, const double volumeOfInterest[6], double voxelSize,
  double pixelSize, SectionPlan& plan);

/// A grid whose pixels are exactly the nx × ny grid with lower corner `corner` (x, y) and the given
/// pixel size, sampled by samplesPerPixel² voxel columns per pixel over z ∈ [zMin, zMax]
/// (nz = max(1, round((zMax − zMin)/voxel)) voxels). For the ground truth of a grid that does not
/// come from PLISimulation.
PixelGrid latticeForPixelGrid(const Vec3& corner, double pixelSize, std::int64_t nx,
  std::int64_t ny, double zMin, double zMax, int samplesPerPixel);

} // namespace fiberpli
