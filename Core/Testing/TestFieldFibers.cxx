// Fibers that follow an orientation field (docs/field-source.md): volume-fraction target, straight
// and bent fibers, reproducibility, two crossing populations, the agreement measure, bad options.
#include "Field/FieldAgreement.h"
#include "Field/FieldFibers.h"
#include "FieldTestFields.h"
#include "MemoryLimitGuard.h"
#include "Tissue/Beading.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace fiberpli;
using fiberpli::testing::bendAbout;
using fiberpli::testing::makeField;

namespace
{
bool onFace(const OrientationField& f, const Vec3& p)
{
  for (int a = 0; a < 3; ++a)
  {
    if (std::fabs(p[a] - f.lower()[a]) < 1e-9 || std::fabs(p[a] - f.upper()[a]) < 1e-9)
    {
      return true;
    }
  }
  return false;
}

/// True when the fiber's end `end` (reached along `outward`) is on a face or the field is empty
/// just beyond it.
bool endsOnBoundaryOrMask(const OrientationField& f, const Vec3& end, const Vec3& outward)
{
  return onFace(f, end) || !fieldIsFull(f, end + 1e-4 * normalized(outward));
}

double fiberVolume(const Fiber& fiber)
{
  double l = 0.0;
  for (std::size_t i = 1; i < fiber.points.size(); ++i)
  {
    l += distance(fiber.points[i - 1], fiber.points[i]);
  }
  return M_PI * fiber.radii[0] * fiber.radii[0] * l;
}

FieldFiberOptions options(double fraction, double radius, double segment)
{
  FieldFiberOptions o;
  o.volumeFraction = fraction;
  o.fiberRadius = radius;
  o.trace.segmentLength = segment;
  o.seed = 5;
  return o;
}
} // namespace

TEST(FieldFibers, UniformFieldGivesStraightFibersAtTheTargetFraction)
{
  const Vec3 axis = normalized(Vec3{ 1, 1, 0 });
  const OrientationField f =
    makeField({ 0, 0, 0 }, 1.0, { 21, 21, 11 }, [&](const Vec3&) { return axis; });
  const FieldFiberResult r = generateFieldFibers({ &f }, options(0.3, 0.5, 1.0));
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_GT(r.model.fibers.size(), 50u);
  EXPECT_DOUBLE_EQ(r.regionVolume, 20.0 * 20.0 * 10.0);
  double total = 0.0;
  for (const Fiber& fiber : r.model.fibers)
  {
    EXPECT_EQ(fiber.bundle, 0);
    for (std::size_t i = 0; i + 1 < fiber.points.size(); ++i)
    {
      EXPECT_LT(norm(cross(normalized(fiber.points[i + 1] - fiber.points[i]), axis)), 1e-9);
    }
    EXPECT_TRUE(onFace(f, fiber.points.front()) && onFace(f, fiber.points.back()));
    total += fiberVolume(fiber);
  }
  // The smallest count that reaches the target: without the last fiber it was still below.
  EXPECT_NEAR(r.volumeFraction, total / r.regionVolume, 1e-12);
  EXPECT_GE(r.volumeFraction, 0.3);
  EXPECT_LT((total - fiberVolume(r.model.fibers.back())) / r.regionVolume, 0.3);
  const FieldAgreement a = fieldAgreement(r.model, f);
  EXPECT_GT(a.voxels, 1000u);
  EXPECT_LT(a.meanErrorDegrees, 1e-6);
}

TEST(FieldFibers, BendFibersStayOnTheirCircleAndEndOnBoundaryOrMask)
{
  const OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 41, 41, 7 }, bendAbout(12.0, 28.0));
  FieldFiberOptions o =
    options(0.25, 0.4, 1.0); // SegmentLength 1 µm: R/12 at the inner edge, R/28 at the outer
  const FieldFiberResult r = generateFieldFibers({ &f }, o);
  ASSERT_TRUE(r.ok()) << r.error;
  // The region's volume is the box's times the share of non-empty grid points.
  EXPECT_NEAR(r.regionVolume / (40.0 * 40.0 * 6.0), nonEmptyShare(f), 1e-12);
  ASSERT_GT(r.model.fibers.size(), 20u);
  for (const Fiber& fiber : r.model.fibers)
  {
    ASSERT_GE(fiber.points.size(), 2u);
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const Vec3& p : fiber.points)
    {
      lo = std::min(lo, std::hypot(p.x, p.y));
      hi = std::max(hi, std::hypot(p.x, p.y));
    }
    EXPECT_LT(hi - lo, 0.01 * 0.5 * (lo + hi)) << "fiber " << fiber.id;
    const std::size_t n = fiber.points.size();
    EXPECT_TRUE(endsOnBoundaryOrMask(f, fiber.points[0], fiber.points[0] - fiber.points[1]));
    EXPECT_TRUE(
      endsOnBoundaryOrMask(f, fiber.points[n - 1], fiber.points[n - 1] - fiber.points[n - 2]));
  }
  const FieldAgreement a = fieldAgreement(r.model, f);
  EXPECT_GT(a.voxels, 200u);
  EXPECT_LT(a.meanErrorDegrees, 2.0);
}

