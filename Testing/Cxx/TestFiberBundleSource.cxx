// FiberBundleSource through VTK: fibers inside the bundle, grid spacing, following an input
// polyline (with scale), ids per shape, Seed reproducibility, pieces, bad input with recovery, and
// every model (small) solved by FiberCollisionSolver without overlaps (independent counter).
#include "ErrorCatcher.h"
#include "IndependentOverlap.h"
#include "PieceCheck.h"
#include "vtkFiberBundleSource.h"
#include "vtkFiberCollisionSolver.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <vector>

namespace
{
using P3 = std::array<double, 3>;

vtkSmartPointer<vtkPolyData> Polyline(
  const std::vector<P3>& points, const std::vector<double>& scale = {})
{
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> lines;
  lines->InsertNextCell(static_cast<vtkIdType>(points.size()));
  for (const P3& p : points)
  {
    lines->InsertCellPoint(pts->InsertNextPoint(p.data()));
  }
  pd->SetPoints(pts);
  pd->SetLines(lines);
  if (!scale.empty())
  {
    vtkNew<vtkDoubleArray> s;
    s->SetName("scale");
    for (double v : scale)
    {
      s->InsertNextValue(v);
    }
    pd->GetPointData()->AddArray(s);
  }
  return pd;
}

/// Quarter circle of radius 40 in the x-y plane, densely sampled (the analytic trajectory).
std::vector<P3> QuarterCircle(int n)
{
  std::vector<P3> p;
  for (int i = 0; i < n; ++i)
  {
    const double a = 0.5 * M_PI * i / (n - 1);
    p.push_back({ 40.0 * std::cos(a), 40.0 * std::sin(a), 0.0 });
  }
  return p;
}

std::vector<std::vector<P3>> Fibers(vtkPolyData* pd)
{
  std::vector<std::vector<P3>> fibers;
  auto it = vtk::TakeSmartPointer(pd->GetLines()->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell())
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    std::vector<P3> f(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      pd->GetPoint(ids[i], f[i].data());
    }
    fibers.push_back(f);
  }
  return fibers;
}

double Field(vtkPolyData* pd, const char* name)
{
  vtkDataArray* a = pd->GetFieldData()->GetArray(name);
  return a ? a->GetTuple1(0) : -1.0;
}

void Small(vtkFiberBundleSource* s, int shape)
{
  s->SetShape(shape);
  s->SetBundleRadius(3.0);
  s->SetLength(16.0);
  s->SetFiberRadius(0.8);
  s->SetRadiusSpread(0.0);
  s->SetFiberSpacing(2.0);
  s->SetNumberOfFibers(0);
  s->SetSegmentLength(2.0);
  s->SetDisplacement(0.2);
  s->SetCrossingAngle(90.0);
  s->SetUncrossedFraction(0.25);
  s->SetRanvierSpacing(-1.0);
  s->SetSeed(3);
}

// The update is an error naming `text` and the source gives no fibers.
void ExpectErrorAndNoFibers(
  vtkFiberBundleSource* src, ErrorCatcher* catcher, const std::string& text)
{
  ExpectUpdateError(src, catcher, text);
  EXPECT_EQ(src->GetOutput()->GetNumberOfLines(), 0);
}

} // namespace

TEST(FiberBundleSource, CylinderFibersStayInsideTheBundleOnTheGrid)
{
  vtkNew<vtkFiberBundleSource> src; // defaults: R 10, L 60, r 0.8, d 2, D 0.2
  src->Update();
  vtkPolyData* out = src->GetOutput();
  const auto fibers = Fibers(out);
  // π(R − r)²·2/(√3 d²) = 76.8 seeds expected in the cropped disc (lattice counts in a disc
  // fluctuate around the area estimate; this one has 85).
  EXPECT_NEAR(static_cast<double>(fibers.size()), 76.8, 0.12 * 76.8);
  const double D = 0.2;
  for (const auto& f : fibers)
  {
    ASSERT_EQ(f.size(), 31u); // round(60 / 2) + 1 points
    for (const P3& p : f)
    {
      EXPECT_LE(std::hypot(p[1], p[2]), 10.0 - 0.8 + D * std::sqrt(2.0) + 1e-9);
      EXPECT_LE(std::abs(p[0]), 30.0 + D + 1e-9);
    }
  }
  EXPECT_EQ(Field(out, "segment_length"), 2.0);
  EXPECT_EQ(Field(out, "seed"), 42.0);

  // Without displacement the cross-section is the triangular grid: nearest neighbour = spacing.
  src->SetDisplacement(0.0);
  src->SetFiberSpacing(2.5);
  src->Update();
  const auto grid = Fibers(src->GetOutput());
  ASSERT_GT(grid.size(), 10u);
  for (std::size_t i = 0; i < grid.size(); ++i)
  {
    double nearest = std::numeric_limits<double>::max();
    for (std::size_t j = 0; j < grid.size(); ++j)
    {
      if (i != j)
      {
        nearest = std::min(
          nearest, std::hypot(grid[i][0][1] - grid[j][0][1], grid[i][0][2] - grid[j][0][2]));
      }
    }
    EXPECT_NEAR(nearest, 2.5, 1e-9);
    EXPECT_NEAR(grid[i][0][0], -30.0, 1e-9);
  }
}

