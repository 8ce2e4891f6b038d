// FiberCollisionSolver through VTK: solved outputs checked by an independent overlap counter,
// invariants (fiber count, order, ids, end points), array pass-through, field data, thread
// independence, MaxSteps, iterations as time, bad input.
#include "ErrorCatcher.h"
#include "FiberTestData.h"
#include "IndependentOverlap.h"
#include "vtkFiberCollisionSolver.h"
#include "vtkFiberCubeSource.h"

#include <vtkCellData.h>
#include <vtkFieldData.h>
#include <vtkFloatArray.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <gtest/gtest.h>

namespace
{
double Field(vtkPolyData* pd, const char* name)
{
  vtkDataArray* a = pd->GetFieldData()->GetArray(name);
  return a ? a->GetTuple1(0) : -1.0;
}

/// Two fibers crossing at 90°, axes 0.5 µm apart, radius 1 (docs/solver.md §10 test 14).
vtkSmartPointer<vtkPolyData> CrossingPair()
{
  std::vector<std::array<double, 4>> a, b;
  for (int i = 0; i <= 20; ++i)
  {
    a.push_back({ -10.0 + i, 0.0, 0.0, 1.0 });
    b.push_back({ 0.0, -10.0 + i, 0.5, 1.0 });
  }
  return MakeFibers({ a, b });
}

vtkSmartPointer<vtkPolyData> SmallDenseCube(int populations, int fibers)
{
  vtkNew<vtkFiberCubeSource> cube;
  cube->SetPopulations(populations);
  cube->SetNumberOfFibers(fibers);
  cube->SetEdgeLength(51.96152422706632 * std::sqrt(fibers / 1000.0)); // the paper's density
  cube->SetFiberRadius(0.8);
  cube->SetSegmentLength(2.0);
  cube->SetDisplacement(0.5);
  cube->SetSeed(11);
  cube->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(cube->GetOutput());
  return out;
}
} // namespace

TEST(FiberCollisionSolver, CrossingPairEndsTouchingFreeWithArraysKept)
{
  auto input = CrossingPair();
  ASSERT_GT(independent::CountOverlaps(input), 0);
  vtkNew<vtkFloatArray> temperature; // a float point array follows the points
  temperature->SetName("temperature");
  vtkNew<vtkIntArray> label; // an int cell array is copied per fiber
  label->SetName("label");
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    temperature->InsertNextValue(static_cast<float>(i));
  }
  label->InsertNextValue(7);
  label->InsertNextValue(9);
  input->GetPointData()->AddArray(temperature);
  input->GetCellData()->AddArray(label);

  vtkNew<vtkFiberCollisionSolver> solver;
  solver->SetInputData(input);
  solver->SetSegmentLength(1.0);
  solver->SetNumberOfThreads(1);
  solver->Update();
  vtkPolyData* out = solver->GetOutput();
  EXPECT_EQ(Field(out, "solved"), 1.0);
  EXPECT_EQ(Field(out, "collisions"), 0.0);
  EXPECT_GT(Field(out, "steps"), 0.0);
  EXPECT_EQ(independent::CountOverlaps(out), 0);
  ASSERT_EQ(out->GetNumberOfLines(), 2);
  EXPECT_EQ(out->GetCellData()->GetArray("fiber_id")->GetTuple1(0), 100);
  EXPECT_EQ(out->GetCellData()->GetArray("fiber_id")->GetTuple1(1), 101);
  ASSERT_NE(out->GetCellData()->GetArray("label"), nullptr);
  EXPECT_EQ(out->GetCellData()->GetArray("label")->GetTuple1(1), 9);
  vtkDataArray* t = out->GetPointData()->GetArray("temperature");
  ASSERT_NE(t, nullptr);
  ASSERT_EQ(t->GetNumberOfTuples(), out->GetNumberOfPoints());
  // Values stay within the fiber's own input range (interpolated between its points).
  vtkIdType npts;
  const vtkIdType* ids;
  out->GetLines()->GetCellAtId(1, npts, ids);
  for (vtkIdType i = 0; i < npts; ++i)
  {
    EXPECT_GE(t->GetTuple1(ids[i]), 21.0);
    EXPECT_LE(t->GetTuple1(ids[i]), 41.0);
  }
}