TEST(FieldFibers, StoredSignsDoNotMatter)
{
  // The same bend with the sign of every other grid point flipped: the same fibers (a fiber whose
  // seed heading flipped is traced the other way round, so its points come reversed).
  const OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 31, 31, 5 }, bendAbout(8.0, 24.0));
  OrientationField flipped = f;
  for (std::size_t i = 0; i < flipped.vectors.size(); i += 2)
  {
    flipped.vectors[i] = -flipped.vectors[i];
  }
  const FieldFiberOptions o = options(0.2, 0.4, 1.0);
  const FieldFiberResult a = generateFieldFibers({ &f }, o);
  const FieldFiberResult b = generateFieldFibers({ &flipped }, o);
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a.model.fibers.size(), b.model.fibers.size());
  for (std::size_t i = 0; i < a.model.fibers.size(); ++i)
  {
    std::vector<Vec3> q = b.model.fibers[i].points;
    if (!(q.front() == a.model.fibers[i].points.front()))
    {
      std::reverse(q.begin(), q.end());
    }
    EXPECT_EQ(a.model.fibers[i].points, q) << "fiber " << i;
  }
}

TEST(FieldFibers, SameSeedSameModel)
{
  const OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 21, 21, 7 }, bendAbout(5.0, 18.0));
  FieldFiberOptions o = options(0.2, 0.4, 1.0);
  o.radiusSpread = 0.3;
  o.radiusDistribution = RadiusDistribution::Gamma;
  const FieldFiberResult a = generateFieldFibers({ &f }, o);
  const FieldFiberResult b = generateFieldFibers({ &f }, o);
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a.model.fibers.size(), b.model.fibers.size());
  for (std::size_t i = 0; i < a.model.fibers.size(); ++i)
  {
    EXPECT_EQ(a.model.fibers[i].points, b.model.fibers[i].points);
    EXPECT_EQ(a.model.fibers[i].radii, b.model.fibers[i].radii);
  }
  o.seed = 6;
  const FieldFiberResult c = generateFieldFibers({ &f }, o);
  ASSERT_TRUE(c.ok());
  EXPECT_NE(c.model.fibers[0].points, a.model.fibers[0].points);
}

TEST(FieldFibers, TwoCrossingFieldsGiveTwoPopulations)
{
  const OrientationField fx = makeField({ 0, 0, 0 }, 1.0, { 16, 16, 16 },
    [](const Vec3&) {
      return Vec3{ 1, 0, 0 };
    });
  const OrientationField fy = makeField({ 0, 0, 0 }, 1.0, { 16, 16, 16 },
    [](const Vec3&) {
      return Vec3{ 0, 1, 0 };
    });
  FieldFiberOptions o = options(0.3, 0.5, 1.0);
  o.populationShares = { 1.0, 3.0 };
  const FieldFiberResult r = generateFieldFibers({ &fx, &fy }, o);
  ASSERT_TRUE(r.ok()) << r.error;
  double volume[2] = { 0.0, 0.0 };
  for (const Fiber& fiber : r.model.fibers)
  {
    ASSERT_TRUE(fiber.bundle == 0 || fiber.bundle == 1);
    const Vec3 axis = fiber.bundle == 0 ? Vec3{ 1, 0, 0 } : Vec3{ 0, 1, 0 };
    EXPECT_LT(norm(cross(normalized(fiber.points.back() - fiber.points.front()), axis)), 1e-9);
    volume[fiber.bundle] += fiberVolume(fiber);
  }
  // Volume shares 1 : 3, to within one fiber (15 µm long, r = 0.5).
  const double oneFiber = M_PI * 0.25 * 15.0;
  EXPECT_NEAR(volume[0], 0.25 * (volume[0] + volume[1]), oneFiber);
  EXPECT_LT(fieldAgreement(r.model, fx, 0).meanErrorDegrees, 1e-6);
  EXPECT_LT(fieldAgreement(r.model, fy, 1).meanErrorDegrees, 1e-6);
  // The measure can fail: population 1 against the other field is 90° off.
  EXPECT_NEAR(fieldAgreement(r.model, fx, 1).meanErrorDegrees, 90.0, 1e-6);
}

