// The data contract (docs/data-contract.md §3) as every filter sees it through FiberPolyData: each
// bad input gives a clear error naming the problem and an empty output, and the pipeline works
// again once the input is fixed.
#include "ErrorCatcher.h"
#include "FiberPolyData.h"
#include "FiberTestData.h"
#include "vtkFiberTubes.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>

#include <gtest/gtest.h>

#include <limits>

namespace
{
/// Runs FiberTubes on `bad`, expects an error containing every string of `expected` and an empty
/// output, then runs it on good input and expects tubes: the pipeline stayed usable.
void ExpectErrorThenRecovery(vtkPolyData* bad, std::initializer_list<const char*> expected)
{
  vtkNew<vtkFiberTubes> tubes;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(tubes);
  tubes->SetInputData(bad);
  tubes->Update();
  for (const char* text : expected)
  {
    EXPECT_NE(catcher->Errors.find(text), std::string::npos)
      << "missing '" << text << "' in: " << catcher->Errors;
  }
  EXPECT_EQ(tubes->GetOutput()->GetNumberOfPoints(), 0);

  catcher->Clear();
  tubes->SetInputData(MakeTwoFibers());
  tubes->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_GT(tubes->GetOutput()->GetNumberOfCells(), 0);
}
/// Polydata whose MTime is fixed: two of them look unchanged to a cache that compares MTimes only.
class FixedMTimePolyData : public vtkPolyData
{
public:
  static FixedMTimePolyData* New();
  vtkTypeMacro(FixedMTimePolyData, vtkPolyData);
  vtkMTimeType GetMTime() override { return 1; }
};
vtkStandardNewMacro(FixedMTimePolyData);
} // namespace

TEST(FiberPolyData, CacheConvertsAnotherInputWithTheSameMTime)
{
  auto two = MakeTwoFibers();
  fiberpli::FiberConversion c = fiberpli::FiberPolyData::ToModel(two, "Test");
  ASSERT_TRUE(c.ok()) << c.error;
  c.model.fibers.pop_back();
  vtkNew<vtkPolyData> one;
  fiberpli::FiberPolyData::FromModel(c.model, one);
  vtkNew<FixedMTimePolyData> a, b;
  a->ShallowCopy(two);
  b->ShallowCopy(one);
  ASSERT_EQ(a->GetMTime(), b->GetMTime());

  fiberpli::FiberModelCache cache;
  EXPECT_EQ(cache.Get(a, "Test").model.fibers.size(), 2u);
  EXPECT_EQ(cache.Get(b, "Test").model.fibers.size(), 1u); // the input connection was switched
  EXPECT_EQ(cache.Get(a, "Test").model.fibers.size(), 2u);
}

TEST(FiberPolyData, RoundTripKeepsPointsRadiiAndIds)
{
  auto input = MakeTwoFibers();
  fiberpli::FiberConversion c = fiberpli::FiberPolyData::ToModel(input, "Test");
  ASSERT_TRUE(c.ok()) << c.error;
  ASSERT_EQ(c.model.fibers.size(), 2u);
  EXPECT_EQ(c.model.fibers[1].id, 101);
  EXPECT_EQ(c.model.fibers[1].bundle, 1);
  EXPECT_EQ(c.model.fibers[1].radii[2], 0.7);
  vtkNew<vtkPolyData> back;
  fiberpli::FiberPolyData::FromModel(c.model, back);
  ASSERT_EQ(back->GetNumberOfPoints(), input->GetNumberOfPoints());
  ASSERT_EQ(back->GetNumberOfLines(), 2);
  for (vtkIdType i = 0; i < input->GetNumberOfPoints(); ++i)
  {
    double a[3], b[3];
    input->GetPoint(i, a);
    back->GetPoint(i, b);
    EXPECT_EQ(a[0], b[0]);
    EXPECT_EQ(a[1], b[1]);
    EXPECT_EQ(a[2], b[2]);
    EXPECT_EQ(input->GetPointData()->GetArray("radius")->GetTuple1(i),
      back->GetPointData()->GetArray("radius")->GetTuple1(i));
  }
  EXPECT_EQ(back->GetCellData()->GetArray("fiber_id")->GetTuple1(1), 101);
}

TEST(FiberPolyData, MissingRadiusIsAnError)
{
  auto bad = MakeFibers({ { { 0, 0, 0, 1 }, { 1, 0, 0, 1 } } }, false);
  ExpectErrorThenRecovery(bad, { "FiberTubes", "'radius'" });
}

TEST(FiberPolyData, MultiComponentRadiusIsAnError)
{
  auto bad = MakeTwoFibers();
  bad->GetPointData()->GetArray("radius")->SetNumberOfComponents(3);
  ExpectErrorThenRecovery(bad, { "'radius'", "components" });
}

TEST(FiberPolyData, NonFiniteCoordinateNamesTheFiber)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto bad =
    MakeFibers({ { { 0, 0, 0, 1 }, { 1, 0, 0, 1 } }, { { 0, 2, 0, 1 }, { 1, nan, 0, 1 } } });
  ExpectErrorThenRecovery(bad, { "line cell 1", "fiber_id 101", "point 1", "non-finite" });
  const double inf = std::numeric_limits<double>::infinity();
  auto bad2 = MakeFibers({ { { 0, 0, 0, 1 }, { inf, 0, 0, 1 } } });
  ExpectErrorThenRecovery(bad2, { "fiber_id 100", "non-finite" });
}

