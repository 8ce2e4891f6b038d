// Orientation field and field-line tracing (docs/field-source.md §2–§3): sign-free interpolation,
// straight lines in a uniform field, circles in a bend, ends on the boundary and on the mask,
// closed field lines.
#include "Field/FieldTracer.h"
#include "Field/OrientationField.h"
#include "FieldTestFields.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace fiberpli;
using fiberpli::testing::bendAbout;
using fiberpli::testing::makeField;

namespace
{
double distanceToFaces(const OrientationField& f, const Vec3& p)
{
  double d = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a)
  {
    d = std::min({ d, std::fabs(p[a] - f.lower()[a]), std::fabs(p[a] - f.upper()[a]) });
  }
  return d;
}
} // namespace

TEST(OrientationField, RefusesFlatGridsAndCountsNaNVectors)
{
  OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 4, 4, 1 },
    [](const Vec3&) {
      return Vec3{ 1, 0, 0 };
    });
  EXPECT_NE(validateOrientationField(f).find("1 point(s) along z"), std::string::npos);
  f = makeField({ 0, 0, 0 }, 1.0, { 3, 3, 3 }, [](const Vec3&) { return Vec3{ 2, 0, 0 }; });
  EXPECT_EQ(validateOrientationField(f), "");
  f.vectors[0] = { std::nan(""), 0, 0 };
  f.vectors[1] = { 0, 0, 0 };
  EXPECT_EQ(normalizeOrientationField(f), 1u);
  EXPECT_EQ(norm2(f.vectors[0]), 0.0);
  EXPECT_DOUBLE_EQ(norm(f.vectors[2]), 1.0);
  EXPECT_DOUBLE_EQ(nonEmptyShare(f), 25.0 / 27.0);
}

TEST(OrientationField, OppositeSignsDoNotCancel)
{
  // Every other grid point stores −x: a plain average would vanish between them.
  OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 4, 4, 4 },
    [](const Vec3& p) {
      return (static_cast<int>(p.x + p.y + p.z) % 2) ? Vec3{ -1, 0, 0 } : Vec3{ 1, 0, 0 };
    });
  Vec3 d;
  ASSERT_TRUE(fieldDirection(f, { 1.5, 1.5, 1.5 }, { 0.3, 1, 0 }, d));
  EXPECT_NEAR(d.x, 1.0, 1e-15);
  ASSERT_TRUE(fieldDirection(f, { 1.5, 1.5, 1.5 }, { -1, 0, 0 }, d));
  EXPECT_NEAR(d.x, -1.0, 1e-15);                         // aligned to the reference
  EXPECT_FALSE(fieldDirection(f, { 3.5, 1, 1 }, {}, d)); // outside the region
}

TEST(FieldTracer, UniformFieldGivesStraightLinesEndingOnTheBoundary)
{
  const Vec3 axis = normalized(Vec3{ 1, 1, 0 });
  const OrientationField f =
    makeField({ 0, 0, 0 }, 1.0, { 21, 21, 11 }, [&](const Vec3&) { return axis; });
  for (const TraceScheme scheme : { TraceScheme::RK2, TraceScheme::RK4 })
  {
    TraceOptions o;
    o.segmentLength = 1.5;
    o.scheme = scheme;
    const TracedLine line = traceFieldLine(f, { 7.3, 4.1, 5.5 }, o);
    ASSERT_GE(line.points.size(), 3u);
    EXPECT_EQ(line.backwardEnd, TraceEnd::Boundary);
    EXPECT_EQ(line.forwardEnd, TraceEnd::Boundary);
    EXPECT_LT(distanceToFaces(f, line.points.front()), 1e-9);
    EXPECT_LT(distanceToFaces(f, line.points.back()), 1e-9);
    // The chord through (7.3, 4.1) along (1, 1): from (3.2, 0) to (20, 16.8), length 16.8·√2.
    EXPECT_NEAR(line.length(), 16.8 * std::sqrt(2.0), 1e-9);
    for (std::size_t i = 0; i + 1 < line.points.size(); ++i)
    {
      const Vec3 seg = line.points[i + 1] - line.points[i];
      EXPECT_LT(norm(cross(normalized(seg), axis)), 1e-9);
      EXPECT_GE(norm(seg), o.segmentLength / 3.0 - 1e-12);
      EXPECT_LE(norm(seg), 4.0 * o.segmentLength / 3.0 + 1e-12);
    }
  }
}

