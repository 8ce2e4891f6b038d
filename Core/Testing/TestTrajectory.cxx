// Trajectory resampling and rotation-minimising frames (docs/tissue-models.md §2): arc-length
// spacing, perpendicular untwisted cross-sections (analytic helix twist), 180° reversals,
// validation.
#include "Tissue/Trajectory.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace fiberpli;

namespace
{
std::vector<Vec3> helix(double a, double b, double turns, int samples)
{
  std::vector<Vec3> p;
  for (int i = 0; i <= samples; ++i)
  {
    const double t = 2.0 * M_PI * turns * i / samples;
    p.push_back({ a * std::cos(t), a * std::sin(t), b * t });
  }
  return p;
}
} // namespace

TEST(Trajectory, StraightLineIsResampledToEqualLinks)
{
  const std::vector<Vec3> line{ { -30.0, 0.0, 0.0 }, { 30.0, 0.0, 0.0 } };
  const ResampledTrajectory t = resampleTrajectory(line, nullptr, 2.0);
  ASSERT_EQ(t.points.size(), 31u); // round(60/2) + 1
  for (std::size_t k = 0; k < t.points.size(); ++k)
  {
    EXPECT_NEAR(t.points[k].x, -30.0 + 2.0 * k, 1e-12);
    EXPECT_EQ(t.points[k].y, 0.0);
    EXPECT_EQ(t.scale[k], 1.0);
  }
  // 7 / 2 rounds to 4 links of 1.75.
  EXPECT_EQ(resampleTrajectory({ { 0, 0, 0 }, { 7, 0, 0 } }, nullptr, 2.0).points.size(), 5u);
  EXPECT_EQ(resampleTrajectory({ { 0, 0, 0 }, { 0.1, 0, 0 } }, nullptr, 2.0).points.size(), 2u);
}

TEST(Trajectory, CurveIsResampledByArcLengthThroughItsPoints)
{
  // A circle of radius 10 given by 13 points over a half turn: the Catmull–Rom curve stays close to
  // the circle and the resampled links are equal and ≈ l.
  std::vector<Vec3> arc;
  for (int i = 0; i <= 12; ++i)
  {
    const double t = M_PI * i / 12.0;
    arc.push_back({ 10.0 * std::cos(t), 10.0 * std::sin(t), 0.0 });
  }
  const ResampledTrajectory t = resampleTrajectory(arc, nullptr, 1.0);
  ASSERT_EQ(t.points.size(), static_cast<std::size_t>(std::lround(10.0 * M_PI)) + 1);
  const double link0 = distance(t.points[0], t.points[1]);
  for (std::size_t k = 0; k + 1 < t.points.size(); ++k)
  {
    EXPECT_NEAR(distance(t.points[k], t.points[k + 1]), link0, 2e-3);
    // The input polyline's chords sag by 10(1 − cos 7.5°) = 0.086; the curve must do better.
    EXPECT_NEAR(norm(t.points[k]), 10.0, 0.06);
  }
  EXPECT_NEAR(link0, 10.0 * M_PI / 31.0, 5e-3);
  EXPECT_EQ(t.points.front(), arc.front());
  EXPECT_EQ(t.points.back(), arc.back());
}

TEST(Trajectory, ScaleInterpolatesAlongTheCurve)
{
  const std::vector<Vec3> line{ { 0, 0, 0 }, { 10, 0, 0 }, { 20, 0, 0 } };
  const std::vector<double> scale{ 1.0, 2.0, 4.0 };
  const ResampledTrajectory t = resampleTrajectory(line, &scale, 1.0);
  ASSERT_EQ(t.points.size(), 21u);
  EXPECT_NEAR(t.scale[5], 1.5, 1e-9);
  EXPECT_NEAR(t.scale[10], 2.0, 1e-9);
  EXPECT_NEAR(t.scale[15], 3.0, 1e-9);
}

