#include "Field/FieldAgreement.h"

#include "Geometry/SymmetricEigen.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace fiberpli
{

Vec3 principalAxis(const double m[9])
{
  const double a[3][3] = { { m[0], m[1], m[2] }, { m[3], m[4], m[5] }, { m[6], m[7], m[8] } };
  double values[3];
  Vec3 vectors[3];
  // Sweeps stop once the off-diagonal part is negligible against the diagonal (1e-30 of its
  // squares): a handful diagonalise the matrix to rounding.
  symmetricEigen3(a, values, vectors, 1e-30);
  return vectors[0];
}

FieldAgreement fieldAgreement(const FiberModel& model, const OrientationField& field, int bundle)
{
  // Orientation tensor Σ l·d·dᵀ per voxel (only voxels with segments are stored).
  std::unordered_map<std::size_t, std::array<double, 9>> tensors;
  for (const Fiber& fiber : model.fibers)
  {
    if (bundle >= 0 && fiber.bundle != bundle)
    {
      continue;
    }
    for (std::size_t s = 0; s + 1 < fiber.points.size(); ++s)
    {
      const Vec3 seg = fiber.points[s + 1] - fiber.points[s];
      const double l = norm(seg);
      const Vec3 mid = 0.5 * (fiber.points[s] + fiber.points[s + 1]);
      if (!(l > 0.0) || !field.contains(mid))
      {
        continue;
      }
      int ijk[3];
      for (int a = 0; a < 3; ++a)
      {
        ijk[a] = std::min(
          std::max(static_cast<int>(std::lround((mid[a] - field.origin[a]) / field.spacing[a])), 0),
          field.dimensions[a] - 1);
      }
      std::array<double, 9>& t =
        tensors.try_emplace(field.index(ijk[0], ijk[1], ijk[2])).first->second;
      const Vec3 d = seg / l;
      for (int i = 0; i < 3; ++i)
      {
        for (int j = 0; j < 3; ++j)
        {
          t[static_cast<std::size_t>(3 * i + j)] += l * d[i] * d[j];
        }
      }
    }
  }
  FieldAgreement result;
  double sum = 0.0;
  for (const auto& [index, t] : tensors)
  {
    const Vec3 f = field.vectors[index];
    if (!(norm2(f) > 0.0))
    {
      continue;
    }
    const Vec3 axis = principalAxis(t.data());
    const double c = std::min(1.0, std::fabs(dot(axis, f)));
    const double degrees = std::acos(c) * 180.0 / M_PI;
    sum += degrees;
    result.maxErrorDegrees = std::max(result.maxErrorDegrees, degrees);
    ++result.voxels;
  }
  result.meanErrorDegrees = result.voxels ? sum / static_cast<double>(result.voxels) : 0.0;
  return result;
}

} // namespace fiberpli
