/// AxisSampler: the optic axis at a continuous ray position (docs/pli-simulation.md §4.5): nearest
/// voxel, or label-aware trilinear Lerp/Slerp over the 8 surrounding voxel centres.
#pragma once

#include "PLI/PLITypes.h"
#include "PLI/Voxeliser.h"

namespace fiberpli
{
namespace pli
{

/// Axis at p (voxel units, global) for label = label(floor(p)) > 0. `clamp` bounds the lateral
/// stencil (the stored block, or the lattice for LateralOutside::Background); z is clamped to
/// [0, n_z). Neighbours with another label or a zero axis are missing; the result is normalised.
/// Returns false when no axis exists (all missing): the step is then isotropic.
bool sampleAxis(const TissueBlock& block, const double p[3], std::int32_t label, Interp interp,
  const GridRange& clamp, double out[3]);

} // namespace pli
} // namespace fiberpli