TEST(FieldFibers, SixComponentArrayIsTwoPopulations)
{
  // One array with two axes per grid point: axis 1 (components 0-2) along x with alternating
  // signs and lengths, absent above z = 12; axis 2 (components 3-5) along -y, absent above z = 8.
  // It gives the fields two 3-component arrays give, hence the same model, and each population
  // follows its own axis.
  const std::array<int, 3> n{ 16, 16, 16 };
  const auto axis1 = [](const Vec3& p) { return p.z > 12.0 ? Vec3{} : Vec3{ 1, 0, 0 }; };
  const auto axis2 = [](const Vec3& p) { return p.z > 8.0 ? Vec3{} : Vec3{ 0, -1, 0 }; };
  const OrientationField fx = makeField({ 0, 0, 0 }, 1.0, n, axis1);
  const OrientationField fy = makeField({ 0, 0, 0 }, 1.0, n, axis2);
  std::vector<double> values, first, second; // the 6-component array and its two halves
  for (std::size_t i = 0; i < fx.size(); ++i)
  {
    const Vec3 p{ static_cast<double>(i % 16), static_cast<double>(i / 16 % 16),
      static_cast<double>(i / 256) };
    const double scale = i % 2 == 0 ? 2.5 : -0.5; // any length, any sign
    const Vec3 v1 = axis1(p) * scale;
    const Vec3 v2 = axis2(p) * (1.0 / scale);
    values.insert(values.end(), { v1.x, v1.y, v1.z, v2.x, v2.y, v2.z });
    first.insert(first.end(), { v1.x, v1.y, v1.z });
    second.insert(second.end(), { v2.x, v2.y, v2.z });
  }
  values[6 * 7 + 3] = second[3 * 7] = std::numeric_limits<double>::quiet_NaN(); // axis 2 of point 7
  std::vector<OrientationField> fields, halves, half;
  std::size_t notFinite = 0;
  ASSERT_EQ(orientationFieldsFromArray(values.data(), fx.size(), 6, fx, fields, notFinite), "");
  ASSERT_EQ(fields.size(), 2u);
  EXPECT_EQ(notFinite, 1u);
  for (const std::vector<double>* a : { &first, &second })
  {
    ASSERT_EQ(orientationFieldsFromArray(a->data(), fx.size(), 3, fx, half, notFinite), "");
    ASSERT_EQ(half.size(), 1u);
    halves.push_back(half[0]);
  }
  EXPECT_EQ(notFinite, 1u);
  EXPECT_EQ(fields[0].vectors, halves[0].vectors);
  EXPECT_EQ(fields[1].vectors, halves[1].vectors);
  EXPECT_TRUE(fields[1].origin == fx.origin && fields[1].dimensions == fx.dimensions);
  // Up to the sign, the analytic axes; the NaN triple is empty.
  for (std::size_t i = 0; i < fx.size(); ++i)
  {
    EXPECT_EQ(std::fabs(dot(fields[0].vectors[i], fx.vectors[i])), norm2(fx.vectors[i]));
    EXPECT_EQ(
      std::fabs(dot(fields[1].vectors[i], fy.vectors[i])), i == 7 ? 0.0 : norm2(fy.vectors[i]));
  }

  const FieldFiberOptions o = options(0.3, 0.5, 1.0);
  const FieldFiberResult six = generateFieldFibers({ &fields[0], &fields[1] }, o);
  const FieldFiberResult two = generateFieldFibers({ &halves[0], &halves[1] }, o);
  ASSERT_TRUE(six.ok() && two.ok()) << six.error << two.error;
  ASSERT_EQ(six.model.fibers.size(), two.model.fibers.size());
  EXPECT_EQ(six.regionVolume, two.regionVolume);
  for (std::size_t i = 0; i < six.model.fibers.size(); ++i)
  {
    EXPECT_EQ(six.model.fibers[i].points, two.model.fibers[i].points);
    EXPECT_EQ(six.model.fibers[i].radii, two.model.fibers[i].radii);
    EXPECT_EQ(six.model.fibers[i].bundle, two.model.fibers[i].bundle);
  }
  int perBundle[2] = { 0, 0 };
  for (const Fiber& fiber : six.model.fibers)
  {
    ++perBundle[fiber.bundle];
    // The absent parts are masks: population 0 stays at z <= 12.5, population 1 at z <= 8.5.
    for (const Vec3& p : fiber.points)
    {
      EXPECT_LE(p.z, (fiber.bundle == 0 ? 12.5 : 8.5) + 1e-9);
    }
  }
  EXPECT_GT(perBundle[0], 20);
  EXPECT_GT(perBundle[1], 20);
  const FieldAgreement a0 = fieldAgreement(six.model, fields[0], 0);
  const FieldAgreement a1 = fieldAgreement(six.model, fields[1], 1);
  EXPECT_GT(a0.voxels, 500u);
  EXPECT_GT(a1.voxels, 300u);
  EXPECT_LT(a0.meanErrorDegrees, 1e-6);
  EXPECT_LT(a1.meanErrorDegrees, 1e-6);
  EXPECT_NEAR(fieldAgreement(six.model, fields[0], 1).meanErrorDegrees, 90.0, 1e-6);

  // 3 components: one field; other counts and sizes are refused with the count.
  ASSERT_EQ(orientationFieldsFromArray(values.data(), fx.size(), 3, fx, fields, notFinite), "");
  EXPECT_EQ(fields.size(), 1u);
  EXPECT_EQ(orientationFieldsFromArray(values.data(), fx.size(), 4, fx, fields, notFinite),
    "has 4 components; an orientation array needs 3 (one axis per point) or 6 (two axes per point: "
    "components 0-2 and 3-5)");
  EXPECT_EQ(orientationFieldsFromArray(values.data(), 10, 6, fx, fields, notFinite),
    "has 10 tuples for 4096 grid points");
  EXPECT_TRUE(fields.empty());
}