TEST(FiberBundleSource, FollowsTheInputPolylineAndItsScale)
{
  // Distance of every fiber point to the circle's axis = |seed offset|·σ, constant along the fiber
  // (parallel transport of a planar curve keeps the in-plane and z offsets).
  std::vector<double> offsets[2];
  for (double sigma : { 1.0, 1.5 })
  {
    vtkNew<vtkFiberBundleSource> src;
    src->SetShape(vtkFiberBundleSource::TRAJECTORY);
    src->SetBundleRadius(4.0);
    src->SetDisplacement(0.0);
    const auto circle = QuarterCircle(40);
    src->SetInputData(Polyline(circle, std::vector<double>(circle.size(), sigma)));
    src->Update();
    const auto fibers = Fibers(src->GetOutput());
    ASSERT_GT(fibers.size(), 5u);
    for (const auto& f : fibers)
    {
      // offset = (ρ − 40, z) in the plane of the circle's normal section
      const double r0 = std::hypot(f[0][0], f[0][1]) - 40.0;
      const double z0 = f[0][2];
      EXPECT_LE(std::hypot(r0, z0), sigma * (4.0 - 0.8) + 1e-6);
      for (const P3& p : f)
      {
        EXPECT_NEAR(std::hypot(p[0], p[1]) - 40.0, r0, 0.02);
        EXPECT_NEAR(p[2], z0, 1e-6);
      }
      // Ends where the curve ends; the end frame is perpendicular to the last chord (2 µm on a
      // 40 µm circle), tilting the offset by up to ρ·sin(0.025) along the curve.
      EXPECT_NEAR(std::atan2(f.back()[1], f.back()[0]), 0.5 * M_PI, 6.0 * 0.025 / 40.0);
    }
    for (const auto& f : fibers)
    {
      offsets[sigma == 1.0 ? 0 : 1].push_back(
        std::hypot(std::hypot(f[0][0], f[0][1]) - 40.0, f[0][2]));
    }
  }
  // Same seeds, offsets scaled by σ = 1.5.
  ASSERT_EQ(offsets[0].size(), offsets[1].size());
  for (std::size_t j = 0; j < offsets[0].size(); ++j)
  {
    EXPECT_NEAR(offsets[1][j], 1.5 * offsets[0][j], 0.01) << j;
  }
}

TEST(FiberBundleSource, IdsAreUniqueAndBundlesPerShape)
{
  const std::vector<std::set<int>> expected = { { 0 }, { 0 }, { 0, 1 }, { 0, 1 }, { 0, 1, 2, 3 } };
  for (int shape : { 0, 2, 3, 4 })
  {
    vtkNew<vtkFiberBundleSource> src;
    Small(src, shape);
    src->Update();
    vtkPolyData* out = src->GetOutput();
    vtkDataArray* fid = out->GetCellData()->GetArray("fiber_id");
    vtkDataArray* bid = out->GetCellData()->GetArray("bundle_id");
    ASSERT_NE(fid, nullptr);
    ASSERT_NE(bid, nullptr);
    std::set<long long> ids;
    std::set<int> bundles;
    for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
    {
      ids.insert(static_cast<long long>(fid->GetTuple1(c)));
      bundles.insert(static_cast<int>(bid->GetTuple1(c)));
    }
    EXPECT_EQ(static_cast<vtkIdType>(ids.size()), out->GetNumberOfCells()) << shape;
    EXPECT_EQ(*ids.begin(), 0) << shape;
    EXPECT_EQ(bundles, expected[shape]) << shape;
  }
}

