// SubstrateMesher: the periodic mesh is a closed, outward 2-manifold once opposite faces are
// identified, its cut vertices lie on the faces, and it encloses the polygon-prism volume of its
// straight fibers exactly; open models give capped closed tubes; the PLY holds what MC/DC parses.
#include "Mesh/SubstrateMesher.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>

using namespace fiberpli;

namespace
{

struct Collected
{
  std::vector<Vec3> vertices;
  std::vector<std::array<std::int64_t, 3>> triangles;
  std::size_t surfaces = 0;
  std::size_t innerSurfaces = 0;
};

Collected collect(const FiberModel& m, const PeriodicCell& cell, const SubstrateMeshOptions& o,
  const std::vector<std::vector<double>>* inner = nullptr)
{
  Collected c;
  const Status s = meshSubstrate(m, inner, cell, o,
    [&](const SubstrateSurface& surface)
    {
      const auto first = static_cast<std::int64_t>(c.vertices.size());
      c.vertices.insert(c.vertices.end(), surface.vertices.begin(), surface.vertices.end());
      for (auto t : surface.triangles)
      {
        c.triangles.push_back({ t[0] + first, t[1] + first, t[2] + first });
      }
      ++c.surfaces;
      c.innerSurfaces += surface.inner ? 1 : 0;
      return true;
    });
  EXPECT_TRUE(s.ok()) << s.error;
  return c;
}

Fiber line(const Vec3& start, const Vec3& step, int links, double radius, std::int64_t id)
{
  Fiber f;
  f.id = id;
  for (int i = 0; i <= links; ++i)
  {
    f.points.push_back(start + step * static_cast<double>(i));
    f.radii.push_back(radius);
  }
  return f;
}

/// Every directed edge once and its reverse once, after identifying vertices by position with the
/// upper faces of the cell mapped onto the lower ones: a closed, consistently oriented 2-manifold.
void expectClosedManifold(const Collected& c, const PeriodicCell* cell)
{
  std::map<std::array<double, 3>, std::int64_t> ids;
  std::vector<std::int64_t> id(c.vertices.size());
  for (std::size_t v = 0; v < c.vertices.size(); ++v)
  {
    std::array<double, 3> key{ c.vertices[v].x, c.vertices[v].y, c.vertices[v].z };
    if (cell != nullptr)
    {
      for (int a = 0; a < 3; ++a)
      {
        if (key[a] == cell->hi[a])
        {
          key[a] = cell->lo[a];
        }
      }
    }
    id[v] = ids.emplace(key, static_cast<std::int64_t>(ids.size())).first->second;
  }
  std::map<std::pair<std::int64_t, std::int64_t>, int> directed;
  for (const auto& t : c.triangles)
  {
    for (int i = 0; i < 3; ++i)
    {
      const std::int64_t a = id[static_cast<std::size_t>(t[i])];
      const std::int64_t b = id[static_cast<std::size_t>(t[(i + 1) % 3])];
      ASSERT_NE(a, b) << "degenerate triangle";
      ++directed[{ a, b }];
    }
  }
  std::size_t bad = 0;
  for (const auto& [edge, count] : directed)
  {
    const auto reverse = directed.find({ edge.second, edge.first });
    if (count != 1 || reverse == directed.end() || reverse->second != 1)
    {
      ++bad;
    }
  }
  EXPECT_EQ(bad, 0u) << "of " << directed.size() << " directed edges";
}

/// Enclosed volume: flux of F = (x − xmin, 0, 0) through the mesh plus the cross-sections on the
/// face x = xmax (closed by the identification); for an open model the mesh alone.
double enclosedVolume(const Collected& c, const PeriodicCell* cell)
{
  const double x0 = cell != nullptr ? cell->lo.x : 0.0;
  double v = 0.0;
  double cap = 0.0;
  for (const auto& t : c.triangles)
  {
    const Vec3& p0 = c.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& p1 = c.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& p2 = c.vertices[static_cast<std::size_t>(t[2])];
    const Vec3 n = cross(p1 - p0, p2 - p0) * 0.5;
    v += n.x * ((p0.x + p1.x + p2.x) / 3.0 - x0);
    if (cell != nullptr)
    {
      const Vec3* p[3] = { &p0, &p1, &p2 };
      for (int i = 0; i < 3; ++i)
      {
        const Vec3& a = *p[i];
        const Vec3& b = *p[(i + 1) % 3];
        if (a.x == cell->hi.x && b.x == cell->hi.x)
        {
          cap -= 0.5 * (a.y * b.z - a.z * b.y);
        }
      }
    }
  }
  return cell != nullptr ? v + (cell->hi.x - cell->lo.x) * cap : v;
}

double polygonArea(double r, int n)
{
  return 0.5 * n * r * r * std::sin(2.0 * M_PI / n);
}

PeriodicCell boxCell()
{
  PeriodicCell cell;
  cell.lo = { 0.0, 0.0, 0.0 };
  cell.hi = { 10.0, 12.0, 8.0 };
  return cell;
}

/// Four straight fibers closed through the cell along x, y, z and the diagonal (10, 12, 0), apart
/// from each other. Their cross-sections with the face x = xmax are closed polygons (enclosedVolume
/// needs that); diagonalZ = 0 puts the diagonal one across the face z = 0 instead.
FiberModel straightPeriodicModel(double diagonalZ = 4.0)
{
  FiberModel m;
  m.fibers.push_back(line({ -3.0, 3.1, 2.2 }, { 2.5, 0.0, 0.0 }, 4, 1.0, 0));
  m.fibers.push_back(line({ 7.3, 1.0, 5.7 }, { 0.0, 3.0, 0.0 }, 4, 0.8, 1));
  m.fibers.push_back(line({ 3.7, 9.5, -2.0 }, { 0.0, 0.0, 2.0 }, 4, 0.9, 2));
  m.fibers.push_back(line({ 3.7, 6.5, diagonalZ }, { 2.0, 2.4, 0.0 }, 5, 0.5, 3));
  return m;
}

} // namespace

