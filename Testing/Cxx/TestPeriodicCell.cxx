// Periodic cells through VTK: FiberCubeSource with Periodic and VolumeFraction, the periodic_cell
// field data, FiberCollisionSolver honouring it, bad input.
#include "ErrorCatcher.h"
#include "vtkFiberCollisionSolver.h"
#include "vtkFiberCubeSource.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>

namespace
{
double Field(vtkPolyData* pd, const char* name, int i = 0)
{
  vtkDataArray* a = pd->GetFieldData()->GetArray(name);
  return a && i < a->GetNumberOfTuples() ? a->GetTuple1(i) : std::nan("");
}

// Every polyline ends at its first point shifted by one edge along exactly one axis.
void ExpectClosed(vtkPolyData* pd, double edge)
{
  auto it = vtk::TakeSmartPointer(pd->GetLines()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    double a[3], b[3];
    pd->GetPoint(ids[0], a);
    pd->GetPoint(ids[n - 1], b);
    double shift = 0.0;
    int moved = 0;
    for (int d = 0; d < 3; ++d)
    {
      if (b[d] != a[d])
      {
        shift = b[d] - a[d];
        ++moved;
      }
    }
    EXPECT_EQ(moved, 1);
    EXPECT_NEAR(shift, edge, 1e-9);
  }
}

vtkSmartPointer<vtkPolyData> PeriodicCube(int populations, double edge, double phi)
{
  vtkNew<vtkFiberCubeSource> cube;
  cube->SetPopulations(populations);
  cube->SetEdgeLength(edge);
  cube->SetPeriodic(true);
  cube->SetVolumeFraction(phi);
  cube->SetDisplacement(0.3);
  cube->SetSeed(4);
  cube->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(cube->GetOutput());
  return out;
}
} // namespace

TEST(PeriodicCell, CubeSourceWritesTheCellAndClosedFibers)
{
  vtkSmartPointer<vtkPolyData> out = PeriodicCube(2, 16.0, 0.5);
  const double expected[6] = { -8, 8, -8, 8, -8, 8 };
  for (int i = 0; i < 6; ++i)
    EXPECT_EQ(Field(out, "periodic_cell", i), expected[i]);
  // N = φ L² / (π r²) = 0.5 · 256 / (π · 0.64) = 63.7 → 64 fibers.
  EXPECT_EQ(out->GetNumberOfLines(), 64);
  ExpectClosed(out, 16.0);

  vtkNew<vtkFiberCubeSource> open;
  open->SetNumberOfFibers(10);
  open->Update();
  EXPECT_EQ(open->GetOutput()->GetFieldData()->GetArray("periodic_cell"), nullptr);
}

TEST(PeriodicCell, SolverKeepsClosureAndReportsFractionAndGap)
{
  vtkNew<vtkFiberCollisionSolver> solver;
  solver->SetInputData(PeriodicCube(2, 14.0, 0.45));
  solver->SetMaxSteps(4000);
  solver->Update();
  vtkPolyData* out = solver->GetOutput();
  EXPECT_EQ(Field(out, "solved"), 1.0);
  EXPECT_EQ(Field(out, "periodic_cell", 1), 7.0);
  EXPECT_GE(Field(out, "volume_fraction"), 0.45);
  EXPECT_LT(Field(out, "volume_fraction"), 0.6);
  EXPECT_GE(Field(out, "min_gap"), 0.0);
  EXPECT_EQ(Field(out, "radius_scale"), 1.0);
  ExpectClosed(out, 14.0);
  vtkDataArray* radius = out->GetPointData()->GetArray("radius");
  EXPECT_EQ(radius->GetRange()[0], 0.8);
  EXPECT_EQ(radius->GetRange()[1], 0.8);
}

TEST(PeriodicCell, BadInputIsAClearError)
{
  vtkNew<vtkFiberCubeSource> cube;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(cube);
  cube->SetPeriodic(true);
  cube->SetEdgeLength(20.0);
  cube->SetVolumeFraction(1.2);
  cube->Update();
  EXPECT_NE(catcher->Errors.find("VolumeFraction is 1.2"), std::string::npos) << catcher->Errors;
  catcher->Clear();
  cube->SetVolumeFraction(-0.5);
  cube->Update();
  EXPECT_NE(catcher->Errors.find("VolumeFraction"), std::string::npos) << catcher->Errors;
  catcher->Clear();
  cube->SetVolumeFraction(0.3);
  cube->SetEdgeLength(3.0);
  cube->Update();
  EXPECT_NE(catcher->Errors.find("EdgeLength is 3"), std::string::npos) << catcher->Errors;

  // A periodic_cell field of the wrong size: the solver names it and stays usable.
  vtkSmartPointer<vtkPolyData> fibers = PeriodicCube(1, 14.0, 0.3);
  vtkNew<vtkDoubleArray> bad;
  bad->SetName("periodic_cell");
  for (double v : { -7.0, 7.0, -7.0, 7.0, -7.0 })
    bad->InsertNextValue(v);
  fibers->GetFieldData()->AddArray(bad);
  vtkNew<vtkFiberCollisionSolver> solver;
  vtkNew<ErrorCatcher> solverErrors;
  solverErrors->Watch(solver);
  solver->SetInputData(fibers);
  solver->Update();
  EXPECT_NE(solverErrors->Errors.find("periodic_cell has 5 values"), std::string::npos)
    << solverErrors->Errors;
  EXPECT_EQ(solver->GetOutput()->GetNumberOfPoints(), 0);
  solverErrors->Clear();
  bad->InsertNextValue(7.0);
  bad->Modified();
  fibers->Modified();
  solver->Update();
  EXPECT_TRUE(solverErrors->Errors.empty()) << solverErrors->Errors;
  EXPECT_GT(solver->GetOutput()->GetNumberOfPoints(), 0);
}
