#include "Field/FieldAgreement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

namespace fiberpli
{

Vec3 principalAxis(const double m[9])
{
  // Cyclic Jacobi rotations: a handful of sweeps diagonalise a 3×3 symmetric matrix to rounding.
  double a[3][3];
  double v[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      a[i][j] = m[3 * i + j];
    }
  }
  for (int sweep = 0; sweep < 50; ++sweep)
  {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    if (off <= 1e-30 * (a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2]) || off == 0.0)
    {
      break;
    }
    for (int p = 0; p < 2; ++p)
    {
      for (int q = p + 1; q < 3; ++q)
      {
        if (a[p][q] == 0.0)
        {
          continue;
        }
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t =
          (theta >= 0.0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0);
        const double s = t * c;
        for (int k = 0; k < 3; ++k) // A ← A·J
        {
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) // A ← Jᵀ·A
        {
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) // V ← V·J
        {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  int best = 0;
  for (int i = 1; i < 3; ++i)
  {
    if (a[i][i] > a[best][best])
    {
      best = i;
    }
  }
  return normalized(Vec3{ v[0][best], v[1][best], v[2][best] });
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
