// PLISimulation and FiberOrientationGroundTruth keep the plan of RequestInformation between
// requests (docs/pli-simulation.md §7.3): whatever changes — the input's fibers, a property, the
// input's bounds under the VolumeOfInterest sentinel — the output equals that of a fresh filter.
#include "ErrorCatcher.h"
#include "FiberTestData.h"
#include "vtkFiberOrientationGroundTruth.h"
#include "vtkPLISimulation.h"

#include <vtkDataArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>

#include <gtest/gtest.h>

#include <cstring>
#include <vector>

namespace
{
/// The values of a point array (empty when absent).
std::vector<double> Values(vtkImageData* img, const char* name)
{
  std::vector<double> v;
  vtkDataArray* a = img->GetPointData()->GetArray(name);
  for (vtkIdType k = 0; a && k < a->GetNumberOfValues(); ++k)
  {
    v.push_back(a->GetComponent(
      k / a->GetNumberOfComponents(), static_cast<int>(k % a->GetNumberOfComponents())));
  }
  return v;
}

bool SameBits(const std::vector<double>& a, const std::vector<double>& b)
{
  return a.size() == b.size() &&
    (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

void Configure(vtkPLISimulation* sim, bool sentinel)
{
  if (!sentinel)
  {
    sim->SetVolumeOfInterest(-8, 8, -8, 8, -4, 4);
  }
  sim->SetVoxelSize(0.5);
  sim->SetPixelSize(1.0);
  sim->SetNumberOfRotations(6);
  sim->SetNoiseGain(0.0);
  sim->SetNumberOfThreads(1);
}

/// Two crossing fibers; `shift` moves the second one along y.
vtkSmartPointer<vtkPolyData> Fibers(double shift)
{
  return MakeFibers({ { { -8, -2, -1.5, 1.2 }, { 8, 2, -1.5, 1.2 } },
    { { -3, -8 + shift, 1.5, 1.2 }, { 3, 8 + shift, 1.5, 1.2 } } });
}

/// The image (intensity) of a fresh filter with the same set-up on `input`.
std::vector<double> Fresh(vtkPolyData* input, bool sentinel, const char* layers)
{
  vtkNew<vtkPLISimulation> sim;
  Configure(sim, sentinel);
  sim->SetLayers(layers);
  sim->SetInputData(input);
  sim->Update();
  return Values(sim->GetOutput(), "intensity");
}
} // namespace

TEST(PLICache, SimulationFollowsEveryChangeOfInputAndProperties)
{
  for (bool sentinel : { false, true })
  {
    vtkNew<vtkPLISimulation> sim;
    vtkNew<ErrorCatcher> catcher;
    catcher->Watch(sim);
    Configure(sim, sentinel);
    sim->SetLayers("1 -0.001 0 p");
    vtkSmartPointer<vtkPolyData> input = Fibers(0.0);
    sim->SetInputData(input);
    sim->Update();
    const std::vector<double> first = Values(sim->GetOutput(), "intensity");
    ASSERT_FALSE(first.empty());
    EXPECT_TRUE(SameBits(first, Fresh(input, sentinel, "1 -0.001 0 p")));
    sim->Update(); // nothing changed: the same image
    EXPECT_TRUE(SameBits(first, Values(sim->GetOutput(), "intensity")));

    // The fibers change in place (same data object, new MTime).
    vtkPoints* points = input->GetPoints();
    for (vtkIdType p = 2; p < 4; ++p)
    {
      double x[3];
      points->GetPoint(p, x);
      points->SetPoint(p, x[0] + 2.0, x[1] + 3.0, x[2]);
    }
    input->Modified();
    sim->Update();
    const std::vector<double> moved = Values(sim->GetOutput(), "intensity");
    EXPECT_FALSE(SameBits(first, moved)) << "sentinel " << sentinel;
    EXPECT_TRUE(SameBits(moved, Fresh(input, sentinel, "1 -0.001 0 p"))) << "sentinel " << sentinel;

    // A property changes.
    sim->SetLayers("1 -0.003 2 p");
    sim->Update();
    const std::vector<double> layered = Values(sim->GetOutput(), "intensity");
    EXPECT_FALSE(SameBits(moved, layered));
    EXPECT_TRUE(SameBits(layered, Fresh(input, sentinel, "1 -0.003 2 p")));
    EXPECT_TRUE(catcher->Errors.empty()) << catcher->Errors;
  }
}

TEST(PLICache, SentinelBoundsFollowTheInput)
{
  vtkNew<vtkPLISimulation> sim;
  Configure(sim, true);
  vtkNew<vtkFiberOrientationGroundTruth> truth;
  truth->SetVoxelSize(0.5);
  truth->SetPixelSize(1.0);
  vtkSmartPointer<vtkPolyData> input = MakeFibers({ { { 0, 0, 0, 1 }, { 10, 0, 0, 1 } } });
  sim->SetInputData(input);
  truth->SetInputData(input);
  sim->Update();
  truth->Update();
  int ext[6];
  sim->GetOutput()->GetExtent(ext);
  EXPECT_EQ(ext[1], 11); // x in [-1, 11]: 12 pixels
  truth->GetOutput()->GetExtent(ext);
  EXPECT_EQ(ext[1], 11);
  input->GetPoints()->SetPoint(1, 20, 0, 0); // now x in [-1, 21]: 22 pixels
  input->Modified();
  sim->Update();
  truth->Update();
  sim->GetOutput()->GetExtent(ext);
  EXPECT_EQ(ext[1], 21);
  truth->GetOutput()->GetExtent(ext);
  EXPECT_EQ(ext[1], 21);
}

TEST(PLICache, GroundTruthFollowsEveryChangeOfInputAndProperties)
{
  vtkSmartPointer<vtkPolyData> input = Fibers(0.0);
  vtkNew<vtkFiberOrientationGroundTruth> truth;
  truth->SetVolumeOfInterest(-8, 8, -8, 8, -4, 4);
  truth->SetVoxelSize(0.5);
  truth->SetPixelSize(1.0);
  truth->SetInputData(input);
  truth->Update();
  const std::vector<double> first = Values(truth->GetOutput(), "direction");
  auto fresh = [&](double pixel)
  {
    vtkNew<vtkFiberOrientationGroundTruth> t;
    t->SetVolumeOfInterest(-8, 8, -8, 8, -4, 4);
    t->SetVoxelSize(0.5);
    t->SetPixelSize(pixel);
    t->SetInputData(input);
    t->Update();
    return Values(t->GetOutput(), "direction");
  };
  ASSERT_EQ(first.size(), 256u);
  EXPECT_TRUE(SameBits(first, fresh(1.0)));
  input->GetPoints()->SetPoint(2, -6, -8, 1.5);
  input->Modified();
  truth->Update();
  const std::vector<double> moved = Values(truth->GetOutput(), "direction");
  EXPECT_FALSE(SameBits(first, moved));
  EXPECT_TRUE(SameBits(moved, fresh(1.0)));
  truth->SetPixelSize(2.0);
  truth->Update();
  EXPECT_EQ(Values(truth->GetOutput(), "direction").size(), 64u);
  EXPECT_TRUE(SameBits(Values(truth->GetOutput(), "direction"), fresh(2.0)));
}
