/// OrientationField: a 3-D fiber orientation field on a regular grid (docs/field-source.md §2). One
/// axis per grid point, sign-free (v and −v are the same fiber orientation); a zero vector marks an
/// empty point (a mask: no fibers there). The region is the box spanned by the grid points.
#pragma once

#include "Geometry/Vec3.h"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace fiberpli
{

struct OrientationField
{
  Vec3 origin;                              ///< µm, position of grid point (0, 0, 0)
  Vec3 spacing{ 1.0, 1.0, 1.0 };            ///< µm, > 0 along every axis
  std::array<int, 3> dimensions{ 0, 0, 0 }; ///< grid points per axis, >= 2 each
  std::vector<Vec3> vectors;                ///< x fastest; unit vectors or zero (empty)

  std::size_t size() const
  {
    return static_cast<std::size_t>(dimensions[0]) * dimensions[1] * dimensions[2];
  }
  std::size_t index(int i, int j, int k) const
  {
    return (static_cast<std::size_t>(k) * dimensions[1] + j) * dimensions[0] + i;
  }
  /// The region's corners: the first and the last grid point.
  Vec3 lower() const { return origin; }
  Vec3 upper() const
  {
    return { origin.x + (dimensions[0] - 1) * spacing.x, origin.y + (dimensions[1] - 1) * spacing.y,
      origin.z + (dimensions[2] - 1) * spacing.z };
  }
  bool contains(const Vec3& p) const
  {
    const Vec3 lo = lower();
    const Vec3 hi = upper();
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
  }
};

/// Empty when the grid is usable (>= 2 points and a finite spacing > 0 along every axis, finite
/// origin, one vector per point), else a message naming what is wrong and its value.
std::string validateOrientationField(const OrientationField& field);

/// Makes every vector a unit vector; a vector that is zero or not finite becomes zero (empty).
/// Returns how many were not finite (NaN or infinite components), for the caller's warning.
std::size_t normalizeOrientationField(OrientationField& field);

/// "" for 3 or 6 components per grid point (one or two axes), else "has <n> components; an
/// orientation array needs 3 ... or 6 ..." (the caller puts the array's name in front).
std::string validateOrientationComponents(int components);

/// The populations of an orientation array with `components` values per grid point (x fastest,
/// `tuples` tuples, interleaved as VTK stores them) on the grid of `grid` (its origin, spacing and
/// dimensions; its vectors are not used): 3 components give one field, 6 give two populations
/// (axis 1 = components 0–2, axis 2 = components 3–5; a zero triple leaves that population empty
/// at that point), exactly the fields two 3-component arrays would give. Every field is normalised
/// (normalizeOrientationField); `notFinite` receives how many triples were NaN or infinite. Returns
/// "" or the reason: validateOrientationComponents's, or a tuple count unlike the grid's.
std::string orientationFieldsFromArray(const double* values, std::size_t tuples, int components,
  const OrientationField& grid, std::vector<OrientationField>& fields, std::size_t& notFinite);

/// The share of grid points that are not empty, in [0, 1].
double nonEmptyShare(const OrientationField& field);

/// The field's axis at p by trilinear interpolation. The non-empty corners are sign-aligned to
/// `reference` before they are averaged (a zero reference: to the corner of largest weight), so
/// opposite but equal axes never cancel. Empty (returns false) outside the region, where the
/// corners that are not empty carry less than half the weight (so the mask's edge lies halfway
/// between an empty and a full grid point), or where the aligned mean vanishes. `direction`
/// receives a unit vector with dot(direction, reference) >= 0.
bool fieldDirection(
  const OrientationField& field, const Vec3& p, const Vec3& reference, Vec3& direction);

/// True where fieldDirection finds an axis.
bool fieldIsFull(const OrientationField& field, const Vec3& p);

} // namespace fiberpli
