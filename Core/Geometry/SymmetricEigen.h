/// SymmetricEigen: the one eigen-decomposition of a symmetric 3×3 matrix, for the orientation
/// tensors of the ground truth and the metrics (Analysis/OrientationTensor.h) and the principal
/// axis of a field's voxel (Field/FieldAgreement.h).
#pragma once

#include "Geometry/Vec3.h"

namespace fiberpli
{

/// Eigen-decomposition of a symmetric 3×3 matrix by cyclic Jacobi rotations: eigenvalues in
/// descending order, vectors[k] the unit eigenvector of values[k]. The sweeps (at most 50) stop
/// when the off-diagonal part is 0 or, with relativeStop > 0, when the sum of its squares is at
/// most relativeStop times that of the diagonal.
void symmetricEigen3(
  const double m[3][3], double values[3], Vec3 vectors[3], double relativeStop = 0.0);

} // namespace fiberpli
