/// OrientationTensor: per-pixel summary of fiber axes (docs/pli-analysis.md §5). Accumulates the
/// tensor M = (1/n_t)·Σ e·eᵀ of the tissue voxels' axes, the tissue fraction and the
/// direction × |inclination| histogram; the mean axis is the principal eigenvector of M (Jacobi).
#pragma once

#include "Geometry/SymmetricEigen.h" // symmetricEigen3
#include "Geometry/Vec3.h"

#include <cstdint>
#include <vector>

namespace fiberpli
{

/// Ground truth of one pixel (§5); angles in radians.
struct PixelTruth
{
  double fraction;          ///< n_t / n_all (NaN when the pixel has no voxel at all)
  double direction;         ///< φ(e1) in [0, π); NaN when n_t = 0
  double inclination;       ///< |α(e1)| in [0, π/2]
  double inclinationSigned; ///< α(e1) of the canonical e1, [−π/2, π/2]
  double anisotropy;        ///< λ1 − λ2 of M (0 = no dominant axis)
};

class TruthAccumulator
{
public:
  /// Histogram of nPhi direction bins over [0°, 180°) × nAlpha |inclination| bins over [0°, 90°].
  explicit TruthAccumulator(int nPhi = 18, int nAlpha = 9);

  void reset();
  /// A voxel without tissue (label 0): counts in n_all only.
  void addBackground(std::int64_t count = 1) { nAll_ += count; }
  /// A tissue voxel with fiber axis e (any sign, any non-zero length).
  void addTissue(const Vec3& axis);

  /// The pixel's truth. histogram (nPhi·nAlpha values, component iα·nPhi + iφ, fractions of the
  /// tissue voxels; all 0 when n_t = 0) is written when not null.
  PixelTruth result(double* histogram) const;

private:
  int nPhi_, nAlpha_;
  std::int64_t nAll_ = 0, nT_ = 0;
  double m_[3][3] = {};
  std::vector<std::int64_t> counts_;
};

} // namespace fiberpli
