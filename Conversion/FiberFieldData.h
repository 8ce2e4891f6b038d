/**
 * @file FiberFieldData.h
 * @brief the one way FiberPLI filters write and read field-data values (steps, seed,
 * polarizer_angles, …; the names are in Core/Model/DataNames.h)
 */
#ifndef FiberFieldData_h
#define FiberFieldData_h

#include "Geometry/PeriodicCell.h"
#include "Model/DataNames.h"
#include "Model/PeriodicCellRule.h"
#include "Util/NumberFormat.h"

#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>

#include <string>
#include <vector>

namespace fiberpli
{

/// Adds (or replaces) a double array `name` holding `values` to the data object's field data.
inline void AddFieldDoubles(
  vtkDataObject* data, const char* name, const std::vector<double>& values)
{
  vtkNew<vtkDoubleArray> a;
  a->SetName(name);
  for (double v : values)
  {
    a->InsertNextValue(v);
  }
  data->GetFieldData()->AddArray(a);
}

/// Adds (or replaces) a one-value int array `name` to the data object's field data.
inline void AddFieldInt(vtkDataObject* data, const char* name, int value)
{
  vtkNew<vtkIntArray> a;
  a->SetName(name);
  a->InsertNextValue(value);
  data->GetFieldData()->AddArray(a);
}

/// The field data array `name` of `data`, or null when it (or the field data) is absent.
inline vtkDataArray* FieldArray(vtkDataObject* data, const char* name)
{
  return data && data->GetFieldData() ? data->GetFieldData()->GetArray(name) : nullptr;
}

/// All values of the field data array `name`, component by component (empty when absent).
inline std::vector<double> FieldValues(vtkDataObject* data, const char* name)
{
  std::vector<double> values;
  vtkDataArray* a = FieldArray(data, name);
  const vtkIdType n = a ? a->GetNumberOfValues() : 0;
  for (vtkIdType k = 0; k < n; ++k)
  {
    values.push_back(a->GetComponent(
      k / a->GetNumberOfComponents(), static_cast<int>(k % a->GetNumberOfComponents())));
  }
  return values;
}

/// The first value of the field data array `name`, or `fallback` when it is absent or empty.
inline double FieldValue(vtkDataObject* data, const char* name, double fallback)
{
  vtkDataArray* a = FieldArray(data, name);
  return a && a->GetNumberOfValues() > 0 ? a->GetComponent(0, 0) : fallback;
}

/// True when the fibers carry FiberCollisionSolver's field data collisions = 0: they claim to be
/// collision-free.
inline bool ClaimsCollisionFree(vtkDataObject* fibers)
{
  vtkDataArray* collisions = FieldArray(fibers, fiberfield::kCollisions);
  return collisions && collisions->GetNumberOfTuples() == 1 && collisions->GetTuple1(0) == 0.0;
}

/// Adds the field `periodic_cell` (xmin xmax ymin ymax zmin zmax) of a periodic substrate.
inline void AddPeriodicCell(vtkDataObject* data, const PeriodicCell& cell)
{
  AddFieldDoubles(data, fiberfield::kPeriodicCell,
    { cell.lo.x, cell.hi.x, cell.lo.y, cell.hi.y, cell.lo.z, cell.hi.z });
}

/// The values of the field `periodic_cell` as they are (false when absent).
inline bool PeriodicCellValues(vtkDataObject* data, std::vector<double>& values)
{
  values = FieldValues(data, fiberfield::kPeriodicCell);
  return FieldArray(data, fiberfield::kPeriodicCell) != nullptr;
}

/// Reads the field `periodic_cell`: false and an empty error when absent; false and a message
/// naming the field when it has the wrong size or bad values; true with the cell otherwise.
inline bool ReadPeriodicCell(vtkDataObject* data, PeriodicCell& cell, std::string& error)
{
  error.clear();
  std::vector<double> values;
  if (!PeriodicCellValues(data, values))
  {
    return false;
  }
  error = periodicCellFromBounds(values.data(), values.size(), cell);
  return error.empty();
}

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberFieldData.h
