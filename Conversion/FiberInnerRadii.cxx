#include "FiberInnerRadii.h"

#include "Model/DataNames.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

namespace fiberpli
{

std::string ReadInnerRadii(vtkPolyData* input, FiberConversion& conversion, const std::string& who)
{
  for (Fiber& f : conversion.model.fibers)
  {
    f.innerRadii.clear();
  }
  vtkDataArray* array = input ? input->GetPointData()->GetArray(fiberfield::kInnerRadius) : nullptr;
  if (array == nullptr)
  {
    return {};
  }
  if (array->GetNumberOfComponents() != 1)
  {
    return who + ": the point array 'inner_radius' has " +
      std::to_string(array->GetNumberOfComponents()) + " components, expected 1";
  }
  if (array->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    return who + ": the point array 'inner_radius' has " +
      std::to_string(array->GetNumberOfTuples()) + " values for " +
      std::to_string(input->GetNumberOfPoints()) + " points";
  }
  for (std::size_t f = 0; f < conversion.sourcePoints.size() && f < conversion.model.fibers.size();
       ++f)
  {
    std::vector<double>& inner = conversion.model.fibers[f].innerRadii;
    for (long long id : conversion.sourcePoints[f])
    {
      inner.push_back(array->GetComponent(static_cast<vtkIdType>(id), 0));
    }
  }
  std::size_t bad = 0;
  const std::string invalid = validateInnerRadii(conversion.model, &bad);
  if (!invalid.empty())
  {
    for (Fiber& f : conversion.model.fibers)
    {
      f.innerRadii.clear();
    }
    // The Core names the fiber of the model; the line cell is what the user can find.
    const std::string cell = bad < conversion.sourceCell.size()
      ? "line cell " + std::to_string(conversion.sourceCell[bad]) + ", "
      : "";
    return who + ": " + cell + invalid;
  }
  return {};
}

void AddInnerRadii(const FiberModel& model, vtkPolyData* output)
{
  if (!hasInnerRadii(model))
  {
    return;
  }
  vtkNew<vtkDoubleArray> inner;
  inner->SetName(fiberfield::kInnerRadius);
  inner->SetNumberOfTuples(static_cast<vtkIdType>(model.numberOfPoints()));
  vtkIdType p = 0;
  for (const Fiber& f : model.fibers)
  {
    const bool sheath = f.innerRadii.size() == f.size();
    for (std::size_t i = 0; i < f.size(); ++i)
    {
      inner->SetValue(p++, sheath ? f.innerRadii[i] : f.radii[i]);
    }
  }
  output->GetPointData()->AddArray(inner);
}

} // namespace fiberpli
