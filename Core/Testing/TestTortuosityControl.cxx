// TortuosityControl (docs/solver.md §5.3) against closed forms: the tortuosity of a sine fiber,
// its restoration after a flattening, and the invariants (ends, closure, straight fibers).
#include "Solver/TortuosityControl.h"

#include <cmath>

#include <gtest/gtest.h>

using namespace fiberpli;

namespace
{
constexpr double kPi = 3.14159265358979323846;

// A fiber along z from 0 to `span` with n points, deviating by amplitude·sin(2π waves z / span)
// along x (plus `bump` at the middle point along y).
Fiber sineFiber(double span, double amplitude, int waves, std::size_t n, double bump = 0.0)
{
  Fiber f;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double z = span * static_cast<double>(i) / static_cast<double>(n - 1);
    f.points.push_back(Vec3{ amplitude * std::sin(2.0 * kPi * waves * z / span), 0.0, z });
    f.radii.push_back(1.0);
  }
  f.points[n / 2].y += bump;
  return f;
}

// Path length of the curve x = A sin(kz) over one period, by a fine midpoint sum (independent of
// the polyline the rule measures).
double sineTortuosity(double amplitude, double wavelength)
{
  const int steps = 200000;
  const double k = 2.0 * kPi / wavelength;
  double length = 0.0;
  for (int i = 0; i < steps; ++i)
  {
    const double z = wavelength * (i + 0.5) / steps;
    const double slope = amplitude * k * std::cos(k * z);
    length += std::sqrt(1.0 + slope * slope) * wavelength / steps;
  }
  return length / wavelength;
}
} // namespace

TEST(TortuosityControl, TortuosityOfASineFiberIsItsArcLengthRatio)
{
  const Fiber f = sineFiber(40.0, 0.7, 4, 801);
  EXPECT_NEAR(fiberTortuosity(f), sineTortuosity(0.7, 10.0), 1e-4);
  const Fiber straight = sineFiber(40.0, 0.0, 4, 21);
  EXPECT_DOUBLE_EQ(fiberTortuosity(straight), 1.0);
  const Vec3 closure{ 0.0, 0.0, 40.0 };
  EXPECT_NEAR(
    fiberTortuosity(f, &closure), fiberTortuosity(f), 1e-12); // the closure is the chord here
}

TEST(TortuosityControl, RestoresAFlattenedSineToTheTarget)
{
  // Target: the tortuosity of amplitude 0.7 at wavelength 10; the fiber has half that amplitude.
  const double target = fiberTortuosity(sineFiber(40.0, 0.7, 4, 81));
  Fiber f = sineFiber(40.0, 0.35, 4, 81);
  const Vec3 first = f.points.front(), last = f.points.back();
  int calls = 0;
  while (controlTortuosity(f, target, 0.0, 0.05, 8.0) && calls < 1000)
  {
    ++calls;
  }
  EXPECT_GT(calls, 5); // 0.05 µm per call: the 0.35 µm of amplitude take several calls
  EXPECT_LT(calls, 1000);
  EXPECT_NEAR(fiberTortuosity(f), target, 1e-9);
  // The shape is the sine of the target amplitude again (scaled, not deformed).
  for (std::size_t i = 0; i < f.size(); ++i)
  {
    EXPECT_NEAR(f.points[i].x, 0.7 * std::sin(2.0 * kPi * 4 * f.points[i].z / 40.0), 0.01) << i;
  }
  EXPECT_EQ(f.points.front(), first); // open ends lie on the axis and stay
  EXPECT_EQ(f.points.back(), last);
}

TEST(TortuosityControl, LeavesFibersAtTheTargetOrStraightAlone)
{
  Fiber f = sineFiber(40.0, 0.7, 4, 81);
  const double tau = fiberTortuosity(f);
  const Fiber before = f;
  EXPECT_FALSE(controlTortuosity(f, tau, 0.0, 0.1, 8.0));           // at the target
  EXPECT_FALSE(controlTortuosity(f, tau + 0.001, 0.002, 0.1, 8.0)); // within the tolerance
  EXPECT_FALSE(controlTortuosity(f, 0.0, 0.0, 0.1, 8.0));           // off
  EXPECT_EQ(f.points, before.points);
  Fiber straight = sineFiber(40.0, 0.0, 4, 21);
  const Fiber s0 = straight;
  EXPECT_FALSE(controlTortuosity(straight, 1.1, 0.0, 0.1, 8.0));
  EXPECT_EQ(straight.points, s0.points);
}

