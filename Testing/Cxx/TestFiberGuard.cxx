// The exception guard of every FiberPLI algorithm (Conversion/FiberGuard.h) and the one periodic
// cell rule (Model/PeriodicCellRule.h) through VTK: an exception escaping the work becomes a VTK
// error naming the algorithm, with empty output, and the pipeline runs again; a periodic_cell with
// finite bounds whose edge overflows is refused by the solver, PLISimulation, the ground truth,
// FiberMetrics and the writer alike (the solver used to die on std::length_error, PLISimulation
// to say "no fiber in the section").
#include "ErrorCatcher.h"
#include "FiberGuard.h"
#include "vtkFiberCollisionSolver.h"
#include "vtkFiberMetrics.h"
#include "vtkFiberOrientationGroundTruth.h"
#include "vtkFiberWriter.h"
#include "vtkPLISimulation.h"

#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkPolyDataAlgorithm.h>
#include <vtkTrivialProducer.h>

#include <gtest/gtest.h>

#include <new>
#include <stdexcept>
#include <string>

namespace
{
/// A source whose work throws what it is told to (after filling its output), or makes one point.
class ThrowingSource : public vtkPolyDataAlgorithm
{
public:
  static ThrowingSource* New();
  vtkTypeMacro(ThrowingSource, vtkPolyDataAlgorithm);
  int Throw = 0; // 0 nothing, 1 std::bad_alloc, 2 std::length_error, 3 an int

protected:
  ThrowingSource() { this->SetNumberOfInputPorts(0); }
  int RequestData(
    vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector) override
  {
    return fiberpli::GuardRequest(this, outputVector, "ThrowingSource",
      [&]() -> int
      {
        vtkPolyData* out = vtkPolyData::GetData(outputVector);
        vtkNew<vtkPoints> points;
        points->InsertNextPoint(1, 2, 3);
        out->SetPoints(points);
        switch (this->Throw)
        {
          case 1:
            throw std::bad_alloc();
          case 2:
            throw std::length_error("vector::_M_default_append");
          case 3:
            throw 42;
          default:
            return 1;
        }
      });
  }
};
vtkStandardNewMacro(ThrowingSource);

/// Two closed straight fibers along x in the cell [-5, 5]^3 carrying `cell` as periodic_cell.
vtkSmartPointer<vtkPolyData> FibersWithCell(const double cell[6])
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkDoubleArray> radius;
  radius->SetName("radius");
  for (int f = 0; f < 2; ++f)
  {
    lines->InsertNextCell(6);
    for (int k = 0; k < 6; ++k)
    {
      lines->InsertCellPoint(points->InsertNextPoint(-5.0 + 2.0 * k, -2.0 + 4.0 * f, 0.0));
      radius->InsertNextValue(1.0);
    }
  }
  pd->SetPoints(points);
  pd->SetLines(lines);
  pd->GetPointData()->AddArray(radius);
  vtkNew<vtkDoubleArray> c;
  c->SetName("periodic_cell");
  for (int i = 0; i < 6; ++i)
  {
    c->InsertNextValue(cell[i]);
  }
  pd->GetFieldData()->AddArray(c);
  return pd;
}
} // namespace

TEST(FiberGuard, AnEscapingExceptionIsAnErrorNamingTheAlgorithm)
{
  vtkNew<ThrowingSource> source;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(source);
  const char* expected[] = { "", "ThrowingSource: out of memory",
    "ThrowingSource: internal error: vector::_M_default_append",
    "ThrowingSource: internal error (unknown exception)" };
  for (int kind : { 1, 2, 3, 0 })
  {
    source->Throw = kind;
    source->Modified();
    catcher->Errors.clear();
    source->Update(); // without the guard the exception leaves Update and ends the program
    if (kind == 0)
    {
      EXPECT_EQ(catcher->Errors, "");
      EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 1)
        << "the pipeline runs again after an exception";
    }
    else
    {
      EXPECT_NE(catcher->Errors.find(expected[kind]), std::string::npos) << catcher->Errors;
      EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 0)
        << "a half-made output after an exception";
    }
  }
}

TEST(FiberGuard, AnOverflowingPeriodicCellIsRefusedByEveryFilter)
{
  const double overflow[6] = { -1e308, 1e308, -5, 5, -5, 5 };
  const std::string expected = "periodic_cell axis x is [-1e+308, 1e+308]";
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(FibersWithCell(overflow));

  vtkNew<vtkFiberCollisionSolver> solver;
  vtkNew<vtkPLISimulation> sim;
  vtkNew<vtkFiberOrientationGroundTruth> truth;
  vtkNew<vtkFiberMetrics> metrics;
  const double voi[6] = { -6, 6, -6, 6, -2, 2 };
  sim->SetVolumeOfInterest(voi);
  sim->SetNumberOfRotations(4);
  sim->SetNumberOfThreads(1);
  truth->SetVolumeOfInterest(voi);
  truth->SetNumberOfThreads(1);
  solver->SetNumberOfThreads(1);
  metrics->SetNumberOfThreads(1);
  for (vtkAlgorithm* a : { static_cast<vtkAlgorithm*>(solver), static_cast<vtkAlgorithm*>(sim),
         static_cast<vtkAlgorithm*>(truth), static_cast<vtkAlgorithm*>(metrics) })
  {
    a->SetInputConnection(producer->GetOutputPort());
    vtkNew<ErrorCatcher> catcher;
    catcher->Watch(a);
    a->Update();
    EXPECT_NE(catcher->Errors.find(expected), std::string::npos)
      << a->GetClassName() << ": " << catcher->Errors;
    EXPECT_EQ(catcher->Errors.find("no fiber"), std::string::npos)
      << a->GetClassName() << ": " << catcher->Errors;
  }
  vtkNew<vtkFiberWriter> writer;
  writer->SetInputConnection(producer->GetOutputPort());
  writer->SetFileName(FIBERPLI_TEST_TMP_DIR "/overflow_cell.h5");
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(writer);
  writer->Write();
  EXPECT_NE(catcher->Errors.find(expected), std::string::npos) << catcher->Errors;

  // The same fibers with a sound cell go through.
  const double good[6] = { -5, 5, -5, 5, -5, 5 };
  producer->SetOutput(FibersWithCell(good));
  vtkNew<ErrorCatcher> clean;
  clean->Watch(sim);
  sim->Update();
  EXPECT_EQ(clean->Errors, "");
  EXPECT_GT(sim->GetOutput()->GetNumberOfPoints(), 0);
}