TEST(FieldFibers, CountModeSplitsByShares)
{
  const OrientationField fx = makeField({ 0, 0, 0 }, 1.0, { 11, 11, 11 },
    [](const Vec3&) {
      return Vec3{ 1, 0, 0 };
    });
  const OrientationField fz = makeField({ 0, 0, 0 }, 1.0, { 11, 11, 11 },
    [](const Vec3&) {
      return Vec3{ 0, 0, 1 };
    });
  FieldFiberOptions o = options(0.3, 0.5, 1.0);
  o.numberOfFibers = 7;
  const FieldFiberResult r = generateFieldFibers({ &fx, &fz }, o);
  ASSERT_TRUE(r.ok()) << r.error;
  ASSERT_EQ(r.model.fibers.size(), 7u);
  int counts[2] = { 0, 0 };
  for (std::size_t i = 0; i < 7; ++i)
  {
    EXPECT_EQ(r.model.fibers[i].id, static_cast<std::int64_t>(i));
    ++counts[r.model.fibers[i].bundle];
  }
  EXPECT_EQ(counts[0], 4); // largest remainder of 3.5 : 3.5 goes to the first
  EXPECT_EQ(counts[1], 3);
}

TEST(FieldFibers, PrincipalAxisOfAKnownTensor)
{
  // d = (1, 2, 2)/3 with weight 3 plus x with weight 1: the largest eigenvector is known in closed
  // form only numerically, so check the eigen-equation instead.
  const Vec3 d = Vec3{ 1, 2, 2 } / 3.0;
  double m[9];
  for (int i = 0; i < 3; ++i)
  {
    for (int j = 0; j < 3; ++j)
    {
      m[3 * i + j] = 3.0 * d[i] * d[j] + (i == 0 && j == 0 ? 1.0 : 0.0);
    }
  }
  const Vec3 v = principalAxis(m);
  const Vec3 mv{ m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
    m[6] * v.x + m[7] * v.y + m[8] * v.z };
  EXPECT_LT(norm(cross(mv, v)), 1e-12);
  // Trace 4, the other two eigenvalues sum to what is left and are smaller.
  EXPECT_GT(dot(mv, v), 3.0);
}

TEST(FieldFibers, BadOptionsNameTheProperty)
{
  const OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 11, 11, 11 },
    [](const Vec3&) {
      return Vec3{ 1, 0, 0 };
    });
  FieldFiberOptions o = options(0.95, 0.5, 1.0);
  EXPECT_EQ(validateFieldFiberOptions(o, f, 1), "VolumeFraction is 0.95, must be in (0, 0.9]");
  o.volumeFraction = 0.0;
  EXPECT_EQ(validateFieldFiberOptions(o, f, 1), "VolumeFraction is 0, must be in (0, 0.9]");
  o = options(0.3, 0.5, -1.0);
  EXPECT_EQ(validateFieldFiberOptions(o, f, 1), "SegmentLength is -1, must be > 0");
  o = options(0.3, 6.0, 1.0);
  EXPECT_NE(validateFieldFiberOptions(o, f, 1).find("FiberRadius is 6"), std::string::npos);
  o = options(0.3, 0.5, 1.0);
  o.numberOfFibers = 2000000000;
  {
    const fiberpli::testing::MemoryLimitGuard limit("64M");
    const std::string problem = validateFieldFiberOptions(o, f, 1);
    EXPECT_NE(problem.find("NumberOfFibers 2000000000"), std::string::npos) << problem;
    EXPECT_NE(problem.find("memory budget"), std::string::npos) << problem;
  }
  const OrientationField empty =
    makeField({ 0, 0, 0 }, 1.0, { 5, 5, 5 }, [](const Vec3&) { return Vec3{}; });
  const FieldFiberResult r = generateFieldFibers({ &empty }, options(0.3, 0.5, 1.0));
  EXPECT_NE(r.error.find("empty everywhere"), std::string::npos) << r.error;
}