TEST(FiberBundleSource, SameSeedSameFibersOtherSeedOtherFibers)
{
  vtkNew<vtkFiberBundleSource> a, b;
  Small(a, vtkFiberBundleSource::CHIASM);
  Small(b, vtkFiberBundleSource::CHIASM);
  a->Update();
  b->Update();
  ASSERT_EQ(a->GetOutput()->GetNumberOfPoints(), b->GetOutput()->GetNumberOfPoints());
  bool same = true;
  for (vtkIdType i = 0; i < a->GetOutput()->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    a->GetOutput()->GetPoint(i, p);
    b->GetOutput()->GetPoint(i, q);
    same = same && p[0] == q[0] && p[1] == q[1] && p[2] == q[2];
  }
  EXPECT_TRUE(same);
  b->SetSeed(4);
  b->Update();
  double p[3], q[3];
  a->GetOutput()->GetPoint(0, p);
  b->GetOutput()->GetPoint(0, q);
  EXPECT_NE(p[0], q[0]);
  EXPECT_EQ(Field(b->GetOutput(), "seed"), 4.0);
}

TEST(FiberBundleSource, PiecesMakeTheWholeModel)
{
  vtkNew<vtkFiberBundleSource> src;
  Small(src, vtkFiberBundleSource::CROSSING);
  src->SetSeed(9);
  fiberpli_test::ExpectPiecesMakeTheWhole(src, 5);
  src->SetShape(vtkFiberBundleSource::TRAJECTORY);
  src->SetInputData(Polyline({ { -10, 0, 0 }, { 0, 2, 0 }, { 10, 0, 1 } }));
  fiberpli_test::ExpectPiecesMakeTheWhole(src, 5);
}

TEST(FiberBundleSource, BadInputIsAClearErrorAndRecoverable)
{
  vtkNew<vtkFiberBundleSource> src;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(src);
  const auto expectError = [&](const std::string& text)
  { ExpectErrorAndNoFibers(src, catcher, text); };
  const auto expectValid = [&]()
  {
    catcher->Clear();
    src->Update();
    EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
    EXPECT_GT(src->GetOutput()->GetNumberOfLines(), 0);
  };
  src->SetShape(vtkFiberBundleSource::TRAJECTORY);
  expectError("Shape is Trajectory but no polyline is connected to input port 0");
  src->SetInputData(Polyline({ { 0, 0, 0 }, { 10, 0, 0 }, { 10, 0, 0 }, { 20, 0, 0 } }));
  expectError("Trajectory point 2 (10, 0, 0) repeats point 1");
  src->SetInputData(Polyline({ { 0, 0, 0 } }));
  expectError("Trajectory has 1 point(s), needs at least 2");
  src->SetInputData(Polyline({ { 0, 0, 0 }, { 10, std::nan(""), 0 }, { 20, 0, 0 } }));
  expectError("Trajectory point 1");
  src->SetInputData(Polyline({ { 0, 0, 0 }, { 10, 0, 0 }, { 20, 0, 0 } }, { 1.0, -1.0, 1.0 }));
  expectError("Trajectory scale at point 1 is -1");
  src->SetInputData(Polyline({ { 0, 0, 0 }, { 10, 0, 0 }, { 20, 0, 0 } }));
  expectValid();
  src->SetBundleRadius(0.5);
  expectError("BundleRadius 0.5 is smaller than FiberRadius 0.8");
  src->SetBundleRadius(10.0);
  expectValid();
  src->SetShape(vtkFiberBundleSource::CYLINDER); // the input is ignored by the other shapes
  expectValid();
  EXPECT_TRUE(catcher->Warnings.empty()) << catcher->Warnings;
  // An empty trajectory is an empty bundle, not an error.
  src->SetShape(vtkFiberBundleSource::TRAJECTORY);
  src->SetInputData(vtkNew<vtkPolyData>().GetPointer());
  catcher->Clear();
  src->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_EQ(src->GetOutput()->GetNumberOfLines(), 0);
  // A sharp corner: one folding warning, output still made.
  src->SetInputData(Polyline({ { 0, 0, 0 }, { 20, 0, 0 }, { 20, 20, 0 } }));
  catcher->Clear();
  src->Update();
  EXPECT_NE(catcher->Warnings.find("radius of curvature"), std::string::npos) << catcher->Warnings;
  EXPECT_GT(src->GetOutput()->GetNumberOfLines(), 0);
}

