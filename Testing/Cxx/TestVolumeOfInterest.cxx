// VolumeOfInterest is checked by one Core function for PLISimulation and
// FiberOrientationGroundTruth (the ground truth once silently used the input bounds for a
// volume inverted on one axis, which PLISimulation rejects). Both refuse it with the same message
// and both accept the all-axes sentinel.
#include "ErrorCatcher.h"
#include "FiberTestData.h"
#include "vtkFiberOrientationGroundTruth.h"
#include "vtkPLISimulation.h"

#include <vtkImageData.h>

#include <gtest/gtest.h>

namespace
{
struct Outcome
{
  std::string errors;
  vtkIdType points;
};

template <class Filter>
Outcome RunWithVolume(const double voi[6])
{
  vtkNew<Filter> filter;
  vtkNew<ErrorCatcher> catcher;
  catcher->Watch(filter);
  filter->SetInputData(MakeTwoFibers());
  filter->SetVolumeOfInterest(voi[0], voi[1], voi[2], voi[3], voi[4], voi[5]);
  filter->SetVoxelSize(0.5);
  filter->SetPixelSize(1.0);
  filter->SetNumberOfThreads(1);
  filter->Update();
  return { catcher->Errors,
    vtkImageData::SafeDownCast(filter->GetOutputDataObject(0))->GetNumberOfPoints() };
}
} // namespace

TEST(VolumeOfInterest, InvertedOnOneAxisIsRefusedByBoth)
{
  const double inverted[6] = { 12, -2, -2, 2, -2, 2 };
  for (const Outcome& o : { RunWithVolume<vtkPLISimulation>(inverted),
         RunWithVolume<vtkFiberOrientationGroundTruth>(inverted) })
  {
    EXPECT_NE(
      o.errors.find("VolumeOfInterest x range [12, -2] must have min < max"), std::string::npos)
      << o.errors;
    EXPECT_EQ(o.points, 0);
  }
}

TEST(VolumeOfInterest, SentinelOnEveryAxisMeansTheInputBoundsForBoth)
{
  const double sentinel[6] = { 1, -1, 1, -1, 1, -1 };
  const Outcome sim = RunWithVolume<vtkPLISimulation>(sentinel);
  const Outcome truth = RunWithVolume<vtkFiberOrientationGroundTruth>(sentinel);
  EXPECT_TRUE(sim.errors.empty()) << sim.errors;
  EXPECT_TRUE(truth.errors.empty()) << truth.errors;
  EXPECT_GT(sim.points, 0);
  EXPECT_EQ(sim.points, truth.points); // the same pixel grid
}
