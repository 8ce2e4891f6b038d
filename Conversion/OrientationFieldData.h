/**
 * @file OrientationFieldData.h
 * @brief a vtkImageData point array of 3-component vectors as a Core orientation field
 *
 * A point array lives on the image's grid (origin at its first point, its spacing and point
 * counts); a cell array on the grid of the cell centres (half a spacing inside, one point fewer
 * along every axis that has cells). The vectors are copied as doubles in VTK's order (x fastest)
 * and normalised (Field/OrientationField.h): zero vectors and vectors with a NaN or infinite
 * component are empty.
 */
#ifndef OrientationFieldData_h
#define OrientationFieldData_h

#include "Field/OrientationField.h"
#include "Util/MemoryBudget.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>

#include <string>

namespace fiberpli
{

/// Fills `field` from `image` and its point (or, with `cells`, cell) array `vectors`; returns "" or
/// a message naming the array and what is wrong (components, tuple count, a rotated image).
/// `notFinite` receives how many vectors were NaN or infinite.
inline std::string ToOrientationField(vtkImageData* image, vtkDataArray* vectors, bool cells,
  OrientationField& field, std::size_t& notFinite)
{
  const std::string name = vectors->GetName() ? vectors->GetName() : "(unnamed)";
  const std::string kind = cells ? "cell" : "point";
  if (vectors->GetNumberOfComponents() != 3)
  {
    return "the " + kind + " array '" + name + "' has " +
      std::to_string(vectors->GetNumberOfComponents()) +
      " components, an orientation field needs 3";
  }
  const vtkIdType expected = cells ? image->GetNumberOfCells() : image->GetNumberOfPoints();
  if (vectors->GetNumberOfTuples() != expected)
  {
    return "the " + kind + " array '" + name + "' has " +
      std::to_string(vectors->GetNumberOfTuples()) + " tuples for " + std::to_string(expected) +
      " " + kind + "s";
  }
  if (!image->GetDirectionMatrix()->IsIdentity())
  {
    return "the image is rotated (its direction matrix is not the identity); resample it onto an "
           "axis-aligned grid";
  }
  int dims[3];
  image->GetDimensions(dims);
  double first[3] = { 0.0, 0.0, 0.0 };
  if (image->GetNumberOfPoints() > 0)
  {
    image->GetPoint(0, first);
  }
  const double* spacing = image->GetSpacing();
  field.origin = { first[0], first[1], first[2] };
  field.spacing = { spacing[0], spacing[1], spacing[2] };
  field.dimensions = { dims[0], dims[1], dims[2] };
  if (cells)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (dims[a] > 1) // an axis of one point has no cells along it: its centres stay in the plane
      {
        field.origin[a] += 0.5 * spacing[a];
        field.dimensions[static_cast<std::size_t>(a)] = dims[a] - 1;
      }
    }
  }
  const vtkIdType n = vectors->GetNumberOfTuples();
  // The field is a double copy of the array: refuse one that cannot fit before allocating it.
  const std::string tooLarge = checkMemoryBudget(static_cast<double>(n) * sizeof(Vec3),
    "the orientation field of the " + kind + " array '" + name + "' (" + std::to_string(n) +
      " vectors)");
  if (!tooLarge.empty())
  {
    return tooLarge;
  }
  field.vectors.resize(static_cast<std::size_t>(n));
  double t[3];
  for (vtkIdType i = 0; i < n; ++i)
  {
    vectors->GetTuple(i, t);
    field.vectors[static_cast<std::size_t>(i)] = { t[0], t[1], t[2] };
  }
  notFinite = normalizeOrientationField(field);
  return {};
}

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: OrientationFieldData.h
