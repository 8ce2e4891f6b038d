/// PixelGrid: the camera pixels over a section lattice and the one voxel ↔ pixel mapping
/// (docs/pli-simulation.md §5.2) that the simulation's binning and the ground truth both use, and
/// the one rectangle type for pixel ranges and voxel-column ranges.
#pragma once

#include "Section/SectionLattice.h"

#include <cstdint>
#include <string>

namespace fiberpli
{

/// Half-open rectangle [i0, i1) × [j0, j1) of a 2-D index grid: pixels of an image (an MPI piece
/// or an UPDATE_EXTENT, pixel (i, j) has linear index i + nx·j) or global voxel columns of a
/// lattice.
struct GridRange
{
  std::int64_t i0 = 0, i1 = 0, j0 = 0, j1 = 0;
  std::int64_t nx() const { return i1 - i0; }
  std::int64_t ny() const { return j1 - j0; }
  std::int64_t count() const { return nx() * ny(); }
};

/// The whole nx × ny image.
inline GridRange wholeImage(std::int64_t nx, std::int64_t ny)
{
  return { 0, nx, 0, ny };
}

/// Empty string when nx, ny >= 0 and the range lies inside the image (an empty range is allowed),
/// else a message naming the offending bound.
std::string validatePixelRange(std::int64_t nx, std::int64_t ny, const GridRange& range);

/// Pixel of voxel index i for scale = VoxelSize/PixelSize: floor((i + ½)·scale) (§5.2).
std::int64_t pixelOfVoxel(std::int64_t i, double scale);
/// Number of pixels for n voxels: round(n·scale).
std::int64_t pixelCount(std::int64_t nVoxels, double scale);
/// Voxels [first, last) that bin into pixel p (empty past the image); voxels mapped past the last
/// pixel are dropped.
void voxelsOfPixel(
  std::int64_t p, double scale, std::int64_t nVoxels, std::int64_t& first, std::int64_t& last);

/// A lattice and the pixel size of its camera image (PixelSize >= VoxelSize).
struct PixelGrid
{
  SectionLattice lattice;
  double pixelSize = 1.0; ///< µm
  double scale() const { return lattice.voxel / pixelSize; }
};

/// Pixel counts nx × ny of a grid (n_px = round(n_vox·scale)). Returns "" or an error naming the
/// bad field (voxel or pixel size, negative counts, PixelSize < VoxelSize, origin not finite).
std::string checkPixelGrid(const PixelGrid& grid, std::int64_t& nx, std::int64_t& ny);

/// The voxel columns that bin into the pixels of `pixels` (a non-empty range inside the image).
GridRange voxelColumnsOf(const PixelGrid& grid, const GridRange& pixels);

} // namespace fiberpli