TEST(SubstrateMesher, PeriodicMeshIsClosedModuloTheCellAndEnclosesThePrismVolume)
{
  const PeriodicCell cell = boxCell();
  const FiberModel m = straightPeriodicModel();
  double expectedByRadius[4] = { 10.0, 12.0, 8.0, std::sqrt(244.0) }; // loop lengths
  for (int sides : { 5, 12, 32 })
  {
    for (double spacing : { 0.0, 1.3 })
    {
      SubstrateMeshOptions o;
      o.sides = sides;
      o.ringSpacing = spacing;
      const Collected c = collect(m, cell, o);
      EXPECT_EQ(c.surfaces, 4u);
      for (const Vec3& p : c.vertices)
      {
        for (int a = 0; a < 3; ++a)
        {
          ASSERT_GE(p[a], cell.lo[a]);
          ASSERT_LE(p[a], cell.hi[a]);
        }
      }
      expectClosedManifold(c, &cell);
      double expected = 0.0;
      for (std::size_t f = 0; f < m.fibers.size(); ++f)
      {
        expected += polygonArea(m.fibers[f].radii[0], sides) * expectedByRadius[f];
      }
      EXPECT_NEAR(enclosedVolume(c, &cell), expected, 1e-9 * expected) << sides << " sides";
    }
  }
}

TEST(SubstrateMesher, FibersAcrossAFaceAndACellEdgeStayClosed)
{
  // The diagonal fiber's rings have vertices exactly on z = 0 and cross the faces z, x and y.
  const PeriodicCell cell = boxCell();
  for (int sides : { 4, 6, 13 })
  {
    SubstrateMeshOptions o;
    o.sides = sides;
    expectClosedManifold(collect(straightPeriodicModel(0.0), cell, o), &cell);
  }
}

TEST(SubstrateMesher, CutVerticesOnOppositeFacesMatchExactly)
{
  const PeriodicCell cell = boxCell();
  FiberModel m;
  m.fibers.push_back(straightPeriodicModel().fibers[0]);
  const Collected c = collect(m, cell, SubstrateMeshOptions{});
  std::map<std::pair<double, double>, int> lowFace;
  std::map<std::pair<double, double>, int> highFace;
  for (const Vec3& p : c.vertices)
  {
    if (p.x == cell.lo.x)
    {
      ++lowFace[{ p.y, p.z }];
    }
    if (p.x == cell.hi.x)
    {
      ++highFace[{ p.y, p.z }];
    }
  }
  EXPECT_EQ(
    lowFace.size(), 32u); // the plane x = 0 ≡ 10 cuts the 16 quads of one link: 2 edges each
  EXPECT_EQ(lowFace, highFace);
}

