// Tube meshes: watertight, outward oriented, exact polygonal volume, no twist at sharp bends.
#include "Mesh/TubeMesher.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

using namespace fiberpli;

namespace
{
Fiber makeFiber(const std::vector<Vec3>& pts, const std::vector<double>& radii)
{
  Fiber f;
  f.points = pts;
  f.radii = radii;
  return f;
}

Vec3 vertex(const TubeMesh& m, std::int64_t i)
{
  return { m.points[3 * i], m.points[3 * i + 1], m.points[3 * i + 2] };
}

/// Number of triangles on each undirected edge, and whether each directed edge occurs once only
/// (consistent orientation: a shared edge is walked in opposite directions by its two triangles).
void checkClosedAndOriented(const TubeMesh& m)
{
  std::map<std::pair<std::int64_t, std::int64_t>, int> directed;
  for (std::size_t t = 0; t < m.numberOfTriangles(); ++t)
  {
    for (int e = 0; e < 3; ++e)
    {
      const std::int64_t a = m.triangles[3 * t + e];
      const std::int64_t b = m.triangles[3 * t + (e + 1) % 3];
      ASSERT_NE(a, b) << "degenerate triangle " << t;
      ++directed[{ a, b }];
    }
  }
  for (const auto& [edge, count] : directed)
  {
    EXPECT_EQ(count, 1) << "directed edge used twice: inconsistent orientation";
    const auto reverse = directed.find({ edge.second, edge.first });
    EXPECT_TRUE(reverse != directed.end()) << "boundary edge " << edge.first << "-" << edge.second;
  }
}

/// Signed volume by the divergence theorem (positive for an outward-oriented closed mesh).
double signedVolume(const TubeMesh& m)
{
  double v = 0.0;
  for (std::size_t t = 0; t < m.numberOfTriangles(); ++t)
  {
    const Vec3 a = vertex(m, m.triangles[3 * t]);
    const Vec3 b = vertex(m, m.triangles[3 * t + 1]);
    const Vec3 c = vertex(m, m.triangles[3 * t + 2]);
    v += dot(a, cross(b, c)) / 6.0;
  }
  return v;
}
} // namespace

TEST(TubeMesher, StraightTubeHasTheExactPolygonalVolume)
{
  for (int sides : { 3, 8, 12, 33 })
  {
    FiberModel model;
    model.fibers.push_back(
      makeFiber({ { 0, 0, 0 }, { 0, 0, 2 }, { 0, 0, 5 }, { 0, 0, 10 } }, { 1.5, 1.5, 1.5, 1.5 }));
    TubeOptions o;
    o.sides = sides;
    TubeMesh m = meshTubes(model, o);
    ASSERT_EQ(m.numberOfPoints(), 4u * sides + 2u);
    ASSERT_EQ(m.numberOfTriangles(), 2u * sides * 3u + 2u * sides);
    checkClosedAndOriented(m);
    // A regular N-gon of circumradius r has area N/2·r²·sin(2π/N).
    const double exact = 10.0 * 0.5 * sides * 1.5 * 1.5 * std::sin(2.0 * M_PI / sides);
    EXPECT_NEAR(signedVolume(m), exact, 1e-3 * exact) << sides << " sides";
  }
}

TEST(TubeMesher, ConicalSegmentsFollowThePerPointRadius)
{
  FiberModel model;
  model.fibers.push_back(makeFiber({ { 0, 0, 0 }, { 4, 0, 0 } }, { 1.0, 2.0 }));
  TubeOptions o;
  o.sides = 64;
  TubeMesh m = meshTubes(model, o);
  checkClosedAndOriented(m);
  // Frustum of regular 64-gons: h/3·(A0 + A1 + sqrt(A0·A1)), A = N/2·r²·sin(2π/N).
  const double k = 0.5 * 64 * std::sin(2.0 * M_PI / 64);
  const double a0 = k * 1.0, a1 = k * 4.0;
  const double exact = 4.0 / 3.0 * (a0 + a1 + std::sqrt(a0 * a1));
  EXPECT_NEAR(signedVolume(m), exact, 1e-9 * exact);
  for (int s = 0; s < 64; ++s)
  {
    EXPECT_NEAR(std::hypot(m.points[3 * s + 1], m.points[3 * s + 2]), 1.0, 1e-12);
    EXPECT_NEAR(std::hypot(m.points[3 * (64 + s) + 1], m.points[3 * (64 + s) + 2]), 2.0, 1e-12);
  }
}

