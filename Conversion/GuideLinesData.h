/**
 * @file GuideLinesData.h
 * @brief the line cells of a vtkPolyData as Core guide lines (Field/GuideField.h)
 *
 * Any polydata with lines will do: fiber polydata (e.g. streamlines read from a .tck file by
 * FiberReader), the output of a stream tracer, lines drawn by hand. Every line or polyline cell is
 * one guide, its points in the input's order (µm); its bundle id is the cell's value of the cell
 * array `bundle_id` when there is one (any integer-valued array), else 0. Vertices, polygons and
 * strips are not guides. No array other than bundle_id is needed (no radius).
 */
#ifndef GuideLinesData_h
#define GuideLinesData_h

#include "Field/GuideField.h"
#include "Model/DataNames.h"
#include "Util/MemoryBudget.h"
#include "Util/NumberFormat.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <string>
#include <vector>

namespace fiberpli
{

/// Fills `guides` with the line cells of `input`; returns "" or a message naming what is wrong (a
/// bundle_id that is no integer, the memory budget). No lines gives no guides and no message (the
/// Core names that).
inline std::string ToGuideLines(vtkPolyData* input, std::vector<GuideLine>& guides)
{
  guides.clear();
  vtkCellArray* lines = input->GetLines();
  if (!lines || lines->GetNumberOfCells() == 0)
  {
    return {};
  }
  const std::string tooLarge =
    checkMemoryBudget(static_cast<double>(lines->GetNumberOfConnectivityIds()) * sizeof(Vec3),
      "the guide lines (" + std::to_string(lines->GetNumberOfConnectivityIds()) + " points)");
  if (!tooLarge.empty())
  {
    return tooLarge;
  }
  vtkDataArray* bundles = input->GetCellData()->GetArray(fiberfield::kBundleId);
  if (bundles && bundles->GetNumberOfComponents() != 1)
  {
    bundles = nullptr;
  }
  // vtkPolyData numbers its cells verts first, then lines.
  const vtkIdType firstLine = input->GetNumberOfVerts();
  guides.reserve(static_cast<std::size_t>(lines->GetNumberOfCells()));
  auto it = vtk::TakeSmartPointer(lines->NewIterator());
  vtkIdType cell = firstLine;
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++cell)
  {
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    it->GetCurrentCell(n, ids);
    GuideLine g;
    g.points.reserve(static_cast<std::size_t>(n));
    for (vtkIdType i = 0; i < n; ++i)
    {
      double p[3];
      input->GetPoint(ids[i], p);
      g.points.push_back({ p[0], p[1], p[2] });
    }
    if (bundles && cell < bundles->GetNumberOfTuples())
    {
      const double b = bundles->GetTuple1(cell);
      if (!(std::isfinite(b) && b == std::floor(b) && std::fabs(b) < 9.0e15))
      {
        return "Input: bundle_id of line cell " + std::to_string(cell) + " is " + formatNumber(b) +
          ", must be an integer";
      }
      g.bundle = static_cast<std::int64_t>(b);
    }
    guides.push_back(std::move(g));
  }
  return {};
}

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: GuideLinesData.h
