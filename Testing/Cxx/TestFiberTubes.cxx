// FiberTubes through VTK: watertight and outward, exact polygonal volume, arrays carried.
#include "ErrorCatcher.h"
#include "FiberTestData.h"
#include "vtkFiberCollisionSolver.h"
#include "vtkFiberCubeSource.h"
#include "vtkFiberTubes.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkMassProperties.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>

namespace
{
/// Every undirected edge must be used by exactly two triangles, once in each direction.
void ExpectWatertight(vtkPolyData* mesh)
{
  std::map<std::pair<vtkIdType, vtkIdType>, int> directed;
  auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    ASSERT_EQ(n, 3);
    for (int e = 0; e < 3; ++e)
    {
      ++directed[{ ids[e], ids[(e + 1) % 3] }];
    }
  }
  std::size_t bad = 0;
  for (const auto& [edge, count] : directed)
  {
    const auto back = directed.find({ edge.second, edge.first });
    if (count != 1 || back == directed.end() || back->second != 1)
    {
      ++bad;
    }
  }
  EXPECT_EQ(bad, 0u) << "edges not shared by exactly two consistently oriented triangles";
}

double SignedVolume(vtkPolyData* mesh)
{
  double v = 0.0;
  auto it = vtk::TakeSmartPointer(mesh->GetPolys()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    double a[3], b[3], c[3];
    mesh->GetPoint(ids[0], a);
    mesh->GetPoint(ids[1], b);
    mesh->GetPoint(ids[2], c);
    v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
           a[2] * (b[0] * c[1] - b[1] * c[0])) /
      6.0;
  }
  return v;
}
} // namespace

TEST(FiberTubes, StraightFiberVolumeMatchesThePolygonalTube)
{
  auto fibers =
    MakeFibers({ { { -3, 1, 2, 0.8 }, { -1, 1, 2, 0.8 }, { 4, 1, 2, 0.8 }, { 7, 1, 2, 0.8 } } });
  for (int sides : { 6, 12, 20 })
  {
    vtkNew<vtkFiberTubes> tubes;
    tubes->SetInputData(fibers);
    tubes->SetNumberOfSides(sides);
    tubes->CappingOn();
    tubes->Update();
    vtkPolyData* out = tubes->GetOutput();
    ExpectWatertight(out);
    const double exact = 10.0 * 0.5 * sides * 0.8 * 0.8 * std::sin(2.0 * M_PI / sides);
    EXPECT_NEAR(SignedVolume(out), exact, 1e-3 * exact);
    // VTK's own volume estimate agrees (independent code path).
    vtkNew<vtkMassProperties> mass;
    mass->SetInputData(out);
    mass->Update();
    EXPECT_NEAR(mass->GetVolume(), exact, 1e-3 * exact);
  }
}

TEST(FiberTubes, CubeTubesAreWatertightAndCarryIds)
{
  vtkNew<vtkFiberCubeSource> cube;
  cube->SetPopulations(3);
  cube->SetNumberOfFibers(30);
  cube->SetEdgeLength(20.0);
  cube->SetSeed(3);
  vtkNew<vtkFiberTubes> tubes;
  tubes->SetInputConnection(cube->GetOutputPort());
  tubes->SetNumberOfSides(8);
  tubes->Update();
  vtkPolyData* out = tubes->GetOutput();
  ExpectWatertight(out);
  EXPECT_GT(SignedVolume(out), 0.0);
  ASSERT_NE(out->GetPointData()->GetNormals(), nullptr);
  vtkDataArray* fiberId = out->GetCellData()->GetArray("fiber_id");
  vtkDataArray* bundleId = out->GetCellData()->GetArray("bundle_id");
  ASSERT_NE(fiberId, nullptr);
  ASSERT_NE(bundleId, nullptr);
  // 30 fibers of n points, 8 sides: 2·8·(n−1) body + 2·8 cap triangles each.
  const vtkIdType n = cube->GetOutput()->GetCell(0)->GetNumberOfPoints();
  ASSERT_EQ(out->GetNumberOfCells(), 30 * (16 * (n - 1) + 16));
  std::map<vtkIdType, int> triangles;
  for (vtkIdType t = 0; t < out->GetNumberOfCells(); ++t)
  {
    const auto id = static_cast<vtkIdType>(fiberId->GetTuple1(t));
    ++triangles[id];
    // Cube ids are population-ordered: 10 fibers per population here.
    EXPECT_EQ(static_cast<int>(bundleId->GetTuple1(t)), static_cast<int>(id / 10));
  }
  EXPECT_EQ(triangles.size(), 30u);
}

