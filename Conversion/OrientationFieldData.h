/**
 * @file OrientationFieldData.h
 * @brief a vtkImageData point array of 3-component vectors as a Core orientation field
 *
 * The grid is the image's (origin at its first point, its spacing and point counts); the vectors
 * are copied as doubles in the image's point order (x fastest) and normalised
 * (Field/OrientationField.h): zero vectors and vectors with a NaN or infinite component are empty.
 */
#ifndef OrientationFieldData_h
#define OrientationFieldData_h

#include "Field/OrientationField.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkMatrix3x3.h>

#include <string>

namespace fiberpli
{

/// Fills `field` from `image` and its point array `vectors`; returns "" or a message naming the
/// array and what is wrong (components, tuple count, a rotated image). `notFinite` receives how many
/// vectors were NaN or infinite.
inline std::string ToOrientationField(vtkImageData* image, vtkDataArray* vectors, OrientationField& field,
  std::size_t& notFinite)
{
  const std::string name = vectors->GetName() ? vectors->GetName() : "(unnamed)";
  if (vectors->GetNumberOfComponents() != 3)
  {
    return "the point array '" + name + "' has " + std::to_string(vectors->GetNumberOfComponents()) +
      " components, an orientation field needs 3";
  }
  if (vectors->GetNumberOfTuples() != image->GetNumberOfPoints())
  {
    return "the point array '" + name + "' has " + std::to_string(vectors->GetNumberOfTuples()) + " tuples for " +
      std::to_string(image->GetNumberOfPoints()) + " points";
  }
  if (!image->GetDirectionMatrix()->IsIdentity())
  {
    return "the image is rotated (its direction matrix is not the identity); resample it onto an axis-aligned grid";
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
  const vtkIdType n = vectors->GetNumberOfTuples();
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