TEST(FieldTracer, BendFieldKeepsTheRadiusWithRK4)
{
  // A quarter annulus 12..28 µm about the z axis in the box [0, 40]² × [0, 6]: field lines are
  // quarter circles from the face y = 0 to the face x = 0.
  const OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 41, 41, 7 }, bendAbout(12.0, 28.0));
  for (const double radius : { 15.0, 20.0, 25.0 })
  {
    TraceOptions o;
    o.segmentLength = radius / 20.0;
    const double phi = 0.7;
    const TracedLine line =
      traceFieldLine(f, { radius * std::cos(phi), radius * std::sin(phi), 3.0 }, o);
    EXPECT_EQ(line.backwardEnd, TraceEnd::Boundary);
    EXPECT_EQ(line.forwardEnd, TraceEnd::Boundary);
    double worst = 0.0;
    for (const Vec3& p : line.points)
    {
      worst = std::max(worst, std::fabs(std::hypot(p.x, p.y) - radius));
      EXPECT_NEAR(p.z, 3.0, 1e-12);
    }
    EXPECT_LT(worst, 0.01 * radius) << "bend radius " << radius;
    EXPECT_NEAR(line.length(), 0.5 * M_PI * radius, 0.02 * radius);
  }
}

TEST(FieldTracer, LinesEndOnTheMaskEdge)
{
  // Uniform along x inside a ball of radius 8 µm, empty outside: chords that end on the ball's
  // surface, to within the grid spacing (the mask's edge lies halfway between grid points).
  const Vec3 c{ 10, 10, 10 };
  const OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 21, 21, 21 },
    [&](const Vec3& p) {
      return distance(p, c) <= 8.0 ? Vec3{ 1, 0, 0 } : Vec3{};
    });
  TraceOptions o;
  o.segmentLength = 1.0;
  for (const Vec3 seed : { Vec3{ 10, 10, 10 }, Vec3{ 12.2, 13.1, 9.4 }, Vec3{ 6.5, 7.0, 14.0 } })
  {
    const TracedLine line = traceFieldLine(f, seed, o);
    EXPECT_EQ(line.backwardEnd, TraceEnd::Empty);
    EXPECT_EQ(line.forwardEnd, TraceEnd::Empty);
    for (const Vec3& end : { line.points.front(), line.points.back() })
    {
      EXPECT_NEAR(distance(end, c), 8.0, 1.0);
      EXPECT_NEAR(end.y, seed.y, 1e-12);
      EXPECT_NEAR(end.z, seed.z, 1e-12);
    }
    // Just beyond each end the field is empty.
    EXPECT_FALSE(fieldIsFull(f, line.points.front() - Vec3{ 1e-4, 0, 0 }));
    EXPECT_FALSE(fieldIsFull(f, line.points.back() + Vec3{ 1e-4, 0, 0 }));
  }
}

TEST(FieldTracer, ClosedFieldLinesStop)
{
  // A full annulus inside the box: every field line is a circle.
  const OrientationField f = makeField({ -30, -30, 0 }, 1.0, { 61, 61, 5 }, bendAbout(15.0, 25.0));
  TraceOptions o;
  o.segmentLength = 1.0;
  const TracedLine closed = traceFieldLine(f, { 20, 0, 2 }, o);
  EXPECT_EQ(closed.forwardEnd, TraceEnd::Closed);
  EXPECT_NEAR(closed.length(), 2.0 * M_PI * 20.0, 2.0 * o.segmentLength);
  EXPECT_LT(distance(closed.points.front(), closed.points.back()), o.segmentLength);
  o.maxLength = 50.0;
  const TracedLine capped = traceFieldLine(f, { 20, 0, 2 }, o);
  EXPECT_EQ(capped.forwardEnd, TraceEnd::LengthCap);
  EXPECT_LE(capped.length(), 50.0 + 1e-9);
  EXPECT_GT(capped.length(), 48.0);
}

TEST(FieldTracer, EmptySeedGivesOnePoint)
{
  const OrientationField f =
    makeField({ 0, 0, 0 }, 1.0, { 5, 5, 5 }, [](const Vec3&) { return Vec3{}; });
  EXPECT_EQ(traceFieldLine(f, { 2, 2, 2 }, TraceOptions{}).points.size(), 1u);
  TraceOptions bad;
  bad.segmentLength = 0.0;
  EXPECT_EQ(validateTraceOptions(bad), "SegmentLength is 0, must be > 0");
}
