/// GroundTruth: orientation ground truth of a fiber model on the pixel grid of a simulated
/// section (docs/pli-analysis.md §5). Voxel centres of the simulation lattice get the fiber axis
/// unit(Q − P) of the link that owns them by the one ownership rule of the simulation
/// (Section/LinkTable.h, docs/pli-simulation.md §3.3, in the same voxel units: the owner of every
/// voxel is the voxeliser's); voxels bin into pixels by the mapping of Section/PixelGrid.h
/// (docs/pli-simulation.md §5.2, all z), and each pixel summarises its voxels with TruthAccumulator
/// (tensor mean axis, anisotropy, tissue fraction, histogram).
#pragma once

#include "Analysis/OrientationTensor.h"
#include "Model/FiberModel.h"
#include "Model/TileReach.h"
#include "Section/PixelGrid.h"
#include "Section/SectionPlan.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

struct GroundTruthOptions
{
  double radiusScale = 1.0; ///< S = largest layer scale: tissue where d <= S·r
  bool maxRadius = false;   ///< RadiusModel Max (max(r_P, r_Q)) instead of the Linear taper
  bool histogram = false;   ///< per-pixel histograms (nPhi·nAlpha doubles per pixel, off: the
                            ///< filter does not output them and 162 doubles per pixel are large)
  int nPhi = 18;            ///< histogram direction bins over [0°, 180°)
  int nAlpha = 9;           ///< histogram |inclination| bins over [0°, 90°]
  int threads = 0;          ///< OpenMP threads, 0 = all
};

/// Per-pixel truth maps on the pixel grid of the lattice (x fastest). Angles in radians.
struct GroundTruthMaps
{
  std::int64_t nx = 0, ny = 0; ///< round(n_vox·VoxelSize/PixelSize)
  std::vector<double> fraction, direction, inclination, inclinationSigned, anisotropy;
  std::vector<double>
    histogram; ///< nPhi·nAlpha values per pixel, pixel-major; empty unless requested
};

/// Ground truth of the pixels in `range` (pixel indices of checkPixelGrid, Section/PixelGrid.h; the
/// grid of a PLISimulation comes from planSection, Section/SectionPlan.h). The maps are
/// resized to the whole grid; pixels outside the range keep their values (NaN / 0 when new).
/// Result is bit-identical for any thread count. The Status error: invalid model (the
/// validateModel message); bad lattice/options/range; more than 2^31 voxels in one pixel row;
/// more memory than the budget of Util/MemoryBudget.h, checked before allocating. aborted:
/// progress asked to stop.
Status computeGroundTruth(const FiberModel& model, const PixelGrid& grid,
  const GroundTruthOptions& options, const GridRange& range, GroundTruthMaps& maps,
  const ProgressFn& progress = {});

/// The fibers the pixels `range` read (docs/pli-simulation.md §6.3): the voxel columns that bin
/// into them over every depth (Section/SectionReach.h), with the options' radius scale.
TileReach groundTruthReach(
  const PixelGrid& grid, const GroundTruthOptions& options, const GridRange& range);

/// Whole-model orientation histogram (fastPLI orientation.py): every link (φ = atan2(dy, dx),
/// θ = arccos(dz/|d|), antipode when θ > 90°) counted in nPhi bins over φ ∈ [0°, 360°) × nTheta
/// bins over θ ∈ [0°, 90°]; component iθ·nPhi + iφ. normalise: divide by the sum (so it sums to
/// 1); perSolidAngle additionally divides each bin by (cos θ_lo − cos θ_hi)·Δφ (Δφ in radians).
/// Zero-length links are skipped. Empty vector when nPhi or nTheta < 1.
std::vector<double> modelOrientationHistogram(
  const FiberModel& model, int nPhi, int nTheta, bool normalise, bool perSolidAngle);

} // namespace fiberpli