TEST(Trajectory, FramesArePerpendicularOrthonormalAndUntwistedOnAHelix)
{
  // Helix (a cos t, a sin t, b t): torsion τ = b/(a² + b²). A rotation-minimising frame turns
  // against the Frenet frame by dθ/ds = −τ (Bishop 1975), so the angle of u in (N, B) is θ0 − τ s.
  const double a = 10.0, b = 3.0;
  const ResampledTrajectory t = resampleTrajectory(helix(a, b, 2.0, 400), nullptr, 0.5);
  const TrajectoryFrames fr = transportFrames(t.points);
  const double c = std::sqrt(a * a + b * b);
  const double tau = b / (c * c);
  double previous = 0.0, twist = 0.0, s = 0.0, s1 = 0.0;
  for (std::size_t k = 0; k < t.points.size(); ++k)
  {
    EXPECT_NEAR(dot(fr.u[k], fr.tangent[k]), 0.0, 1e-9);
    EXPECT_NEAR(dot(fr.v[k], fr.tangent[k]), 0.0, 1e-9);
    EXPECT_NEAR(dot(fr.u[k], fr.v[k]), 0.0, 1e-9);
    EXPECT_NEAR(norm(fr.u[k]), 1.0, 1e-9);
    EXPECT_NEAR(dot(cross(fr.u[k], fr.v[k]), fr.tangent[k]), 1.0, 1e-9); // right-handed
    if (k > 0)
    {
      s += distance(t.points[k], t.points[k - 1]);
    }
    if (k == 0 || k + 1 == t.points.size())
    {
      continue; // one-sided tangents at the ends
    }
    const double tt = std::atan2(t.points[k].y, t.points[k].x);
    const Vec3 N{ -std::cos(tt), -std::sin(tt), 0.0 };
    const Vec3 B{ b * std::sin(tt) / c, -b * std::cos(tt) / c, a / c };
    const double theta = std::atan2(dot(fr.u[k], B), dot(fr.u[k], N));
    if (k == 1)
    {
      s1 = s;
    }
    else
    {
      twist += std::remainder(theta - previous, 2.0 * M_PI);
    }
    previous = theta;
    EXPECT_NEAR(twist, -tau * (s - s1), 0.01) << "point " << k;
  }
  // Two turns: a frame that twisted with the Frenet frame would show 0 here instead.
  EXPECT_LT(twist, -1.0);
}

TEST(Trajectory, PlanarCurveKeepsTheOutOfPlaneAxis)
{
  // The paper's example f(t) = (t³, t, 0): every minimal rotation is about ±e_z, so the frame
  // vector that starts as e_z stays e_z exactly (no twist) and the in-plane one stays in-plane.
  std::vector<Vec3> f;
  for (int i = -20; i <= 20; ++i)
  {
    const double t = 0.1 * i;
    f.push_back({ 10.0 * t * t * t, 10.0 * t, 0.0 });
  }
  const ResampledTrajectory t = resampleTrajectory(f, nullptr, 1.0);
  const TrajectoryFrames fr = transportFrames(t.points);
  // After the first rotation the z components of u and v are fixed: every later rotation is about
  // ±e_z, which leaves z components unchanged, so the out-of-plane part of each offset is constant.
  for (std::size_t k = 0; k < t.points.size(); ++k)
  {
    EXPECT_NEAR(fr.u[k].z, fr.u[0].z, 1e-12) << k;
    EXPECT_NEAR(fr.v[k].z, fr.v[0].z, 1e-12) << k;
    EXPECT_NEAR(fr.tangent[k].z, 0.0, 1e-15);
  }
}