TEST(FiberCollisionSolver, SmallCubesAreSolvedWithFibersAndIdsKept)
{
  for (int populations = 1; populations <= 3; ++populations)
  {
    auto input = SmallDenseCube(populations, 40);
    vtkNew<vtkFiberCollisionSolver> solver;
    solver->SetInputData(input);
    solver->SetSegmentLength(2.0);
    solver->SetMinCurvatureRadius(4.0);
    solver->SetMaxSteps(20000);
    solver->Update();
    vtkPolyData* out = solver->GetOutput();
    EXPECT_EQ(Field(out, "solved"), 1.0) << populations << " populations";
    EXPECT_EQ(independent::CountOverlaps(out), 0) << populations << " populations";
    ASSERT_EQ(out->GetNumberOfLines(), input->GetNumberOfLines());
    for (vtkIdType c = 0; c < input->GetNumberOfLines(); ++c)
    {
      EXPECT_EQ(out->GetCellData()->GetArray("fiber_id")->GetTuple1(c),
        input->GetCellData()->GetArray("fiber_id")->GetTuple1(c));
      EXPECT_EQ(out->GetCellData()->GetArray("bundle_id")->GetTuple1(c),
        input->GetCellData()->GetArray("bundle_id")->GetTuple1(c));
    }
  }
}

TEST(FiberCollisionSolver, SameOutputForOneAndTwoThreads)
{
  auto input = SmallDenseCube(2, 40);
  vtkNew<vtkFiberCollisionSolver> one, two;
  for (auto* s : { one.Get(), two.Get() })
  {
    s->SetInputData(input);
    s->SetMinCurvatureRadius(4.0);
  }
  one->SetNumberOfThreads(1);
  two->SetNumberOfThreads(2);
  one->Update();
  two->Update();
  ASSERT_EQ(one->GetOutput()->GetNumberOfPoints(), two->GetOutput()->GetNumberOfPoints());
  for (vtkIdType i = 0; i < one->GetOutput()->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    one->GetOutput()->GetPoint(i, p);
    two->GetOutput()->GetPoint(i, q);
    ASSERT_EQ(p[0], q[0]);
    ASSERT_EQ(p[1], q[1]);
    ASSERT_EQ(p[2], q[2]);
  }
  EXPECT_EQ(Field(one->GetOutput(), "steps"), Field(two->GetOutput(), "steps"));
}

TEST(FiberCollisionSolver, MaxStepsReachedStillGivesOutputAndWarns)
{
  auto input = SmallDenseCube(3, 60);
  vtkNew<vtkFiberCollisionSolver> solver;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(solver);
  solver->SetInputData(input);
  solver->SetMaxSteps(2);
  solver->Update();
  vtkPolyData* out = solver->GetOutput();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(Field(out, "solved"), 0.0);
  EXPECT_EQ(Field(out, "steps"), 2.0);
  EXPECT_GT(Field(out, "collisions"), 0.0);
  EXPECT_NE(catcher->Warnings.find("capsule pairs still overlap after 2 steps"), std::string::npos)
    << catcher->Warnings;
  EXPECT_EQ(out->GetNumberOfLines(), 60);
}