TEST(FieldFibers, SliversGiveAnErrorNotEndlessTinyFibers)
{
  // Along x but full only around the plane x = 5: every line is about 1 µm long, below a third of
  // the 4 µm segment, so no fiber is accepted and the generator gives up with an error.
  const OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 11, 11, 11 },
    [](const Vec3& p) {
      return p.x == 5.0 ? Vec3{ 1, 0, 0 } : Vec3{};
    });
  FieldFiberOptions o = options(0.3, 0.2, 4.0);
  const FieldFiberResult r = generateFieldFibers({ &f }, o);
  EXPECT_NE(r.error.find("slivers"), std::string::npos) << r.error;
  EXPECT_TRUE(r.model.empty());
  // With 2 µm segments the same lines are long enough: fibers 1 µm long through the sheet.
  o.trace.segmentLength = 2.0;
  const FieldFiberResult ok = generateFieldFibers({ &f }, o);
  ASSERT_TRUE(ok.ok()) << ok.error;
  for (const Fiber& fiber : ok.model.fibers)
  {
    EXPECT_NEAR(distance(fiber.points.front(), fiber.points.back()), 1.0, 1e-6);
  }
}

TEST(FieldFibers, BeadingAndMyelin)
{
  // Beading: along every traced fiber the radius has the requested coefficient of variation and its
  // mean over the points is the radius drawn (FiberRadius, constant distribution); the volume
  // counted is that of the beaded links. Myelin: inner radius = GRatio × radius at every point.
  const OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 31, 31, 7 }, bendAbout(8.0, 26.0));
  FieldFiberOptions o = options(0.2, 0.5, 1.0);
  o.realism.beadingCV = 0.2;
  o.realism.beadingLength = 4.0;
  o.realism.gRatio = 0.6;
  const FieldFiberResult r = generateFieldFibers({ &f }, o);
  ASSERT_TRUE(r.ok()) << r.error;
  double total = 0.0;
  int checked = 0;
  for (const Fiber& fiber : r.model.fibers)
  {
    ASSERT_EQ(fiber.innerRadii.size(), fiber.radii.size());
    double mean = 0.0;
    for (std::size_t i = 0; i < fiber.radii.size(); ++i)
    {
      EXPECT_NEAR(fiber.innerRadii[i], 0.6 * fiber.radii[i], 1e-12);
      mean += fiber.radii[i] / static_cast<double>(fiber.radii.size());
    }
    EXPECT_NEAR(mean, 0.5, 1e-9);
    if (fiber.size() >= 8)
    {
      EXPECT_NEAR(coefficientOfVariation(fiber.radii, false), 0.2, 1e-6) << "fiber " << fiber.id;
      ++checked;
    }
    for (std::size_t i = 1; i < fiber.size(); ++i)
    {
      total += M_PI * 0.5 *
        (fiber.radii[i - 1] * fiber.radii[i - 1] + fiber.radii[i] * fiber.radii[i]) *
        distance(fiber.points[i - 1], fiber.points[i]);
    }
  }
  EXPECT_GT(checked, 10);
  EXPECT_NEAR(r.volumeFraction, total / r.regionVolume, 1e-12);
  // Tortuosity is not the field source's: refused by name.
  o.realism.tortuosity = 1.1;
  EXPECT_NE(validateFieldFiberOptions(o, f, 1).find("Tortuosity"), std::string::npos);
}

TEST(FieldFibers, ProgressCanStopIt)
{
  const OrientationField f = makeField({ 0, 0, 0 }, 1.0, { 31, 31, 31 },
    [](const Vec3&) {
      return Vec3{ 1, 0, 0 };
    });
  int calls = 0;
  const FieldFiberResult r =
    generateFieldFibers({ &f }, options(0.5, 0.3, 1.0), [&](double) { return ++calls < 2; });
  EXPECT_TRUE(r.aborted);
  EXPECT_TRUE(r.error.empty());
  EXPECT_TRUE(r.model.empty());
  EXPECT_EQ(calls, 2);
}