TEST(TortuosityControl, SmoothPartOnlyABumpIsNotAmplified)
{
  // A flattened sine with a one-point bump: the bump is finer than the shortest kept wavelength
  // (8 µm), so the growth follows the sine and the bump stays about as it was.
  const double target = fiberTortuosity(sineFiber(40.0, 0.7, 4, 81));
  Fiber f = sineFiber(40.0, 0.35, 4, 81, 0.3);
  for (int i = 0; i < 1000 && controlTortuosity(f, target, 0.0, 0.05, 8.0); ++i)
  {
  }
  EXPECT_NEAR(f.points[40].y, 0.3, 0.1); // a kink scaled with k would have doubled it
}

TEST(TortuosityControl, AClosedFiberStaysClosed)
{
  // A fiber closed through a cell of edge 40 along z, shifted off the axis: after scaling, the
  // last point is still exactly the first plus the closure, and the mean position is kept.
  Fiber f = sineFiber(40.0, 0.3, 2, 41);
  for (Vec3& p : f.points)
  {
    p.x += 5.0;
  }
  const Vec3 closure{ 0.0, 0.0, 40.0 };
  f.points.back() = f.points.front() + closure;
  const double target = 1.02;
  int calls = 0;
  while (controlTortuosity(f, target, 0.0, 0.05, 8.0, &closure) && calls < 1000)
  {
    ++calls;
    ASSERT_EQ(f.points.back(), f.points.front() + closure);
  }
  EXPECT_NEAR(fiberTortuosity(f, &closure), target, 2e-3);
  double meanX = 0.0;
  for (std::size_t i = 0; i + 1 < f.size(); ++i)
  {
    meanX += f.points[i].x;
  }
  EXPECT_NEAR(meanX / (f.size() - 1), 5.0, 1e-9);
}

TEST(TortuosityControl, AWavelengthLimitScalesOnlyTheShortBends)
{
  // A fiber closed through a cell of edge 60 along z: a sweep of one wave over the cell
  // (wavelength 60, amplitude 2 along y) and a flattened undulation of six waves (wavelength 10,
  // amplitude 0.2 along x). With modes up to 15 µm only the undulation grows: the sweep stays
  // exactly as it was (its mode is outside the band) and the x-amplitude reaches what the target
  // needs; with every mode, the sweep grows too.
  const double span = 60.0;
  const std::size_t n = 241;
  const auto fiber = [&](double sweep, double wiggle)
  {
    Fiber f;
    for (std::size_t i = 0; i < n; ++i)
    {
      const double z = span * static_cast<double>(i) / static_cast<double>(n - 1);
      f.points.push_back(Vec3{
        wiggle * std::sin(2.0 * kPi * 6.0 * z / span), sweep * std::sin(2.0 * kPi * z / span), z });
      f.radii.push_back(1.0);
    }
    return f;
  };
  const Vec3 closure{ 0.0, 0.0, span };
  const double target = fiberTortuosity(fiber(2.0, 0.5), &closure);
  Fiber banded = fiber(2.0, 0.2);
  Fiber all = banded;
  const Fiber before = banded;
  for (int i = 0; i < 1000 && controlTortuosity(banded, target, 0.0, 0.05, 8.0, &closure, 15.0);
       ++i)
  {
  }
  for (int i = 0; i < 1000 && controlTortuosity(all, target, 0.0, 0.05, 8.0, &closure); ++i)
  {
  }
  EXPECT_NEAR(fiberTortuosity(banded, &closure), target, 1e-9);
  EXPECT_NEAR(fiberTortuosity(all, &closure), target, 1e-9);
  double sweepChange = 0.0, allSweepChange = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    sweepChange = std::max(sweepChange, std::fabs(banded.points[i].y - before.points[i].y));
    allSweepChange = std::max(allSweepChange, std::fabs(all.points[i].y - before.points[i].y));
    const double z = before.points[i].z;
    EXPECT_NEAR(banded.points[i].x, 0.5 * std::sin(2.0 * kPi * 6.0 * z / span), 0.02) << i;
  }
  EXPECT_LT(sweepChange, 1e-9);
  EXPECT_GT(allSweepChange, 0.1);
  // No mode in the band (the band ends below the shortest mode kept, 8 µm): nothing moves.
  Fiber none = before;
  EXPECT_FALSE(controlTortuosity(none, target, 0.0, 0.05, 8.0, &closure, 7.0));
  EXPECT_EQ(none.points, before.points);
}
