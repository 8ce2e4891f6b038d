#include "FiberInnerRadii.h"

#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

namespace fiberpli
{

std::string ReadInnerRadii(vtkPolyData* input, const FiberConversion& conversion, const std::string& who,
  InnerRadii& inner)
{
  inner.clear();
  vtkDataArray* array = input ? input->GetPointData()->GetArray(kInnerRadiusArray) : nullptr;
  if (array == nullptr)
  {
    return {};
  }
  if (array->GetNumberOfComponents() != 1)
  {
    return who + ": the point array 'inner_radius' has " + std::to_string(array->GetNumberOfComponents()) +
      " components, expected 1";
  }
  if (array->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    return who + ": the point array 'inner_radius' has " + std::to_string(array->GetNumberOfTuples()) +
      " values for " + std::to_string(input->GetNumberOfPoints()) + " points";
  }
  inner.resize(conversion.sourcePoints.size());
  for (std::size_t f = 0; f < conversion.sourcePoints.size(); ++f)
  {
    for (long long id : conversion.sourcePoints[f])
    {
      inner[f].push_back(array->GetComponent(static_cast<vtkIdType>(id), 0));
    }
  }
  std::size_t bad = 0;
  const std::string invalid = validateInnerRadii(conversion.model, inner, &bad);
  if (!invalid.empty())
  {
    inner.clear();
    // The Core names the fiber of the model; the line cell is what the user can find.
    const std::string cell =
      bad < conversion.sourceCell.size() ? "line cell " + std::to_string(conversion.sourceCell[bad]) + ", " : "";
    return who + ": " + cell + invalid;
  }
  return {};
}

} // namespace fiberpli
