/**
 * @file FiberFieldData.h
 * @brief the one way FiberPLI filters write field-data values (steps, seed, polarizer_angles, …)
 */
#ifndef FiberFieldData_h
#define FiberFieldData_h

#include <vtkDataObject.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIntArray.h>
#include <vtkNew.h>

#include <vector>

namespace fiberpli
{

/// Adds (or replaces) a double array `name` holding `values` to the data object's field data.
inline void AddFieldDoubles(vtkDataObject* data, const char* name, const std::vector<double>& values)
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

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberFieldData.h