TEST(TubeMesher, NoTwistAtSharpBendsAndOnAHelix)
{
  // A zig-zag with 90° corners, a hairpin and a repeated point, then a helix.
  FiberModel model;
  model.fibers.push_back(makeFiber(
    { { 0, 0, 0 }, { 4, 0, 0 }, { 4, 4, 0 }, { 4, 4, 0 }, { 4, 4, 4 }, { 8, 4, 4 }, { 0, 4.5, 4 } },
    { 0.5, 0.5, 0.8, 0.8, 0.5, 0.5, 0.6 }));
  Fiber helix;
  for (int i = 0; i <= 60; ++i)
  {
    const double t = 0.2 * i;
    helix.points.push_back({ 5.0 * std::cos(t), 5.0 * std::sin(t), 1.0 * t });
    helix.radii.push_back(0.7);
  }
  model.fibers.push_back(helix);
  TubeOptions o;
  o.sides = 12;
  TubeMesh m = meshTubes(model, o);
  checkClosedAndOriented(m);
  EXPECT_GT(signedVolume(m), 0.0);
  // Twist shows as long diagonal edges between consecutive rings: with parallel transport every
  // vertex of ring i+1 lies next to the vertex of the same index of ring i. Check on the helix.
  const std::size_t firstHelixVertex = model.fibers[0].points.size() * 12 + 2;
  for (std::size_t i = 0; i + 1 < helix.points.size(); ++i)
  {
    const double step = distance(helix.points[i], helix.points[i + 1]);
    for (int s = 0; s < 12; ++s)
    {
      const Vec3 a = vertex(m, static_cast<std::int64_t>(firstHelixVertex + i * 12 + s));
      const Vec3 b = vertex(m, static_cast<std::int64_t>(firstHelixVertex + (i + 1) * 12 + s));
      EXPECT_LT(distance(a, b), step + 0.3 * 0.7) << "ring " << i << " vertex " << s;
    }
  }
  for (float x : m.normals)
  {
    ASSERT_TRUE(std::isfinite(x));
  }
}

TEST(TubeMesher, AnExactHairpinTurnsTheRingByTheDocumentedHalfTurn)
{
  // Out along a and straight back: the last ring axis is exactly −a. The ring frame then turns by π
  // about unit(a × e_m), e_m the axis least aligned with a (here e_z), as the bundle frames do.
  // For a = (3, 2, 1)/√14 the start frame u0 = unit(a × e_y) differs from that axis, so the half
  // turn really moves the ring (keeping u0 would be another, frame-dependent rule).
  const Vec3 a = normalized(Vec3{ 3.0, 2.0, 1.0 });
  FiberModel model;
  model.fibers.push_back(makeFiber({ { 0, 0, 0 }, 4.0 * a, { 0, 0, 0 } }, { 0.5, 0.5, 0.5 }));
  TubeOptions o;
  o.sides = 8;
  o.capping = false;
  const TubeMesh m = meshTubes(model, o);
  ASSERT_EQ(m.numberOfPoints(), 3u * 8u);
  const Vec3 u0 = normalized(cross(a, Vec3{ 0, 1, 0 }));
  const Vec3 k = normalized(cross(a, Vec3{ 0, 0, 1 }));
  const Vec3 u2 = 2.0 * dot(k, u0) * k - u0; // u0 turned by π about k
  ASSERT_GT(distance(u2, u0), 0.1);
  EXPECT_NEAR(distance(vertex(m, 0), 0.5 * u0), 0.0, 1e-12);
  EXPECT_NEAR(distance(vertex(m, 8), 4.0 * a + 0.5 * u0), 0.0, 1e-12);
  EXPECT_NEAR(distance(vertex(m, 16), 0.5 * u2), 0.0, 1e-12);
  for (int s = 0; s < 8; ++s) // the last ring stays perpendicular to its axis −a
  {
    EXPECT_NEAR(dot(vertex(m, 16 + s), a), 0.0, 1e-12) << s;
    EXPECT_NEAR(norm(vertex(m, 16 + s)), 0.5, 1e-12) << s;
  }
}