TEST(FiberPolyData, ZeroOrNegativeRadiusNamesTheFiber)
{
  auto zero = MakeFibers({ { { 0, 0, 0, 1 }, { 1, 0, 0, 0 } } });
  ExpectErrorThenRecovery(zero, { "fiber_id 100", "radius 0" });
  auto negative =
    MakeFibers({ { { 0, 0, 0, 1 }, { 1, 0, 0, 1 } }, { { 0, 0, 0, -2 }, { 1, 0, 0, 1 } } });
  ExpectErrorThenRecovery(negative, { "fiber_id 101", "radius -2" });
}

TEST(FiberPolyData, CellsWithoutLinesAreAnError)
{
  auto bad = MakeFibers({});
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(0, 1, 0);
  bad->SetPoints(points);
  vtkNew<vtkCellArray> polys;
  const vtkIdType tri[3] = { 0, 1, 2 };
  polys->InsertNextCell(3, tri);
  bad->SetPolys(polys);
  ExpectErrorThenRecovery(bad, { "no line cell" });
}

TEST(FiberPolyData, ShortFibersAreDroppedWithOneWarning)
{
  auto input =
    MakeFibers({ { { 0, 0, 0, 1 } }, { { 0, 5, 0, 1 }, { 4, 5, 0, 1 } }, { { 9, 9, 9, 1 } } });
  vtkNew<vtkFiberTubes> tubes;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(tubes);
  tubes->SetInputData(input);
  tubes->SetNumberOfSides(6);
  tubes->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_NE(
    catcher->Warnings.find("2 fiber(s) with fewer than 2 points dropped"), std::string::npos)
    << catcher->Warnings;
  vtkPolyData* out = tubes->GetOutput();
  ASSERT_EQ(out->GetNumberOfCells(), 2 * 6 + 2 * 6);
  EXPECT_EQ(out->GetCellData()->GetArray("fiber_id")->GetTuple1(0), 101);
}

TEST(FiberPolyData, EmptyInputIsAnEmptyModel)
{
  vtkNew<vtkPolyData> empty;
  fiberpli::FiberConversion c = fiberpli::FiberPolyData::ToModel(empty, "Test");
  EXPECT_TRUE(c.ok());
  EXPECT_TRUE(c.model.empty());
}

TEST(FiberPolyData, ArraysOfTheWrongLengthAreAnError)
{
  auto shortRadius = MakeTwoFibers();
  shortRadius->GetPointData()->GetArray("radius")->SetNumberOfTuples(3);
  ExpectErrorThenRecovery(shortRadius, { "'radius' has 3 values for 7 points" });
  auto shortIds = MakeTwoFibers();
  shortIds->GetCellData()->GetArray("bundle_id")->SetNumberOfTuples(1);
  ExpectErrorThenRecovery(shortIds, { "'bundle_id' has 1 values for 2 cells" });
}

TEST(FiberPolyData, LinesReferringToMissingPointsAreAnError)
{
  auto bad = MakeTwoFibers();
  const vtkIdType ids[2] = { 0, 99 };
  bad->GetLines()->InsertNextCell(2, ids);
  bad->GetCellData()->GetArray("fiber_id")->InsertNextTuple1(102);
  bad->GetCellData()->GetArray("bundle_id")->InsertNextTuple1(0);
  ExpectErrorThenRecovery(bad, { "line cell 2 refers to point 99" });
}

TEST(FiberPolyData, IdsThatAreNoIntegersOfTheirRangeAreErrors)
{
  // fiber_id NaN / 1e30 / 2.5 in a double array, bundle_id 3e9 (beyond int): each an error naming
  // the array, the cell and the value (they used to become INT64_MIN / INT_MIN silently).
  const struct
  {
    const char* array;
    double value;
    const char* text;
  } cases[] = { { "fiber_id", std::numeric_limits<double>::quiet_NaN(), "fiber_id is nan" },
    { "fiber_id", 1e30, "fiber_id is 1e+30" }, { "fiber_id", 2.5, "fiber_id is 2.5" },
    { "bundle_id", 3e9, "bundle_id is 3e+09" } };
  for (const auto& c : cases)
  {
    auto bad = MakeTwoFibers();
    vtkNew<vtkDoubleArray> ids;
    ids->SetName(c.array);
    ids->SetNumberOfTuples(2);
    ids->SetValue(0, 7);
    ids->SetValue(1, c.value);
    bad->GetCellData()->RemoveArray(c.array);
    bad->GetCellData()->AddArray(ids);
    ExpectErrorThenRecovery(bad, { "line cell 1", c.text });
  }
  // Integral values in a double array and a 64-bit id beyond 2^53 are read exactly.
  auto good = MakeTwoFibers();
  vtkNew<vtkIdTypeArray> big;
  big->SetName("fiber_id");
  big->SetNumberOfTuples(2);
  big->SetValue(0, 9007199254740993LL); // 2^53 + 1: not representable as a double
  big->SetValue(1, -5);
  good->GetCellData()->RemoveArray("fiber_id");
  good->GetCellData()->AddArray(big);
  vtkNew<vtkDoubleArray> bundles;
  bundles->SetName("bundle_id");
  bundles->SetNumberOfTuples(2);
  bundles->SetValue(0, -3.0);
  bundles->SetValue(1, 2147483647.0);
  good->GetCellData()->RemoveArray("bundle_id");
  good->GetCellData()->AddArray(bundles);
  const fiberpli::FiberConversion c = fiberpli::FiberPolyData::ToModel(good, "Test");
  ASSERT_TRUE(c.ok()) << c.error;
  EXPECT_EQ(c.model.fibers[0].id, 9007199254740993LL);
  EXPECT_EQ(c.model.fibers[1].id, -5);
  EXPECT_EQ(c.model.fibers[0].bundle, -3);
  EXPECT_EQ(c.model.fibers[1].bundle, 2147483647);
}
