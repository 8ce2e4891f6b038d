// ExpectPiecesMakeTheWhole: the pieces 0..P-1 of a fiber source (P = 1..maxPieces), one after the
// other, are its one-piece output: the same lines in the same order with the same points, radii
// and fiber ids, and every piece carries the same field data (docs/tissue-models.md §9).
#pragma once

#include <vtkAlgorithm.h>
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace fiberpli_test
{
struct Line
{
  std::vector<double> values; // x y z radius per point, then the fiber id
};

inline std::vector<Line> Lines(vtkPolyData* pd)
{
  std::vector<Line> lines;
  vtkDataArray* radius = pd->GetPointData()->GetArray("radius");
  vtkDataArray* ids = pd->GetCellData()->GetArray("fiber_id");
  auto it = vtk::TakeSmartPointer(pd->GetLines()->NewIterator());
  vtkIdType c = 0;
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++c)
  {
    vtkIdType n = 0;
    const vtkIdType* pts = nullptr;
    it->GetCurrentCell(n, pts);
    Line line;
    for (vtkIdType k = 0; k < n; ++k)
    {
      double p[3];
      pd->GetPoint(pts[k], p);
      line.values.insert(line.values.end(), { p[0], p[1], p[2], radius->GetTuple1(pts[k]) });
    }
    line.values.push_back(ids->GetTuple1(c));
    lines.push_back(line);
  }
  return lines;
}

inline std::string FieldText(vtkPolyData* pd)
{
  std::string text;
  vtkFieldData* fd = pd->GetFieldData();
  for (int a = 0; a < fd->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = fd->GetArray(a);
    text += std::string(fd->GetArrayName(a)) + ":";
    for (vtkIdType t = 0; array && t < array->GetNumberOfTuples() * array->GetNumberOfComponents();
         ++t)
    {
      text += " " +
        std::to_string(array->GetComponent(t / array->GetNumberOfComponents(),
          static_cast<int>(t % array->GetNumberOfComponents())));
    }
    text += "; ";
  }
  return text;
}

inline void ExpectPiecesMakeTheWhole(vtkAlgorithm* source, int maxPieces)
{
  source->UpdatePiece(0, 1, 0);
  vtkNew<vtkPolyData> whole;
  whole->DeepCopy(vtkPolyData::SafeDownCast(source->GetOutputDataObject(0)));
  const std::vector<Line> all = Lines(whole);
  ASSERT_GE(all.size(), static_cast<std::size_t>(maxPieces));
  for (int pieces = 1; pieces <= maxPieces; ++pieces)
  {
    std::size_t next = 0;
    for (int piece = 0; piece < pieces; ++piece)
    {
      source->UpdatePiece(piece, pieces, 0);
      vtkPolyData* part = vtkPolyData::SafeDownCast(source->GetOutputDataObject(0));
      const std::vector<Line> mine = Lines(part);
      EXPECT_EQ(mine.size(), all.size() * (piece + 1) / pieces - all.size() * piece / pieces)
        << "piece " << piece << " of " << pieces;
      for (const Line& line : mine)
      {
        ASSERT_LT(next, all.size());
        EXPECT_EQ(line.values, all[next].values)
          << "fiber " << next << " in piece " << piece << " of " << pieces;
        ++next;
      }
      EXPECT_EQ(FieldText(part), FieldText(whole)) << "piece " << piece << " of " << pieces;
    }
    EXPECT_EQ(next, all.size()) << pieces << " pieces";
  }
}
} // namespace fiberpli_test