TEST(FiberBundleSource, DefaultChiasmHasNoFoldingWarning)
{
  vtkNew<vtkFiberBundleSource> src;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(src);
  src->SetShape(vtkFiberBundleSource::CHIASM);
  src->Update();
  EXPECT_TRUE(catcher->Warnings.empty()) << catcher->Warnings;
  EXPECT_GT(src->GetOutput()->GetNumberOfLines(), 100);
}

TEST(FiberBundleSource, EveryModelIsSolvedWithoutOverlaps)
{
  for (int shape : { 0, 1, 2, 3, 4 })
  {
    vtkNew<vtkFiberBundleSource> src;
    Small(src, shape);
    if (shape <= vtkFiberBundleSource::TRAJECTORY || shape == vtkFiberBundleSource::YSHAPE)
    {
      src->SetFiberSpacing(
        1.5); // < 2r: bundles that do not cross start with overlapping neighbours
    }
    if (shape == vtkFiberBundleSource::TRAJECTORY) // the paper's f(t) = (t³, t, 0), scaled
    {
      std::vector<P3> curve;
      for (int i = 0; i <= 10; ++i)
      {
        const double t = -1.0 + 0.2 * i;
        curve.push_back({ 8.0 * t * t * t, 8.0 * t, 0.0 });
      }
      src->SetInputData(Polyline(curve));
    }
    vtkNew<vtkFiberCollisionSolver> solver;
    solver->SetInputConnection(src->GetOutputPort());
    solver->SetSegmentLength(2.0);
    solver->SetMaxSteps(5000);
    solver->Update();
    vtkPolyData* out = solver->GetOutput();
    ASSERT_GT(independent::CountOverlaps(src->GetOutput()), 0) << shape; // the start collides
    EXPECT_EQ(Field(out, "solved"), 1.0) << shape;
    EXPECT_EQ(independent::CountOverlaps(out), 0) << shape;
    EXPECT_EQ(out->GetNumberOfLines(), src->GetOutput()->GetNumberOfLines()) << shape;
  }
}

TEST(FiberBundleSource, NegativeAndOutOfRangePropertiesAreNamedNotClamped)
{
  // The setters used to clamp: NumberOfFibers -1 became 0 (a grid, no message), FiberRadius -2
  // became 0 ("is 0"), Shape 7 became Chiasm. Now each is an error with the value typed.
  vtkNew<vtkFiberBundleSource> src;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(src);
  const auto expectError = [&](const std::string& text)
  { ExpectErrorAndNoFibers(src, catcher, text); };
  src->SetNumberOfFibers(-1);
  expectError("NumberOfFibers is -1");
  src->SetNumberOfFibers(0);
  src->SetFiberRadius(-2.0);
  expectError("FiberRadius is -2");
  src->SetFiberRadius(0.8);
  src->SetShape(7);
  expectError("Shape is 7");
  src->SetShape(vtkFiberBundleSource::CYLINDER);
  src->SetRadiusDistribution(9);
  expectError("RadiusDistribution is 9");
  src->SetRadiusDistribution(0);
  src->SetSeed(-4);
  expectError("Seed is -4");
  src->SetSeed(1);
  catcher->Clear();
  src->Update();
  EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  EXPECT_GT(src->GetOutput()->GetNumberOfLines(), 0);
}

TEST(FiberBundleSource, ScaleArrayOfTheWrongLengthIsAnError)
{
  // A 'scale' point array with fewer values than points used to be read past its end / ignored.
  auto trajectory = Polyline({ { 0, 0, 0 }, { 10, 0, 0 }, { 20, 0, 0 } }, { 1.0, 1.5, 1.0 });
  trajectory->GetPointData()->GetArray("scale")->SetNumberOfTuples(2);
  vtkNew<vtkFiberBundleSource> src;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(src);
  src->SetShape(vtkFiberBundleSource::TRAJECTORY);
  src->SetInputData(trajectory);
  src->Update();
  EXPECT_NE(catcher->Errors.find("'scale' has 2 values for 3 points"), std::string::npos)
    << catcher->Errors;
  EXPECT_EQ(src->GetOutput()->GetNumberOfLines(), 0);
}
