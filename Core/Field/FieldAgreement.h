/// FieldAgreement: how well a fiber model follows an orientation field (docs/field-source.md §4).
/// Per grid voxel (the grid point nearest a segment's midpoint) the fibers' local mean axis is the
/// principal axis of the length-weighted orientation tensor of the segments there; its angle to the
/// field's axis at that grid point, averaged over the voxels that hold segments and a non-empty
/// field, is the mean angular error.
#pragma once

#include "Field/OrientationField.h"
#include "Model/FiberModel.h"

#include <cstddef>

namespace fiberpli
{

struct FieldAgreement
{
  double meanErrorDegrees = 0.0; ///< mean over the voxels counted
  double maxErrorDegrees = 0.0;  ///< largest voxel error
  std::size_t voxels = 0;        ///< voxels with segments and a non-empty field
};

/// The agreement of the fibers of `bundle` (-1: all fibers) with `field`.
FieldAgreement fieldAgreement(
  const FiberModel& model, const OrientationField& field, int bundle = -1);

/// The unit eigenvector of the largest eigenvalue of the symmetric 3×3 matrix m (row-major).
Vec3 principalAxis(const double m[9]);

} // namespace fiberpli