TEST(TubeMesher, OutputIsIndependentOfThreadCountAndCanBeAborted)
{
  FiberModel model;
  for (int f = 0; f < 600; ++f)
  {
    model.fibers.push_back(
      makeFiber({ { 0, 0, 1.0 * f }, { 3, 1, 1.0 * f }, { 5, 0, 1.0 * f } }, { 0.4, 0.4, 0.4 }));
  }
  TubeOptions o;
  o.numberOfThreads = 1;
  TubeMesh one = meshTubes(model, o);
  o.numberOfThreads = 2;
  TubeMesh two = meshTubes(model, o);
  EXPECT_EQ(one.points, two.points);
  EXPECT_EQ(one.triangles, two.triangles);
  EXPECT_EQ(one.triangleFiber.back(), 599);

  int calls = 0;
  TubeMesh aborted = meshTubes(model, o, [&](double) { return ++calls < 2; });
  EXPECT_TRUE(aborted.aborted);
  EXPECT_EQ(aborted.numberOfTriangles(), 0u);
}

TEST(TubeMesher, SidesOutsideTheRangeAreNamed)
{
  TubeOptions o;
  for (int bad : { -1, 0, 2, kMaxTubeSides + 1 })
  {
    o.sides = bad;
    EXPECT_EQ(
      checkTubeOptions(o), "NumberOfSides is " + std::to_string(bad) + ", must be in [3, 64]");
  }
  for (int good : { 3, 12, kMaxTubeSides })
  {
    o.sides = good;
    EXPECT_EQ(checkTubeOptions(o), "");
  }
}

TEST(TubeMesher, InnerTubesAreClosedOutwardAndFollowTheInnerRadius)
{
  // Two straight fibers, one myelinated (inner radius 0.9 of 1.5), one not: the inner tube of the
  // first is a closed outward tube of the polygonal volume at 0.9; the second has none.
  FiberModel model;
  model.fibers.push_back(makeFiber({ { 0, 0, 0 }, { 0, 0, 4 }, { 0, 0, 10 } }, { 1.5, 1.5, 1.5 }));
  model.fibers.back().innerRadii = { 0.9, 0.9, 0.9 };
  model.fibers.push_back(makeFiber({ { 5, 0, 0 }, { 5, 0, 10 } }, { 1.0, 1.0 }));
  TubeOptions o;
  o.sides = 16;
  const TubeMesh plain = meshTubes(model, o);
  EXPECT_TRUE(plain.triangleSurface.empty()); // off: today's mesh
  o.innerTubes = true;
  const TubeMesh both = meshTubes(model, o);
  checkClosedAndOriented(both);
  ASSERT_EQ(both.triangleSurface.size(), both.numberOfTriangles());
  // The outer tubes come first, unchanged.
  ASSERT_GT(both.points.size(), plain.points.size());
  EXPECT_TRUE(std::equal(plain.points.begin(), plain.points.end(), both.points.begin()));
  EXPECT_TRUE(std::equal(plain.triangles.begin(), plain.triangles.end(), both.triangles.begin()));
  TubeMesh inner, outer;
  for (std::size_t t = 0; t < both.numberOfTriangles(); ++t)
  {
    TubeMesh& part = both.triangleSurface[t] ? inner : outer;
    part.triangles.insert(
      part.triangles.end(), both.triangles.begin() + 3 * t, both.triangles.begin() + 3 * t + 3);
    part.triangleFiber.push_back(both.triangleFiber[t]);
  }
  inner.points = outer.points = both.points;
  const auto polygon = [](double r) { return 0.5 * 16 * r * r * std::sin(2.0 * M_PI / 16); };
  EXPECT_NEAR(signedVolume(inner), 10.0 * polygon(0.9), 1e-9);
  EXPECT_NEAR(signedVolume(outer), 10.0 * polygon(1.5) + 10.0 * polygon(1.0), 1e-9);
  for (std::int64_t f : inner.triangleFiber)
  {
    ASSERT_EQ(f, 0); // only the myelinated fiber
  }
  // The same for any thread count.
  o.numberOfThreads = 1;
  const TubeMesh one = meshTubes(model, o);
  o.numberOfThreads = 2;
  EXPECT_EQ(one.points, meshTubes(model, o).points);
}