TEST(SubstrateMesher, UndulatingLoopsStayClosedAndNearTheirTubeVolume)
{
  PeriodicCell cell;
  cell.lo = { -5.0, -5.0, -5.0 };
  cell.hi = { 5.0, 5.0, 5.0 };
  FiberModel m;
  for (int f = 0; f < 2; ++f)
  {
    Fiber fiber;
    fiber.id = f;
    const int n = 40;
    for (int i = 0; i <= n; ++i)
    {
      const double t = 2.0 * M_PI * i / n;
      // Across the faces z = ±5 only (enclosedVolume needs closed sections on x = xmax).
      fiber.points.push_back(
        { -2.5 + 5.0 * f + 0.8 * std::sin(t), 0.8 * std::cos(2 * t), -5.3 + 10.0 * i / n });
      fiber.radii.push_back(1.1);
    }
    m.fibers.push_back(fiber);
  }
  SubstrateMeshOptions o;
  o.sides = 24;
  const Collected c = collect(m, cell, o);
  expectClosedManifold(c, &cell);
  // A gently bent polygon tube: volume ≈ polygon area × arc length (Pappus), within 1 %.
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < m.fibers[0].size(); ++i)
  {
    length += norm(m.fibers[0].points[i + 1] - m.fibers[0].points[i]);
  }
  const double expected = 2.0 * polygonArea(1.1, 24) * length;
  EXPECT_NEAR(enclosedVolume(c, &cell), expected, 0.01 * expected);
}

TEST(SubstrateMesher, OpenModelGivesCappedClosedTubesAndInnerSurfaces)
{
  FiberModel m;
  m.fibers.push_back(line({ 0.0, 0.0, 0.0 }, { 0.3, 0.4, 1.2 }, 6, 0.7, 0));
  m.fibers.push_back(line({ 5.0, 0.0, 0.0 }, { 0.0, 1.0, 0.0 }, 3, 0.4, 1));
  std::vector<std::vector<double>> inner = { std::vector<double>(7, 0.5),
    std::vector<double>(4, 0.3) };
  SubstrateMeshOptions o;
  o.sides = 9;
  const PeriodicCell none;
  const Collected outer = collect(m, none, o);
  expectClosedManifold(outer, nullptr);
  const double l0 = 6.0 * norm(Vec3{ 0.3, 0.4, 1.2 });
  const double expected = polygonArea(0.7, 9) * l0 + polygonArea(0.4, 9) * 3.0;
  EXPECT_NEAR(enclosedVolume(outer, nullptr), expected, 1e-9 * expected);

  const Collected both = collect(m, none, o, &inner);
  EXPECT_EQ(both.surfaces, 4u);
  EXPECT_EQ(both.innerSurfaces, 2u);
  expectClosedManifold(both, nullptr);
  // Each surface is outward: the volumes add up.
  const double withInner = expected + polygonArea(0.5, 9) * l0 + polygonArea(0.3, 9) * 3.0;
  EXPECT_NEAR(enclosedVolume(both, nullptr), withInner, 1e-9 * withInner);

  std::vector<std::vector<double>> tooBig = { std::vector<double>(7, 0.8),
    std::vector<double>(4, 0.3) };
  const Status s = meshSubstrate(m, &tooBig, none, o, [](const SubstrateSurface&) { return true; });
  EXPECT_NE(s.error.find("inner_radius 0.8 of fiber 0 (id 0) point 0"), std::string::npos)
    << s.error;
}

