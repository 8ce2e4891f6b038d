#include "Field/OrientationField.h"

#include "Util/NumberFormat.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace fiberpli
{

std::string validateOrientationField(const OrientationField& f)
{
  static const char* const kAxis[3] = { "x", "y", "z" };
  for (int a = 0; a < 3; ++a)
  {
    if (f.dimensions[a] < 2)
    {
      return std::string("the field has ") + std::to_string(f.dimensions[a]) + " point(s) along " +
        kAxis[a] +
        ", needs at least 2 along every axis (a region of zero thickness holds no fiber volume)";
    }
    if (!(std::isfinite(f.spacing[a]) && f.spacing[a] > 0.0))
    {
      return std::string("the field's spacing along ") + kAxis[a] + " is " +
        formatNumber(f.spacing[a]) + ", must be > 0";
    }
  }
  if (!isFinite(f.origin))
  {
    return "the field's origin is not finite";
  }
  if (f.vectors.size() != f.size())
  {
    return "the field has " + std::to_string(f.vectors.size()) + " vectors for " +
      std::to_string(f.size()) + " grid points";
  }
  return {};
}

std::size_t normalizeOrientationField(OrientationField& f)
{
  std::size_t notFinite = 0;
  for (Vec3& v : f.vectors)
  {
    if (!isFinite(v))
    {
      ++notFinite;
      v = Vec3{};
      continue;
    }
    const double n = norm(v);
    v = n > 0.0 && std::isfinite(n) ? v / n : Vec3{};
  }
  return notFinite;
}

std::string validateOrientationComponents(int components)
{
  if (components == 3 || components == 6)
  {
    return {};
  }
  return "has " + std::to_string(components) +
    " components; an orientation array needs 3 (one axis per point) or 6 (two axes per point: "
    "components 0-2 and 3-5)";
}

std::string orientationFieldsFromArray(const double* values, std::size_t tuples, int components,
  const OrientationField& grid, std::vector<OrientationField>& fields, std::size_t& notFinite)
{
  fields.clear();
  notFinite = 0;
  const std::string badComponents = validateOrientationComponents(components);
  if (!badComponents.empty())
  {
    return badComponents;
  }
  if (tuples != grid.size())
  {
    return "has " + std::to_string(tuples) + " tuples for " + std::to_string(grid.size()) +
      " grid points";
  }
  const int populations = components / 3;
  for (int p = 0; p < populations; ++p)
  {
    OrientationField f;
    f.origin = grid.origin;
    f.spacing = grid.spacing;
    f.dimensions = grid.dimensions;
    f.vectors.resize(tuples);
    const double* v = values + 3 * p;
    for (std::size_t i = 0; i < tuples; ++i, v += components)
    {
      f.vectors[i] = { v[0], v[1], v[2] };
    }
    notFinite += normalizeOrientationField(f);
    fields.push_back(std::move(f));
  }
  return {};
}

double nonEmptyShare(const OrientationField& f)
{
  if (f.vectors.empty())
  {
    return 0.0;
  }
  const auto full =
    std::count_if(f.vectors.begin(), f.vectors.end(), [](const Vec3& v) { return norm2(v) > 0.0; });
  return static_cast<double>(full) / static_cast<double>(f.vectors.size());
}

bool fieldDirection(
  const OrientationField& f, const Vec3& p, const Vec3& reference, Vec3& direction)
{
  if (!f.contains(p))
  {
    return false;
  }
  int cell[3];
  double t[3];
  for (int a = 0; a < 3; ++a)
  {
    const double u = (p[a] - f.origin[a]) / f.spacing[a];
    cell[a] = std::min(std::max(static_cast<int>(std::floor(u)), 0), f.dimensions[a] - 2);
    t[a] = std::min(std::max(u - cell[a], 0.0), 1.0);
  }
  Vec3 corners[8];
  double weights[8];
  double fullWeight = 0.0;
  int heaviest = -1;
  for (int c = 0; c < 8; ++c)
  {
    const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    weights[c] = (di ? t[0] : 1.0 - t[0]) * (dj ? t[1] : 1.0 - t[1]) * (dk ? t[2] : 1.0 - t[2]);
    corners[c] = f.vectors[f.index(cell[0] + di, cell[1] + dj, cell[2] + dk)];
    if (norm2(corners[c]) > 0.0)
    {
      fullWeight += weights[c];
      if (heaviest < 0 || weights[c] > weights[heaviest])
      {
        heaviest = c;
      }
    }
  }
  if (heaviest < 0 || fullWeight < 0.5)
  {
    return false;
  }
  const Vec3 ref = norm2(reference) > 0.0 ? reference : corners[heaviest];
  Vec3 sum;
  for (int c = 0; c < 8; ++c)
  {
    sum += (dot(corners[c], ref) < 0.0 ? -weights[c] : weights[c]) * corners[c];
  }
  const double n = norm(sum);
  // The aligned corners are unit vectors within 90° of ref, so their mean is short only when they
  // spread over nearly a half-sphere: no usable axis there.
  if (!(n > 1e-6 * fullWeight))
  {
    return false;
  }
  direction = sum / n;
  if (dot(direction, ref) < 0.0)
  {
    direction = -direction;
  }
  return true;
}

bool fieldIsFull(const OrientationField& f, const Vec3& p)
{
  Vec3 d;
  return fieldDirection(f, p, Vec3{}, d);
}

} // namespace fiberpli
