/// Simulator: voxel-resolution image stacks of every view for a range of voxel columns
/// (docs/pli-simulation.md §3.5 column tiles, §4 propagation, §6.1 OpenMP). Tissue is voxelised per
/// tile (tile ± tilt halo, all depths) into a per-thread buffer and never stored whole.
#pragma once

#include "Model/FiberModel.h"
#include "PLI/PLITypes.h"
#include "Util/Progress.h"

#include <cstdint>
#include <vector>

namespace fiberpli
{
namespace pli
{

/// Bytes per voxel of the tile buffer (§3.4: owner key, then axis + label, in place).
constexpr std::size_t kTileBytesPerVoxel = 16;

struct SimResult
{
  Status status; ///< error, warnings, and aborted when progress asked to stop (out is then empty)
  bool emptySection = false; ///< no fiber voxel in the requested columns: background only
  bool overlap = false; ///< some voxel was reachable by two fibers (nearest won; no warning here)
  double voxeliseCpuSeconds = 0.0;  ///< summed over threads
  double propagateCpuSeconds = 0.0; ///< summed over threads
  std::int64_t voxelsVoxelised = 0; ///< including tile halos
  std::int64_t raySteps = 0;        ///< steps over all views and columns
  std::size_t estimatedBytes = 0;   ///< tile buffers + output stacks + links
};

/// Tilt halo of §3.5 for these views: ceil((n_z/2)·tan θ_max) + 2 (0/1 for untilted views).
std::int64_t tiltHalo(const SectionLattice& lattice, const std::vector<View>& views, Interp interp);

/// Voxel columns whose links the rays of `cols` read: the columns and, on the tilted sensor, the
/// columns of their stretched mid-plane images, grown by the tilt halo (the region of simulate's
/// link table, and of the fibers an MPI tile receives, PLIReach.h).
GridRange linkRegion(const SectionLattice& lattice, const SimParams& params,
  const std::vector<View>& views, const GridRange& cols);

/// Memory estimate (bytes) of simulate() for these arguments, without allocating.
double estimateSimulationBytes(const SectionLattice& lattice, const SimParams& params,
  const std::vector<View>& views, const GridRange& cols);

/// Empty string when lattice/params/views/cols can be simulated, else a message naming the option
/// (also when estimateSimulationBytes exceeds the memory budget, Util/MemoryBudget.h).
std::string validateSimulation(const SectionLattice& lattice, const SimParams& params,
  const std::vector<View>& views, const GridRange& cols);

/// Voxel-resolution intensities I_v(i, j, k) for the columns `cols` (global voxel indices; they may
/// lie outside [0, n) laterally) and every view: out[v] covers cols, nrho = params.rho.size().
/// Each column is computed by the same operations for any thread count, tile size or split, so
/// results are bitwise identical. progress is called between tile batches.
SimResult simulate(const FiberModel& model, const TissueSpec& spec, const SectionLattice& lattice,
  const SimParams& params, const std::vector<View>& views, const GridRange& cols,
  std::vector<Stack>& out, const ProgressFn& progress = {});

} // namespace pli
} // namespace fiberpli