TEST(FiberCollisionSolver, IterationsAsTimeShowTheFibersSeparating)
{
  auto input = CrossingPair();
  vtkNew<vtkFiberCollisionSolver> solver;
  solver->SetInputData(input);
  solver->SetSegmentLength(1.0);
  solver->SetIterationsAsTime(true);
  solver->SetTimeStepInterval(1);
  solver->SetMaxSteps(200);
  solver->UpdateInformation();
  vtkInformation* info = solver->GetOutputInformation(0);
  ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  // The timeline ends where the solve ended, not at MaxSteps: one time step per solver
  // step (interval 1) and the last one is the final step.
  const int length = info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const double* times = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  EXPECT_LT(length, 201);
  for (int i = 0; i < length; ++i)
    EXPECT_EQ(times[i], static_cast<double>(i));

  solver->UpdateTimeStep(0.0);
  EXPECT_EQ(Field(solver->GetOutput(), "steps"), 0.0);
  EXPECT_EQ(Field(solver->GetOutput(), "solved"), 0.0);
  EXPECT_GT(independent::CountOverlaps(solver->GetOutput()), 0);
  solver->UpdateTimeStep(200.0);
  EXPECT_EQ(Field(solver->GetOutput(), "solved"), 1.0);
  EXPECT_EQ(independent::CountOverlaps(solver->GetOutput()), 0);
  EXPECT_EQ(Field(solver->GetOutput(), "steps"), times[length - 1]);
}

TEST(FiberCollisionSolver, IterationsAsTimeIsBoundedByMaximumSnapshots)
{
  // MaxSteps 2^31 - 1 used to allocate 43 M time values in RequestInformation (and overflow
  // step += interval); MaximumSnapshots 4 with interval 1 keeps at most 4 states plus the final
  // one, thinned to steps 0, 2^k, 2·2^k, … that still cover the whole solve.
  auto input = CrossingPair();
  vtkNew<vtkFiberCollisionSolver> solver;
  solver->SetInputData(input);
  solver->SetSegmentLength(1.0);
  solver->SetIterationsAsTime(true);
  solver->SetTimeStepInterval(1);
  solver->SetMaximumSnapshots(4);
  solver->SetMaxSteps(VTK_INT_MAX);
  solver->UpdateInformation();
  vtkInformation* info = solver->GetOutputInformation(0);
  const int length = info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  const double* times = info->Get(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
  ASSERT_GE(length, 2);
  EXPECT_LE(length, 5);
  EXPECT_EQ(times[0], 0.0);
  const double interval = times[1];
  EXPECT_GT(interval, 1.0); // thinned
  for (int i = 1; i + 1 < length; ++i)
    EXPECT_EQ(times[i], i * interval);
  solver->UpdateTimeStep(times[length - 1]);
  EXPECT_EQ(Field(solver->GetOutput(), "solved"), 1.0);
  EXPECT_EQ(Field(solver->GetOutput(), "steps"), times[length - 1]);
  EXPECT_LT(times[length - 1], 4 * interval + interval); // the solve ended within the last span
  // Between two time steps the earlier snapshot is shown.
  solver->UpdateTimeStep(interval + 0.5);
  EXPECT_EQ(Field(solver->GetOutput(), "steps"), interval);
}

TEST(FiberCollisionSolver, BadInputIsAClearErrorAndRecoverable)
{
  vtkNew<vtkFiberCollisionSolver> solver;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(solver);
  solver->SetInputData(MakeFibers({ { { 0, 0, 0, 1 }, { 1, 0, 0, 1 } } }, false));
  solver->Update();
  EXPECT_NE(catcher->Errors.find("FiberCollisionSolver: the input has no point array 'radius'"),
    std::string::npos)
    << catcher->Errors;
  EXPECT_EQ(solver->GetOutput()->GetNumberOfPoints(), 0);
  const double nan = std::nan("");
  catcher->Clear();
  solver->SetInputData(MakeFibers({ { { 0, 0, 0, 1 }, { 1, nan, 0, 1 } } }));
  solver->Update();
  EXPECT_NE(catcher->Errors.find("non-finite"), std::string::npos) << catcher->Errors;
  catcher->Clear();
  solver->SetInputData(CrossingPair());
  solver->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(solver->GetOutput()->GetNumberOfLines(), 2);
}
