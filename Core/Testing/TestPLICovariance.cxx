// Rotation and mirror covariance of every PLI view, registered and on the tilted sensor (where the
// image is stretched about its centre along the tilt azimuth). Turning the fiber model by 90°, 180°
// or 270° about z, or mirroring it in x or y, must turn every image of every view exactly:
//  - pixel (i, j) goes where the transform puts the voxel centre;
//  - the view of tilt azimuth φ_t goes to the azimuth of the transformed beam direction;
//  - polarizer angles: a rotation by α turns every fiber direction by α, so I'(ρ) = I(ρ − α);
//    a mirror maps directions φ → −φ and flips the handedness of the circular light, which for a
//    chain of retarders is the same as analysing at ρ + 90°, so I'(ρ) = I(90° − ρ).
// The model uses dyadic coordinates, so the transformed tissue is bitwise the transformed
// tissue: any difference comes from the ray marcher or the axis interpolation.
#include "PLI/PLIPipeline.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace fiberpli;
using namespace fiberpli::pli;

namespace
{
constexpr int kRot = 18; // 10° steps: closed under ρ → ρ ± 90° and ρ → 90° − ρ

/// (x, y) → (a·x + b·y, c·x + d·y), a signed permutation of the axes.
struct Transform
{
  const char* name;
  int a, b, c, d;
  Vec3 apply(const Vec3& p) const { return { a * p.x + b * p.y, c * p.x + d * p.y, p.z }; }
  bool mirror() const { return a * d - b * c < 0; }
  int rotationDeg() const { return static_cast<int>(std::lround(std::atan2(c, a) * 180.0 / M_PI)); }
};

const Transform kTransforms[] = {
  { "rot90", 0, -1, 1, 0 },
  { "rot180", -1, 0, 0, -1 },
  { "rot270", 0, 1, -1, 0 },
  { "mirrorX", -1, 0, 0, 1 },
  { "mirrorY", 1, 0, 0, -1 },
};

// Fibers in several directions, some inclined, with axon / myelin layers (parallel, isotropic
// and radial axes, so samples meet label boundaries and zero axes). Dyadic numbers only.
FiberModel model()
{
  FiberModel m;
  auto add = [&m](Vec3 c, Vec3 u, double r)
  {
    Fiber f;
    f.points = { c - 32.0 * u, c + 32.0 * u };
    f.radii = { r, r };
    m.fibers.push_back(f);
  };
  add({ -3.375, 2.125, 0.25 }, { 1.0, 0.25, 0.125 }, 2.8125);
  add({ 3.625, -2.875, -0.5 }, { 0.375, 1.0, -0.25 }, 2.40625);
  add({ 1.125, 4.0625, 1.0 }, { -0.75, 0.5, 0.625 }, 1.96875);
  add({ -4.25, -5.125, 0.0 }, { 0.5, -0.625, 0.875 }, 1.71875);
  return m;
}

PLIOptions options(Interp interp, double step)
{
  PLIOptions o;
  const double voi[6] = { -8, 8, -8, 8, -5, 5 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  o.voxelSize = 1.0;
  o.pixelSize = 1.0;
  o.opticalSigma = 0.0;
  o.noiseGain = 0.0;
  o.numberOfRotations = kRot;
  o.tiltAngle = 5.5;
  o.layers = "0.5 -0.004 10 p; 0.75 0 5 b; 1 0.004 1 r";
  o.interpolation = interp;
  o.stepSize = step;
  o.numberOfThreads = 1;
  return o;
}

PLIImage run(const FiberModel& m, const PLIOptions& o)
{
  PLIImage img;
  const Status st = runPLI(m, o, GridRange{}, img);
  EXPECT_TRUE(st.ok()) << st.error;
  return img;
}

int wrap(int k, int n)
{
  return ((k % n) + n) % n;
}
} // namespace

TEST(PLICovariance, EveryViewTurnsWithTheModelForEveryInterpolationAndStep)
{
  const FiberModel base = model();
  for (bool sensor : { false, true })
    for (TiltConvention conv : { TiltConvention::Physical, TiltConvention::FastPLI })
      for (Interp interp : { Interp::NN, Interp::Lerp, Interp::Slerp })
        for (double step : { 0.5, 1.0, 2.0 })
        {
          PLIOptions o = options(interp, step);
          o.tiltConvention =
            conv; // both conventions rotate the axes with the stage, either way round
          // The tilted sensor stretches about the image centre along the azimuth: both turn with T.
          o.tiltedSensor = sensor;
          const PLIImage ref = run(base, o);
          ASSERT_EQ(ref.views.size(), 5u);
          const std::int64_t n = ref.views[0].nx; // square image
          ASSERT_EQ(n, 16);
          for (const Transform& T : kTransforms)
          {
            FiberModel m = base;
            for (Fiber& f : m.fibers)
              for (Vec3& p : f.points)
                p = T.apply(p);
            const PLIImage img = run(m, o); // the VOI is symmetric, so it maps onto itself
            ASSERT_EQ(img.views.size(), 5u);
            double worst = 0.0;
            for (int v = 0; v < 5; ++v)
            {
              // Beam azimuth of view v (view 0 is untilted) and of its image under T.
              int w = 0;
              if (v > 0)
              {
                const double phi = (v - 1) * M_PI / 2;
                const Vec3 L = T.apply({ std::round(std::cos(phi)), std::round(std::sin(phi)), 0 });
                w = 1 + wrap(static_cast<int>(std::lround(std::atan2(L.y, L.x) * 2 / M_PI)), 4);
              }
              for (std::int64_t j = 0; j < n; ++j)
                for (std::int64_t i = 0; i < n; ++i)
                {
                  // Voxel centre relative to the image centre, in half-voxels (exact integers).
                  const Vec3 c = T.apply({ 2.0 * i + 1 - n, 2.0 * j + 1 - n, 0 });
                  const std::int64_t i2 = (static_cast<std::int64_t>(c.x) + n - 1) / 2;
                  const std::int64_t j2 = (static_cast<std::int64_t>(c.y) + n - 1) / 2;
                  for (int k = 0; k < kRot; ++k)
                  {
                    const int k2 =
                      T.mirror() ? wrap(kRot / 2 - k, kRot) : wrap(k + T.rotationDeg() / 10, kRot);
                    const double d =
                      std::fabs(img.views[w].at(i2, j2, k2) - ref.views[v].at(i, j, k));
                    worst = std::max(worst, d);
                  }
                }
              ASSERT_LT(worst, 1e-12 * o.lightIntensity)
                << T.name << " view " << v << " -> " << w << " interpolation "
                << static_cast<int>(interp) << " StepSize " << step << " convention "
                << static_cast<int>(conv) << " TiltedSensor " << sensor;
            }
          }
        }
}

TEST(PLICovariance, TheModelIsNotSymmetricSoTheTestCanFail)
{
  // Guard: if the model were symmetric under a transform, the covariance test would pass for
  // any permutation of the views. Every transform must change the untilted image.
  const FiberModel base = model();
  const PLIOptions o = options(Interp::Slerp, 1.0);
  const PLIImage ref = run(base, o);
  for (const Transform& T : kTransforms)
  {
    FiberModel m = base;
    for (Fiber& f : m.fibers)
      for (Vec3& p : f.points)
        p = T.apply(p);
    const PLIImage img = run(m, o);
    double diff = 0.0;
    for (std::size_t q = 0; q < ref.views[0].data.size(); ++q)
      diff = std::max(diff, std::fabs(img.views[0].data[q] - ref.views[0].data[q]));
    EXPECT_GT(diff, 100.0) << T.name;
  }
}
