// Small fiber polydata for the VTK tests, built by hand (independent of the conversion layer).
#pragma once

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <array>
#include <vector>

/// Polydata with one polyline per entry of `fibers` (points x, y, z, r), fiber_id = 100 + index,
/// bundle_id = index % 2.
inline vtkSmartPointer<vtkPolyData> MakeFibers(
  const std::vector<std::vector<std::array<double, 4>>>& fibers, bool withRadius = true)
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("radius");
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkIdTypeArray> fiberId;
  fiberId->SetName("fiber_id");
  vtkNew<vtkIntArray> bundleId;
  bundleId->SetName("bundle_id");
  for (std::size_t f = 0; f < fibers.size(); ++f)
  {
    lines->InsertNextCell(static_cast<vtkIdType>(fibers[f].size()));
    for (const auto& p : fibers[f])
    {
      lines->InsertCellPoint(points->InsertNextPoint(p[0], p[1], p[2]));
      radius->InsertNextValue(p[3]);
    }
    fiberId->InsertNextValue(static_cast<vtkIdType>(100 + f));
    bundleId->InsertNextValue(static_cast<int>(f % 2));
  }
  pd->SetPoints(points);
  pd->SetLines(lines);
  if (withRadius)
  {
    pd->GetPointData()->AddArray(radius);
  }
  pd->GetCellData()->AddArray(fiberId);
  pd->GetCellData()->AddArray(bundleId);
  return pd;
}

/// Two valid fibers: a straight one along x and a bent one.
inline vtkSmartPointer<vtkPolyData> MakeTwoFibers()
{
  return MakeFibers({ { { 0, 0, 0, 1 }, { 5, 0, 0, 1 }, { 10, 0, 0, 1 } },
    { { 0, 5, 0, 0.5 }, { 3, 5, 0, 0.6 }, { 3, 8, 0, 0.7 }, { 3, 8, 4, 0.5 } } });
}
