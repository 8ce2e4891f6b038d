// The tilted-sensor mode (docs/pli-simulation.md §4.6): the tilted camera sees the section
// foreshortened by cos τ along the tilt azimuth, about the image centre. Checked against closed
// forms on an absorbing band (its optical-density integral and centroid along the tilt direction
// shrink by cos τ, across it nothing changes), bit-for-bit identity where the mode must change
// nothing, and independence of tile size, threads and pixel sub-range. Rotation covariance:
// TestPLICovariance.
#include "PLITestUtil.h"

#include "PLI/PLIPipeline.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace fiberpli;
using namespace fiberpli::pli;

namespace
{
constexpr double kDeg = M_PI / 180.0;

/// A band 0 < x < 40 µm (fiber along y, radius 20, axis at x = 20) through a 2 µm section: the
/// circle's sagitta over |z| <= 1 is 0.025 µm, so the band's cross-section is 79.99 µm².
FiberModel band()
{
  FiberModel m;
  Fiber f;
  f.points = { { 20, -100, 0 }, { 20, 100, 0 } };
  f.radii = { 20, 20 };
  m.fibers.push_back(f);
  return m;
}

PLIOptions bandOptions(bool sensor)
{
  PLIOptions o;
  const double voi[6] = { -64, 64, -8, 8, -1, 1 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  o.voxelSize = 0.5;
  o.pixelSize = 0.5;
  o.opticalSigma = 0.0;
  o.noiseGain = 0.0;
  o.numberOfRotations = 3;
  o.layers = "1 0 50 b"; // isotropic, μ = 50/mm: the image is the optical density
  o.tiltAngles = { 40.0 };
  o.tiltAzimuths = { 0.0, 90.0 };
  o.tiltedSensor = sensor;
  o.numberOfThreads = 1;
  return o;
}

PLIImage run(const FiberModel& m, const PLIOptions& o, GridRange px = GridRange{})
{
  PLIImage img;
  const Status st = runPLI(m, o, px, img);
  EXPECT_TRUE(st.ok()) << st.error;
  return img;
}

/// ∫ OD dx (µm) and the OD centroid (µm from the image centre) along row j of view v.
void odMoments(
  const PLIImage& img, int v, std::int64_t j, double pixel, double& integral, double& centroid)
{
  const double background = 0.25 * 26000.0; // ½·(½ I0) without birefringence or absorption
  const Stack& s = img.views[static_cast<std::size_t>(v)];
  double sum = 0.0, first = 0.0;
  for (std::int64_t i = 0; i < s.nx; ++i)
  {
    const double od = -std::log(s.at(i, j, 0) / background);
    const double x = (static_cast<double>(i) + 0.5 - 0.5 * static_cast<double>(s.nx)) * pixel;
    sum += od * pixel;
    first += od * pixel * x;
  }
  integral = sum;
  centroid = first / sum;
}
} // namespace

TEST(PLITiltedSensor, BandShrinksByCosTauAlongTheTiltAndNotAcrossIt)
{
  const FiberModel m = band();
  const PLIImage reg = run(m, bandOptions(false));
  const PLIImage sen = run(m, bandOptions(true));
  ASSERT_EQ(reg.views.size(), 3u);
  ASSERT_EQ(sen.views.size(), 3u);
  const double tau = 40.0 * kDeg, mu = 50e-3; // 1/µm
  const double area = 79.99;                  // µm², the band's cross-section in the section
  const std::int64_t j = 16;                  // any row: the band is uniform along y
  double iu, cu, ir, cr, is, cs;
  odMoments(reg, 0, j, 0.5, iu, cu);
  odMoments(reg, 1, j, 0.5, ir, cr);
  odMoments(sen, 1, j, 0.5, is, cs);
  // Untilted: μ·area, centred on the band. Registered tilted view: every ray crosses the
  // mid-plane at its pixel centre, path 1/cos τ longer: μ·area/cos τ, centroid unmoved.
  EXPECT_NEAR(iu, mu * area, 0.01 * mu * area);
  EXPECT_NEAR(cu, 20.0, 0.1);
  EXPECT_NEAR(ir, mu * area / std::cos(tau), 0.01 * mu * area);
  EXPECT_NEAR(cr, 20.0, 0.1);
  // Tilted sensor: the sensor point s sees the mid-plane point s/cos τ, so the band's image is
  // cos τ narrower (integral μ·area) and its centroid at 20·cos τ.
  EXPECT_NEAR(is, mu * area, 0.01 * mu * area);
  EXPECT_NEAR(cs, 20.0 * std::cos(tau), 0.1);
  EXPECT_GT(std::fabs(cs - cr), 4.0); // 20·(1 − cos 40°) = 4.7 µm: the test can fail
  // The view tilted along y (azimuth 90°) is stretched along y only, where the band is uniform:
  // the same image as registered, bit for bit; the untilted view never changes.
  EXPECT_EQ(sen.views[2].data, reg.views[2].data);
  EXPECT_EQ(sen.views[0].data, reg.views[0].data);
}

namespace
{
FiberModel crossing()
{
  FiberModel m;
  m.fibers.push_back(plitest::line({ -1.25, 0.5, 0.25 }, { 1.0, 0.25, 0.125 }, 12, 2.5));
  m.fibers.push_back(plitest::line({ 2.5, -1.5, -0.5 }, { -0.5, 1.0, 0.375 }, 12, 1.75));
  return m;
}

PLIOptions crossingOptions(bool sensor)
{
  PLIOptions o;
  const double voi[6] = { -6, 6, -6, 6, -3, 3 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  o.voxelSize = 0.5;
  o.pixelSize = 1.0;
  o.noiseGain = 0.0;
  o.numberOfRotations = 6;
  o.tiltAngle = 8.0;
  o.tiltAzimuths = { 0.0, 90.0, 200.0, 315.0 };
  o.refractiveIndex = 1.3;
  o.layers = "0.7 -0.004 5 p; 1 0.002 1 r";
  o.tiltedSensor = sensor;
  o.numberOfThreads = 1;
  return o;
}
} // namespace

// No tilted view (TiltAngle 0): the mode changes nothing, bit for bit; with tilted views it
// changes only them.
TEST(PLITiltedSensor, ChangesOnlyTheTiltedViews)
{
  const FiberModel m = crossing();
  PLIOptions off = crossingOptions(false), on = crossingOptions(true);
  off.tiltAngle = on.tiltAngle = 0.0;
  const PLIImage a = run(m, off), b = run(m, on);
  ASSERT_EQ(a.views.size(), 1u);
  ASSERT_EQ(b.views.size(), 1u);
  EXPECT_EQ(a.views[0].data, b.views[0].data);
  const PLIImage c = run(m, crossingOptions(false)), d = run(m, crossingOptions(true));
  ASSERT_EQ(c.views.size(), 5u);
  EXPECT_EQ(c.views[0].data, d.views[0].data);
  for (std::size_t v = 1; v < 5; ++v)
  {
    double diff = 0.0;
    for (std::size_t q = 0; q < c.views[v].data.size(); ++q)
      diff = std::max(diff, std::fabs(c.views[v].data[q] - d.views[v].data[q]));
    EXPECT_GT(diff, 1.0) << "view " << v; // 8° tilt on a 12 µm image: shifts of at most 0.06 µm
  }
}

// The stretched blocks are cut per tile and per thread: the image must not depend on either, and
// a pixel sub-range (one MPI rank's piece) is exactly the crop of the whole image.
TEST(PLITiltedSensor, IndependentOfTilesThreadsAndPieces)
{
  const FiberModel m = crossing();
  PLIOptions o = crossingOptions(true);
  o.tiltAngle = 30.0;
  const PLIImage ref = run(m, o);
  PLIOptions p = o;
  p.tileSize = 5;
  p.numberOfThreads = 2;
  const PLIImage tiled = run(m, p);
  for (std::size_t v = 0; v < ref.views.size(); ++v)
    EXPECT_EQ(tiled.views[v].data, ref.views[v].data) << "view " << v;
  const GridRange piece{ 7, 12, 2, 9 };
  const PLIImage part = run(m, o, piece);
  for (std::size_t v = 0; v < ref.views.size(); ++v)
    for (std::int64_t j = piece.j0; j < piece.j1; ++j)
      for (std::int64_t i = piece.i0; i < piece.i1; ++i)
        for (int k = 0; k < ref.views[v].nrho; ++k)
          ASSERT_EQ(part.views[v].at(i, j, k), ref.views[v].at(i, j, k))
            << v << " " << i << " " << j;
}
