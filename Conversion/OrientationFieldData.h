/**
 * @file OrientationFieldData.h
 * @brief a vtkImageData point or cell array of fiber axes as Core orientation fields
 *
 * A point array lives on the image's grid (origin at its first point, its spacing and point
 * counts); a cell array on the grid of the cell centres (half a spacing inside, one point fewer
 * along every axis that has cells). A 3-component array is one field, a 6-component array two
 * (one per population: components 0–2 and 3–5, Field/OrientationField.h
 * orientationFieldsFromArray). The vectors are copied as doubles in VTK's order (x fastest) and
 * normalised: zero vectors and vectors with a NaN or infinite component are empty.
 */
#ifndef OrientationFieldData_h
#define OrientationFieldData_h

#include "ArrayValues.h"
#include "Field/OrientationField.h"
#include "Util/MemoryBudget.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>

#include <string>
#include <vector>

namespace fiberpli
{

/// Appends to `fields` the field(s) of `image`'s point (or, with `cells`, cell) array `vectors`:
/// one for 3 components, two for 6. Returns "" or a message naming the array and what is wrong
/// (components, tuple count, a rotated image, the memory budget). `notFinite` receives how many
/// axes were NaN or infinite.
inline std::string ToOrientationFields(vtkImageData* image, vtkDataArray* vectors, bool cells,
  std::vector<OrientationField>& fields, std::size_t& notFinite)
{
  const std::string name = vectors->GetName() ? vectors->GetName() : "(unnamed)";
  const std::string kind = cells ? "cell" : "point";
  const std::string what = "the " + kind + " array '" + name + "' ";
  const int components = vectors->GetNumberOfComponents();
  const std::string badComponents = validateOrientationComponents(components);
  if (!badComponents.empty())
  {
    return what + badComponents;
  }
  const vtkIdType expected = cells ? image->GetNumberOfCells() : image->GetNumberOfPoints();
  if (vectors->GetNumberOfTuples() != expected)
  {
    return what + "has " + std::to_string(vectors->GetNumberOfTuples()) + " tuples for " +
      std::to_string(expected) + " " + kind + "s";
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
  OrientationField grid;
  grid.origin = { first[0], first[1], first[2] };
  grid.spacing = { spacing[0], spacing[1], spacing[2] };
  grid.dimensions = { dims[0], dims[1], dims[2] };
  if (cells)
  {
    for (int a = 0; a < 3; ++a)
    {
      if (dims[a] > 1) // an axis of one point has no cells along it: its centres stay in the plane
      {
        grid.origin[a] += 0.5 * spacing[a];
        grid.dimensions[static_cast<std::size_t>(a)] = dims[a] - 1;
      }
    }
  }
  const vtkIdType n = vectors->GetNumberOfTuples();
  // The fields are a double copy of the array (one Vec3 per axis), other types are read through a
  // double copy first: refuse what cannot fit before allocating it.
  const bool copied = vtkDoubleArray::SafeDownCast(vectors) == nullptr;
  const std::string tooLarge =
    checkMemoryBudget(static_cast<double>(n) * components * sizeof(double) * (copied ? 2.0 : 1.0),
      "the orientation field of the " + kind + " array '" + name + "' (" + std::to_string(n) + " " +
        (components == 6 ? "pairs of axes" : "vectors") + ")");
  if (!tooLarge.empty())
  {
    return tooLarge;
  }
  std::vector<double> buffer;
  const double* values = AsDoubles(vectors, buffer);
  std::vector<OrientationField> made;
  const std::string problem = orientationFieldsFromArray(
    values, static_cast<std::size_t>(n), components, grid, made, notFinite);
  if (!problem.empty())
  {
    return what + problem;
  }
  for (OrientationField& f : made)
  {
    fields.push_back(std::move(f));
  }
  return {};
}

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: OrientationFieldData.h