TEST(Trajectory, HandlesHalfTurnReversals)
{
  // t_0 = −e_z is a 180° turn from the reference e_z (fastPLI aborts here).
  const TrajectoryFrames down = transportFrames({ { 0, 0, 0 }, { 0, 0, -1 }, { 0, 0, -2 } });
  for (std::size_t k = 0; k < 3; ++k)
  {
    EXPECT_TRUE(isFinite(down.u[k]) && isFinite(down.v[k]));
    EXPECT_NEAR(dot(down.u[k], down.tangent[k]), 0.0, 1e-15);
    EXPECT_NEAR(dot(cross(down.u[k], down.v[k]), down.tangent[k]), 1.0, 1e-15);
  }
  // A hairpin polyline reversing within a link.
  const std::vector<Vec3> hairpin{ { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 }, { 1, 0, 0 },
    { 0, 0, 0 } };
  const TrajectoryFrames h = transportFrames(hairpin);
  for (std::size_t k = 0; k < hairpin.size(); ++k)
  {
    EXPECT_TRUE(isFinite(h.u[k]) && isFinite(h.v[k])) << k;
    EXPECT_NEAR(norm(h.u[k]), 1.0, 1e-12) << k;
    EXPECT_NEAR(dot(h.u[k], h.tangent[k]), 0.0, 1e-12) << k;
  }
  // rotateMinimal(a, −a, ·) is a proper rotation taking a to −a.
  const Vec3 a = normalized(Vec3{ 1.0, 2.0, 3.0 });
  EXPECT_NEAR(distance(rotateMinimal(a, -a, a), -a), 0.0, 1e-12);
  const Vec3 w = normalized(cross(a, Vec3{ 0, 0, 1 }));
  const Vec3 x = cross(a, w);
  EXPECT_NEAR(dot(cross(rotateMinimal(a, -a, w), rotateMinimal(a, -a, x)), rotateMinimal(a, -a, a)),
    1.0, 1e-12);
}

TEST(Trajectory, ValidationNamesThePoint)
{
  EXPECT_NE(validateTrajectory({ { 0, 0, 0 } }).find("1 point"), std::string::npos);
  EXPECT_NE(validateTrajectory({}).find("needs at least 2"), std::string::npos);
  const std::string repeated = validateTrajectory({ { 0, 0, 0 }, { 1, 0, 0 }, { 1, 0, 0 } });
  EXPECT_NE(repeated.find("point 2"), std::string::npos) << repeated;
  EXPECT_NE(repeated.find("repeats point 1"), std::string::npos) << repeated;
  const std::string nan = validateTrajectory({ { 0, 0, 0 }, { 1, std::nan(""), 0 } });
  EXPECT_NE(nan.find("point 1"), std::string::npos) << nan;
  EXPECT_NE(nan.find("not finite"), std::string::npos) << nan;
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_NE(validateTrajectory({ { inf, 0, 0 }, { 1, 0, 0 } }).find("point 0"), std::string::npos);
  const std::vector<double> badScale{ 1.0, -1.0 };
  EXPECT_NE(validateTrajectory({ { 0, 0, 0 }, { 1, 0, 0 } }, &badScale).find("scale at point 1"),
    std::string::npos);
  const std::vector<double> shortScale{ 1.0 };
  EXPECT_FALSE(validateTrajectory({ { 0, 0, 0 }, { 1, 0, 0 } }, &shortScale).empty());
  EXPECT_TRUE(validateTrajectory({ { 0, 0, 0 }, { 1, 0, 0 }, { 0, 0, 0 } }).empty());
}

TEST(Trajectory, MinimumCircumradiusOfACircleAndALine)
{
  std::vector<Vec3> circle;
  for (int i = 0; i < 10; ++i)
  {
    circle.push_back({ 5.0 * std::cos(0.3 * i), 5.0 * std::sin(0.3 * i), 1.0 });
  }
  std::size_t where = 99;
  EXPECT_NEAR(minimumCircumradius(circle, &where), 5.0, 1e-9);
  EXPECT_GE(where, 1u);
  EXPECT_TRUE(std::isinf(minimumCircumradius({ { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 } })));
}