TEST(SubstrateMesher, PlyHoldsOnlyWhatMcdcParses)
{
  const PeriodicCell cell = boxCell();
  const FiberModel m = straightPeriodicModel();
  SubstrateMeshOptions o;
  o.sides = 7;
  std::ostringstream out;
  SubstrateMeshCounts counts;
  ASSERT_TRUE(writeSubstratePly(out, m, nullptr, cell, o, counts).ok());
  const Collected c = collect(m, cell, o);
  EXPECT_EQ(counts.vertices, c.vertices.size());
  EXPECT_EQ(counts.triangles, c.triangles.size());
  std::istringstream in(out.str());
  std::string lineText;
  std::size_t vertexLines = 0;
  std::size_t faceLines = 0;
  bool body = false;
  while (std::getline(in, lineText))
  {
    if (!body)
    {
      body = lineText == "end_header";
      EXPECT_EQ(lineText.find("normal"), std::string::npos);
      continue;
    }
    std::istringstream fields(lineText);
    std::vector<std::string> tokens;
    for (std::string t; fields >> t;)
    {
      tokens.push_back(t);
    }
    if (vertexLines < counts.vertices)
    {
      ASSERT_EQ(tokens.size(), 3u) << lineText;
      ++vertexLines;
    }
    else
    {
      ASSERT_EQ(tokens.size(), 4u) << lineText;
      EXPECT_EQ(tokens[0], "3");
      for (int k = 1; k < 4; ++k)
      {
        EXPECT_LT(std::stoull(tokens[k]), counts.vertices);
      }
      ++faceLines;
    }
  }
  EXPECT_EQ(vertexLines, counts.vertices);
  EXPECT_EQ(faceLines, counts.triangles);

  const std::string snippet = mcdcConfigSnippet("cell.ply", cell.lo, cell.hi);
  EXPECT_NE(snippet.find("ply cell.ply\nply_scale 0.001\n"), std::string::npos);
  EXPECT_NE(snippet.find("0.01 0.012 0.008\n</voxels>"), std::string::npos) << snippet;
}

TEST(SubstrateMesher, OptionsAreChecked)
{
  SubstrateMeshOptions o;
  o.sides = 2;
  EXPECT_NE(checkSubstrateMeshOptions(o).find("NumberOfSides is 2"), std::string::npos);
  o.sides = 8;
  o.ringSpacing = -1.0;
  EXPECT_NE(checkSubstrateMeshOptions(o).find("RingSpacing is -1"), std::string::npos);
  EXPECT_EQ(substrateSidesForTolerance(1.0, 1.0 - std::cos(M_PI / 10.0)), 10);
}

namespace
{

/// First crossing of the segment p → p + s with a triangle: parameter in (0, 1], or > 1 for none.
/// Edges count as hits on both triangles (inclusive bounds), so a step along a shared edge can
/// not slip between them.
double firstHit(const Collected& c, const Vec3& p, const Vec3& s, Vec3& normal)
{
  double best = 2.0;
  for (const auto& t : c.triangles)
  {
    const Vec3& a = c.vertices[static_cast<std::size_t>(t[0])];
    const Vec3 e1 = c.vertices[static_cast<std::size_t>(t[1])] - a;
    const Vec3 e2 = c.vertices[static_cast<std::size_t>(t[2])] - a;
    const Vec3 h = cross(s, e2);
    const double det = dot(e1, h);
    if (std::abs(det) < 1e-300)
    {
      continue;
    }
    const Vec3 q = p - a;
    const double u = dot(q, h) / det;
    if (u < -1e-9 || u > 1.0 + 1e-9)
    {
      continue;
    }
    const Vec3 r = cross(q, e1);
    const double v = dot(s, r) / det;
    if (v < -1e-9 || u + v > 1.0 + 1e-9)
    {
      continue;
    }
    const double tt = dot(e2, r) / det;
    if (tt > 1e-12 && tt <= 1.0 && tt < best)
    {
      best = tt;
      normal = normalized(cross(e1, e2));
    }
  }
  return best;
}

/// Distance from p to the nearest lattice image of the infinite line a + t·d.
double periodicAxisDistance(const Vec3& p, const Vec3& a, const Vec3& d, const PeriodicCell& cell)
{
  const Vec3 e = cell.edge();
  const Vec3 u = normalized(d);
  double best = std::numeric_limits<double>::infinity();
  for (int i = -2; i <= 2; ++i)
  {
    for (int j = -2; j <= 2; ++j)
    {
      for (int k = -2; k <= 2; ++k)
      {
        const Vec3 q = p - a - Vec3{ i * e.x, j * e.y, k * e.z };
        best = std::min(best, norm(q - u * dot(q, u)));
      }
    }
  }
  return best;
}

/// One step of a walker reflecting at the mesh and wrapping at the cell faces.
void walkStep(const Collected& c, const PeriodicCell& cell, Vec3& p, Vec3 s)
{
  for (int bounce = 0; bounce < 100 && norm2(s) > 0.0; ++bounce)
  {
    // Up to the nearest cell face first: the mesh is wrapped into the cell.
    double tFace = 1.0;
    int faceAxis = -1;
    for (int a = 0; a < 3; ++a)
    {
      if (s[a] > 0.0 && (cell.hi[a] - p[a]) / s[a] < tFace)
      {
        tFace = (cell.hi[a] - p[a]) / s[a];
        faceAxis = a;
      }
      if (s[a] < 0.0 && (cell.lo[a] - p[a]) / s[a] < tFace)
      {
        tFace = (cell.lo[a] - p[a]) / s[a];
        faceAxis = a;
      }
    }
    Vec3 n;
    const double tHit = firstHit(c, p, s * tFace, n);
    if (tHit <= 1.0)
    {
      const Vec3 hit = p + s * (tFace * tHit);
      Vec3 rest = s * (1.0 - tFace * tHit);
      const double side = dot(s, n) > 0.0 ? -1.0 : 1.0; // back to where the walker came from
      rest = rest - n * (2.0 * dot(rest, n));
      p = hit + n * (side * 1e-9);
      s = rest;
      continue;
    }
    p = p + s * tFace;
    s = s * (1.0 - tFace);
    if (faceAxis < 0)
    {
      return;
    }
    // Wrap to the opposite face.
    p[faceAxis] = s[faceAxis] > 0.0 ? cell.lo[faceAxis] : cell.hi[faceAxis];
  }
}

} // namespace

