// FiberCubeSource through VTK: counts, arrays, reproducibility, pieces, bad properties.
#include "ErrorCatcher.h"
#include "PieceCheck.h"
#include "vtkFiberCubeSource.h"

#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

TEST(FiberCubeSource, ProducesTheRequestedFibersWithTheContractArrays)
{
  vtkNew<vtkFiberCubeSource> cube;
  cube->SetPopulations(2);
  cube->SetNumberOfFibers(41);
  cube->SetEdgeLength(30.0);
  cube->SetFiberRadius(0.6);
  cube->SetSegmentLength(3.0);
  cube->SetDisplacement(0.25);
  cube->SetSeed(5);
  cube->Update();
  vtkPolyData* out = cube->GetOutput();
  ASSERT_EQ(out->GetNumberOfLines(), 41);
  EXPECT_EQ(out->GetNumberOfPoints(), 41 * 11); // round(30 / 3) + 1 points per fiber
  vtkDataArray* radius = out->GetPointData()->GetArray("radius");
  ASSERT_NE(radius, nullptr);
  EXPECT_EQ(radius->GetRange()[0], 0.6);
  EXPECT_EQ(radius->GetRange()[1], 0.6);
  vtkDataArray* bundle = out->GetCellData()->GetArray("bundle_id");
  ASSERT_NE(bundle, nullptr);
  ASSERT_NE(out->GetCellData()->GetArray("fiber_id"), nullptr);
  int perBundle[2] = { 0, 0 };
  for (vtkIdType c = 0; c < 41; ++c)
  {
    ++perBundle[static_cast<int>(bundle->GetTuple1(c))];
  }
  EXPECT_EQ(perBundle[0], 21);
  EXPECT_EQ(perBundle[1], 20);
  double bounds[6];
  out->GetBounds(bounds);
  for (int a = 0; a < 3; ++a)
  {
    EXPECT_GE(bounds[2 * a], -15.25 - 1e-12);
    EXPECT_LE(bounds[2 * a + 1], 15.25 + 1e-12);
  }
  EXPECT_EQ(out->GetFieldData()->GetArray("segment_length")->GetTuple1(0), 3.0);
}

TEST(FiberCubeSource, SameSeedSameOutput)
{
  vtkNew<vtkFiberCubeSource> a, b;
  for (vtkFiberCubeSource* s : { a.Get(), b.Get() })
  {
    s->SetNumberOfFibers(20);
    s->SetEdgeLength(20.0);
    s->SetSeed(9);
    s->Update();
  }
  ASSERT_EQ(a->GetOutput()->GetNumberOfPoints(), b->GetOutput()->GetNumberOfPoints());
  for (vtkIdType i = 0; i < a->GetOutput()->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    a->GetOutput()->GetPoint(i, p);
    b->GetOutput()->GetPoint(i, q);
    ASSERT_EQ(p[0], q[0]);
    ASSERT_EQ(p[1], q[1]);
    ASSERT_EQ(p[2], q[2]);
  }
}

TEST(FiberCubeSource, PiecesMakeTheWholeModel)
{
  vtkNew<vtkFiberCubeSource> cube;
  cube->SetPopulations(3);
  cube->SetNumberOfFibers(17);
  cube->SetEdgeLength(20.0);
  cube->SetSeed(12);
  fiberpli_test::ExpectPiecesMakeTheWhole(cube, 5);
  cube->SetPeriodic(true); // periodic_cell on every piece
  cube->SetVolumeFraction(0.25);
  cube->SetRadiusSpread(0.2);
  cube->SetRadiusDistribution(1);
  fiberpli_test::ExpectPiecesMakeTheWhole(cube, 5);
  cube->SetVolumeFraction(0.0); // 3 fibers in 8 pieces: piece 1 is empty but has the cell
  cube->SetNumberOfFibers(3);
  cube->UpdatePiece(1, 8, 0);
  EXPECT_EQ(cube->GetOutput()->GetNumberOfLines(), 0);
  EXPECT_NE(cube->GetOutput()->GetFieldData()->GetArray("periodic_cell"), nullptr);
}

TEST(FiberCubeSource, BadPropertiesAreNamedAndRecoverable)
{
  vtkNew<vtkFiberCubeSource> cube;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(cube);
  cube->SetNumberOfFibers(10);
  cube->SetEdgeLength(1.0);
  cube->SetFiberRadius(0.8);
  cube->Update();
  EXPECT_NE(catcher->Errors.find("EdgeLength"), std::string::npos) << catcher->Errors;
  EXPECT_EQ(cube->GetOutput()->GetNumberOfPoints(), 0);
  catcher->Clear();
  cube->SetFiberRadius(0.0);
  cube->SetEdgeLength(10.0);
  cube->Update();
  EXPECT_NE(catcher->Errors.find("FiberRadius"), std::string::npos) << catcher->Errors;
  catcher->Clear();
  cube->SetFiberRadius(0.3);
  cube->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(cube->GetOutput()->GetNumberOfLines(), 10);
}

TEST(FiberCubeSource, NegativeAndOutOfRangePropertiesAreNamedNotClamped)
{
  // The setters used to clamp silently: NumberOfFibers -1 → an empty cube without a word,
  // EdgeLength -5 → "EdgeLength is 0", Populations 7 → 3.
  vtkNew<vtkFiberCubeSource> cube;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(cube);
  cube->SetNumberOfFibers(20);
  const auto expectError = [&](const std::string& text) { ExpectUpdateError(cube, catcher, text); };
  cube->SetNumberOfFibers(-1);
  expectError("NumberOfFibers is -1");
  cube->SetNumberOfFibers(20);
  cube->SetEdgeLength(-5.0);
  expectError("EdgeLength is -5");
  cube->SetEdgeLength(20.0);
  cube->SetFiberRadius(-0.5);
  expectError("FiberRadius is -0.5");
  cube->SetFiberRadius(0.8);
  cube->SetPopulations(7);
  expectError("Populations is 7");
  cube->SetPopulations(3);
  cube->SetSeed(-1);
  expectError("Seed is -1");
  cube->SetSeed(42);
  catcher->Clear();
  cube->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(cube->GetOutput()->GetNumberOfLines(), 20);
}