TEST(FiberTubes, EmptyInputGivesEmptyOutputWithoutError)
{
  vtkNew<vtkPolyData> empty;
  vtkNew<vtkFiberTubes> tubes;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(tubes);
  tubes->SetInputData(empty);
  tubes->Update();
  EXPECT_EQ(tubes->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
}

TEST(FiberTubes, NumberOfSidesOutOfRangeIsNamedNotClamped)
{
  // NumberOfSides used to be clamped to [3, 64] without a word.
  vtkNew<vtkFiberTubes> tubes;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(tubes);
  tubes->SetInputData(MakeFibers({ { { 0, 0, 0, 1 }, { 10, 0, 0, 1 } } }));
  const auto expectError = [&](const std::string& text)
  { ExpectUpdateError(tubes, catcher, text); };
  tubes->SetNumberOfSides(2);
  expectError("NumberOfSides is 2, must be in [3, 64]");
  tubes->SetNumberOfSides(65);
  expectError("NumberOfSides is 65");
  tubes->SetNumberOfSides(-1);
  expectError("NumberOfSides is -1");
  tubes->SetNumberOfSides(8);
  catcher->Clear();
  tubes->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(tubes->GetOutput()->GetNumberOfPoints(), 2 * 8 + 2); // two rings and two cap centres
  EXPECT_EQ(
    tubes->GetOutput()->GetNumberOfCells(), 2 * 8 + 2 * 8); // side quads as triangles, two fans
}

TEST(FiberTubes, InnerTubesOnRequestAreWatertightOutwardAndLabelled)
{
  // A myelinated cube (GRatio 0.6): with InnerTubes every fiber gets a second closed, outward tube
  // at its inner radius, the tubes' volumes in the ratio g² (straight fibers of constant radius),
  // and tube_surface tells them apart. Off (the default) is the mesh of before, without
  // tube_surface.
  vtkNew<vtkFiberCubeSource> cube;
  cube->SetPopulations(2);
  cube->SetNumberOfFibers(12);
  cube->SetEdgeLength(20.0);
  cube->SetSeed(3);
  cube->SetGRatio(0.6);
  vtkNew<vtkFiberTubes> plain;
  plain->SetInputConnection(cube->GetOutputPort());
  plain->SetNumberOfSides(10);
  plain->Update();
  EXPECT_EQ(plain->GetOutput()->GetCellData()->GetArray("tube_surface"), nullptr);
  vtkNew<vtkFiberTubes> tubes;
  tubes->SetInputConnection(cube->GetOutputPort());
  tubes->SetNumberOfSides(10);
  tubes->InnerTubesOn();
  tubes->Update();
  vtkPolyData* out = tubes->GetOutput();
  ExpectWatertight(out);
  ASSERT_EQ(out->GetNumberOfCells(), 2 * plain->GetOutput()->GetNumberOfCells());
  vtkDataArray* surface = out->GetCellData()->GetArray("tube_surface");
  ASSERT_NE(surface, nullptr);
  // Split the triangles by surface and compare the signed volumes of the two closed sets.
  vtkNew<vtkPolyData> outer, inner;
  vtkNew<vtkCellArray> outerPolys, innerPolys;
  auto it = vtk::TakeSmartPointer(out->GetPolys()->NewIterator());
  vtkIdType t = 0;
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++t)
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    (surface->GetTuple1(t) == 0 ? outerPolys.Get() : innerPolys.Get())->InsertNextCell(n, ids);
  }
  outer->SetPoints(out->GetPoints());
  outer->SetPolys(outerPolys);
  inner->SetPoints(out->GetPoints());
  inner->SetPolys(innerPolys);
  ExpectWatertight(inner);
  ExpectWatertight(outer);
  const double vOuter = SignedVolume(outer), vInner = SignedVolume(inner);
  EXPECT_NEAR(vOuter, SignedVolume(plain->GetOutput()), 1e-9 * vOuter); // the outer tubes unchanged
  EXPECT_GT(vInner, 0.0);                                               // outward
  EXPECT_NEAR(vInner / vOuter, 0.36, 1e-9);                             // g² for a constant g
  // A bad inner_radius is an error naming it.
  auto fibers = MakeFibers({ { { 0, 0, 0, 1.0 }, { 5, 0, 0, 1.0 } } });
  vtkNew<vtkDoubleArray> bad;
  bad->SetName("inner_radius");
  bad->InsertNextValue(0.5);
  bad->InsertNextValue(1.5);
  fibers->GetPointData()->AddArray(bad);
  vtkNew<vtkFiberTubes> badTubes;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(badTubes);
  badTubes->SetInputData(fibers);
  badTubes->InnerTubesOn();
  badTubes->Update();
  EXPECT_NE(catcher->Errors.find("inner_radius"), std::string::npos) << catcher->Errors;
  EXPECT_NE(catcher->Errors.find("1.5"), std::string::npos) << catcher->Errors;
}

TEST(FiberTubes, TubesKeepTheModelsFieldData)
{
  // A periodic cube solved: its tubes carry the same solved, collisions and periodic_cell values
  // (they used to be dropped, so a saved tubes file no longer said what it was).
  vtkNew<vtkFiberCubeSource> cube;
  cube->SetPopulations(1);
  cube->SetNumberOfFibers(4);
  cube->SetEdgeLength(12.0);
  cube->SetPeriodic(1);
  cube->SetSeed(2);
  vtkNew<vtkFiberCollisionSolver> solver;
  solver->SetInputConnection(cube->GetOutputPort());
  solver->SetMaxSteps(200);
  solver->SetNumberOfThreads(1);
  vtkNew<vtkFiberTubes> tubes;
  tubes->SetInputConnection(solver->GetOutputPort());
  tubes->Update();
  vtkFieldData* model = solver->GetOutput()->GetFieldData();
  vtkFieldData* out = tubes->GetOutput()->GetFieldData();
  ASSERT_GT(tubes->GetOutput()->GetNumberOfCells(), 0);
  for (const char* name : { "solved", "collisions", "periodic_cell", "steps" })
  {
    vtkDataArray* a = model->GetArray(name);
    vtkDataArray* b = out->GetArray(name);
    ASSERT_NE(a, nullptr) << name;
    ASSERT_NE(b, nullptr) << name << " dropped by FiberTubes";
    ASSERT_EQ(b->GetNumberOfValues(), a->GetNumberOfValues()) << name;
    for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
    {
      EXPECT_EQ(b->GetTuple1(i), a->GetTuple1(i)) << name << " " << i;
    }
  }
  EXPECT_EQ(out->GetArray("periodic_cell")->GetTuple1(1), 6.0);
}