TEST(SubstrateMesher, RandomWalkersNeverCrossThePeriodicMesh)
{
  const PeriodicCell cell = boxCell();
  const FiberModel m = straightPeriodicModel();
  SubstrateMeshOptions o;
  o.sides = 10;
  const Collected c = collect(m, cell, o);
  const double inscribed = std::cos(M_PI / o.sides);
  std::mt19937_64 rng(7);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  auto axisDistance = [&](const Vec3& p, std::size_t f)
  {
    const Fiber& fiber = m.fibers[f];
    return periodicAxisDistance(
      p, fiber.points.front(), fiber.points.back() - fiber.points.front(), cell);
  };
  const double step = 0.15;
  int crossedIn = 0;
  int crossedOut = 0;
  for (int w = 0; w < 24; ++w)
  {
    const std::size_t f = static_cast<std::size_t>(w % 4);
    const bool intra = w < 16;
    Vec3 p;
    // Intra-axonal: inside the polygon of fiber f; extra-axonal: outside every circle.
    for (;;)
    {
      p = { cell.lo.x + uni(rng) * 10.0, cell.lo.y + uni(rng) * 12.0, cell.lo.z + uni(rng) * 8.0 };
      bool ok = intra ? axisDistance(p, f) < 0.9 * inscribed * m.fibers[f].radii[0] : true;
      for (std::size_t g = 0; g < 4 && !intra; ++g)
      {
        ok = ok && axisDistance(p, g) > m.fibers[g].radii[0] * 1.05;
      }
      if (ok)
      {
        break;
      }
    }
    for (int k = 0; k < 1500; ++k)
    {
      const Vec3 s = normalized(Vec3{ gauss(rng), gauss(rng), gauss(rng) }) * step;
      walkStep(c, cell, p, s);
      if (intra && axisDistance(p, f) > m.fibers[f].radii[0] + 1e-7)
      {
        ++crossedOut;
        break;
      }
      bool inside = false;
      for (std::size_t g = 0; g < 4 && !intra; ++g)
      {
        inside = inside || axisDistance(p, g) < inscribed * m.fibers[g].radii[0] - 1e-7;
      }
      if (inside)
      {
        ++crossedIn;
        break;
      }
    }
  }
  EXPECT_EQ(crossedOut, 0);
  EXPECT_EQ(crossedIn, 0);
}
