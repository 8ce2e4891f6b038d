// Fibers that follow guide lines (docs/field-source.md §7): the length of a segment inside a ball,
// the rasterised field of straight and circular guides against their known axes, the mask around
// the guides, populations by bundle id, thread independence and bad input.
#include "Field/FieldAgreement.h"
#include "Field/FieldFibers.h"
#include "Field/GuideField.h"
#include "MemoryLimitGuard.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using namespace fiberpli;

namespace
{
/// Distance of p from the segment [a, b] (independent of the code under test).
double distanceToSegment(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 d = b - a;
  const double t = std::min(1.0, std::max(0.0, dot(p - a, d) / norm2(d)));
  return distance(p, a + t * d);
}

double distanceToGuides(const Vec3& p, const std::vector<GuideLine>& guides)
{
  double best = std::numeric_limits<double>::infinity();
  for (const GuideLine& g : guides)
  {
    for (std::size_t i = 1; i < g.points.size(); ++i)
    {
      best = std::min(best, distanceToSegment(p, g.points[i - 1], g.points[i]));
    }
  }
  return best;
}

/// Straight guides along u through the given offsets, from -half to +half, one point every step.
std::vector<GuideLine> straightGuides(
  const Vec3& u, const std::vector<Vec3>& offsets, double half, double step, std::int64_t bundle)
{
  std::vector<GuideLine> guides;
  for (const Vec3& o : offsets)
  {
    GuideLine g;
    g.bundle = bundle;
    for (double t = -half; t < half; t += step)
    {
      g.points.push_back(o + t * u);
    }
    g.points.push_back(o + half * u);
    guides.push_back(g);
  }
  return guides;
}

/// A bundle of half circles about the z axis: radii R + dr, heights dz, one point per degree.
std::vector<GuideLine> arcBundle(
  double R, const std::vector<double>& dr, const std::vector<double>& dz)
{
  std::vector<GuideLine> guides;
  for (double r : dr)
  {
    for (double z : dz)
    {
      GuideLine g;
      for (int deg = 0; deg <= 180; ++deg)
      {
        const double phi = deg * M_PI / 180.0;
        g.points.push_back({ (R + r) * std::cos(phi), (R + r) * std::sin(phi), z });
      }
      guides.push_back(g);
    }
  }
  return guides;
}

Vec3 gridPoint(const OrientationField& f, std::size_t index)
{
  const std::size_t nx = static_cast<std::size_t>(f.dimensions[0]);
  const std::size_t ny = static_cast<std::size_t>(f.dimensions[1]);
  return { f.origin.x + static_cast<double>(index % nx) * f.spacing.x,
    f.origin.y + static_cast<double>(index / nx % ny) * f.spacing.y,
    f.origin.z + static_cast<double>(index / (nx * ny)) * f.spacing.z };
}

FieldFiberOptions fiberOptions(double fraction, double radius, double segment)
{
  FieldFiberOptions o;
  o.volumeFraction = fraction;
  o.fiberRadius = radius;
  o.trace.segmentLength = segment;
  o.seed = 9;
  return o;
}

GuideFieldOptions guideOptions(double radius, double spacing)
{
  GuideFieldOptions o;
  o.radius = radius;
  o.spacing = spacing;
  return o;
}
} // namespace

TEST(GuideField, SegmentLengthInBall)
{
  const Vec3 c{ 1, 2, 3 };
  // Through the centre: the diameter; from the centre: the radius; at distance h: 2·sqrt(r²-h²).
  EXPECT_NEAR(segmentLengthInBall(c - Vec3{ 5, 0, 0 }, c + Vec3{ 5, 0, 0 }, c, 2.0), 4.0, 1e-12);
  EXPECT_NEAR(segmentLengthInBall(c, c + Vec3{ 0, 5, 0 }, c, 2.0), 2.0, 1e-12);
  EXPECT_NEAR(
    segmentLengthInBall(c + Vec3{ -5, 1.2, 0 }, c + Vec3{ 5, 1.2, 0 }, c, 2.0), 3.2, 1e-12);
  // Wholly inside: its own length; outside, tangent or of zero length: nothing.
  EXPECT_NEAR(segmentLengthInBall(c, c + Vec3{ 0.3, 0.4, 0 }, c, 2.0), 0.5, 1e-12);
  EXPECT_EQ(segmentLengthInBall(c + Vec3{ 3, 0, 0 }, c + Vec3{ 9, 0, 0 }, c, 2.0), 0.0);
  EXPECT_EQ(segmentLengthInBall(c + Vec3{ -5, 2, 0 }, c + Vec3{ 5, 2, 0 }, c, 2.0), 0.0);
  EXPECT_EQ(segmentLengthInBall(c, c, c, 2.0), 0.0);
  // Reversed: the same length.
  EXPECT_NEAR(segmentLengthInBall(c + Vec3{ 1, 0, 0 }, c - Vec3{ 5, 0, 0 }, c, 2.0), 3.0, 1e-12);
}

TEST(GuideField, StraightGuidesGiveParallelFibersInsideTheirTubes)
{
  // Three parallel guides along an oblique axis, 8 µm apart (separate tubes of radius 2.5),
  // sampled unevenly. Every non-empty grid point is within GuideRadius of a guide and carries the
  // guides' axis; every fiber is parallel to it and inside the tubes (a point where the field is
  // full has a full grid corner within half a voxel diagonal).
  const Vec3 u = normalized(Vec3{ 1.0, 0.5, 0.25 });
  const Vec3 v = normalized(cross(u, Vec3{ 0, 0, 1 }));
  const Vec3 w = cross(u, v);
  const std::vector<GuideLine> guides =
    straightGuides(u, { Vec3{}, 8.0 * v, 8.0 * w }, 20.0, 1.7, 0);
  const double r = 2.5, s = 0.5;
  const GuideFieldResult g = guideOrientationFields(guides, guideOptions(r, s));
  ASSERT_TRUE(g.ok()) << g.error;
  ASSERT_EQ(g.fields.size(), 1u);
  const OrientationField& f = g.fields[0];
  EXPECT_EQ(validateOrientationField(f), "");
  std::size_t full = 0;
  for (std::size_t i = 0; i < f.size(); ++i)
  {
    const double d = distanceToGuides(gridPoint(f, i), guides);
    if (std::fabs(d - r) < 1e-9)
    {
      continue; // on the tube's surface: either is right to rounding
    }
    ASSERT_EQ(norm2(f.vectors[i]) > 0.0, d < r) << "grid point " << i << " at distance " << d;
    if (d < r)
    {
      ++full;
      EXPECT_LT(norm(cross(f.vectors[i], u)), 1e-12);
    }
  }
  EXPECT_GT(full, 5000u);
  // The grid covers the guides padded by GuideRadius.
  for (const GuideLine& line : guides)
  {
    for (const Vec3& p : line.points)
    {
      for (int a = 0; a < 3; ++a)
      {
        EXPECT_LE(f.lower()[a], p[a] - r + 1e-9);
        EXPECT_GE(f.upper()[a], p[a] + r - 1e-9);
      }
    }
  }

  const FieldFiberResult fibers = generateFieldFibers({ &f }, fiberOptions(0.3, 0.3, 1.0));
  ASSERT_TRUE(fibers.ok()) << fibers.error;
  ASSERT_GT(fibers.model.fibers.size(), 30u);
  const double reach = r + 0.5 * std::sqrt(3.0) * s + 1e-9;
  for (const Fiber& fiber : fibers.model.fibers)
  {
    for (std::size_t i = 0; i + 1 < fiber.points.size(); ++i)
    {
      EXPECT_LT(norm(cross(normalized(fiber.points[i + 1] - fiber.points[i]), u)), 1e-9);
    }
    for (const Vec3& p : fiber.points)
    {
      EXPECT_LT(distanceToGuides(p, guides), reach) << "fiber " << fiber.id;
    }
  }
  const FieldAgreement a = fieldAgreement(fibers.model, f);
  EXPECT_GT(a.voxels, 1000u);
  EXPECT_LT(a.meanErrorDegrees, 1e-6);
}

TEST(GuideField, CircularArcBundleKeepsFibersAtItsRadius)
{
  // A bundle of 25 half circles of radius 30 ± 2 µm about the z axis (a 4 × 4 µm cross-section).
  // The field follows e_φ, the fibers stay inside the bundle's tube (radius 30 ± (2 + GuideRadius
  // + half a voxel diagonal)) and keep their own distance from the axis to within 2 % of it (the
  // field is symmetric about every radial plane except within GuideRadius of the arc's ends, and
  // the guides are chords of 1°, within half a degree of the circle's tangent: 1° at most).
  const double R = 30.0, r = 3.0, s = 1.0;
  const std::vector<GuideLine> guides = arcBundle(R, { -2, -1, 0, 1, 2 }, { -2, -1, 0, 1, 2 });
  const GuideFieldResult g = guideOrientationFields(guides, guideOptions(r, s));
  ASSERT_TRUE(g.ok()) << g.error;
  const OrientationField& f = g.fields[0];
  double sum = 0.0, worst = 0.0, inner = 0.0;
  std::size_t full = 0;
  OrientationField analytic = f; // e_φ on the same grid and mask
  for (std::size_t i = 0; i < f.size(); ++i)
  {
    if (!(norm2(f.vectors[i]) > 0.0))
    {
      continue;
    }
    const Vec3 p = gridPoint(f, i);
    const Vec3 ephi = normalized(Vec3{ -p.y, p.x, 0.0 });
    analytic.vectors[i] = ephi;
    const double degrees =
      std::acos(std::min(1.0, std::fabs(dot(f.vectors[i], ephi)))) * 180 / M_PI;
    if (p.y > r) // away from the ends at φ = 0 and 180°: symmetric
    {
      EXPECT_LT(degrees, 1.0) << "grid point " << p.x << " " << p.y << " " << p.z;
      inner = std::max(inner, degrees);
    }
    sum += degrees;
    worst = std::max(worst, degrees);
    ++full;
  }
  ASSERT_GT(full, 3000u);
  EXPECT_LT(sum / full, 0.5);

  const FieldFiberResult fibers = generateFieldFibers({ &f }, fiberOptions(0.25, 0.3, 1.0));
  ASSERT_TRUE(fibers.ok()) << fibers.error;
  ASSERT_GT(fibers.model.fibers.size(), 30u);
  const double reach = 2.0 + r + 0.5 * std::sqrt(3.0) * s;
  double largestSpread = 0.0;
  for (const Fiber& fiber : fibers.model.fibers)
  {
    double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
    for (const Vec3& p : fiber.points)
    {
      const double rho = std::hypot(p.x, p.y);
      lo = std::min(lo, rho);
      hi = std::max(hi, rho);
      EXPECT_LT(std::fabs(rho - R), reach) << "fiber " << fiber.id;
      EXPECT_LT(std::fabs(p.z), reach) << "fiber " << fiber.id;
    }
    EXPECT_LT(hi - lo, 0.02 * R) << "fiber " << fiber.id;
    largestSpread = std::max(largestSpread, hi - lo);
  }
  const FieldAgreement own = fieldAgreement(fibers.model, f);
  const FieldAgreement exact = fieldAgreement(fibers.model, analytic);
  EXPECT_GT(own.voxels, 1000u);
  EXPECT_LT(own.meanErrorDegrees, 2.0);
  EXPECT_LT(exact.meanErrorDegrees, 2.0);
  std::cout << "arc bundle: field error mean " << sum / full << "°, max " << worst
            << "° (away from the ends " << inner << "°); " << fibers.model.fibers.size()
            << " fibers, largest radial spread " << largestSpread << " µm; agreement "
            << own.meanErrorDegrees << "° (guide field), " << exact.meanErrorDegrees
            << "° (e_phi)\n";
}

TEST(GuideField, WeightsCountLengthNotPoints)
{
  // Two crossing guides in one population: the axis where they meet depends on their relative
  // weights. Sampling one of them 8 times more finely (collinear pieces) leaves the field as it
  // was; counting segments instead of length would tilt it towards the finely sampled guide.
  const Vec3 x{ 1, 0, 0 };
  const Vec3 d = normalized(Vec3{ 1, 1, 0 });
  std::vector<GuideLine> coarse = straightGuides(x, { Vec3{} }, 10.0, 2.0, 0);
  std::vector<GuideLine> fine = coarse;
  coarse.push_back(straightGuides(d, { Vec3{ 0, 0, 0.5 } }, 10.0, 2.0, 0)[0]);
  fine.push_back(straightGuides(d, { Vec3{ 0, 0, 0.5 } }, 10.0, 0.25, 0)[0]);
  const GuideFieldResult a = guideOrientationFields(coarse, guideOptions(2.0, 0.5));
  const GuideFieldResult b = guideOrientationFields(fine, guideOptions(2.0, 0.5));
  ASSERT_TRUE(a.ok() && b.ok());
  ASSERT_EQ(a.fields[0].dimensions, b.fields[0].dimensions);
  std::size_t mixed = 0;
  for (std::size_t i = 0; i < a.fields[0].size(); ++i)
  {
    const Vec3 va = a.fields[0].vectors[i], vb = b.fields[0].vectors[i];
    ASSERT_EQ(norm2(va) > 0.0, norm2(vb) > 0.0) << "grid point " << i;
    EXPECT_LT(norm(cross(va, vb)), 1e-9) << "grid point " << i;
    // Between the two directions where both guides reach: a mixed axis.
    mixed += norm(cross(va, x)) > 0.1 && norm(cross(va, d)) > 0.1;
  }
  EXPECT_GT(mixed, 10u);
}

TEST(GuideField, SameFieldForAnyThreadCount)
{
  const std::vector<GuideLine> guides = arcBundle(20.0, { -1, 1 }, { 0, 1.5 });
  GuideFieldOptions o = guideOptions(2.5, 0.7);
  o.threads = 1;
  const GuideFieldResult one = guideOrientationFields(guides, o);
  o.threads = 3;
  const GuideFieldResult three = guideOrientationFields(guides, o);
  ASSERT_TRUE(one.ok() && three.ok());
  EXPECT_EQ(one.fields[0].vectors, three.fields[0].vectors);
  EXPECT_GT(nonEmptyShare(one.fields[0]), 0.0);
}

TEST(GuideField, BundlesBecomePopulations)
{
  // Bundle 7 along x and bundle 3 along y cross in the middle. ByBundle: one field each, in the
  // order of the bundle ids, each population along its own guides everywhere, also where they
  // cross; One: a single field.
  std::vector<GuideLine> guides =
    straightGuides(Vec3{ 1, 0, 0 }, { Vec3{}, Vec3{ 0, 1, 0 } }, 12.0, 1.0, 7);
  const std::vector<GuideLine> across =
    straightGuides(Vec3{ 0, 1, 0 }, { Vec3{}, Vec3{ 0, 0, 1 } }, 12.0, 1.0, 3);
  guides.insert(guides.end(), across.begin(), across.end());
  GuideFieldOptions o = guideOptions(2.0, 0.5);
  o.populations = GuidePopulations::ByBundle;
  const GuideFieldResult g = guideOrientationFields(guides, o);
  ASSERT_TRUE(g.ok()) << g.error;
  ASSERT_EQ(g.fields.size(), 2u);
  EXPECT_EQ(g.bundles, (std::vector<std::int64_t>{ 3, 7 }));
  const FieldFiberResult fibers =
    generateFieldFibers({ &g.fields[0], &g.fields[1] }, fiberOptions(0.2, 0.25, 1.0));
  ASSERT_TRUE(fibers.ok()) << fibers.error;
  int counts[2] = { 0, 0 };
  for (const Fiber& fiber : fibers.model.fibers)
  {
    ++counts[fiber.bundle];
    const Vec3 axis = fiber.bundle == 0 ? Vec3{ 0, 1, 0 } : Vec3{ 1, 0, 0 };
    for (std::size_t i = 0; i + 1 < fiber.points.size(); ++i)
    {
      EXPECT_LT(norm(cross(normalized(fiber.points[i + 1] - fiber.points[i]), axis)), 1e-9);
    }
  }
  EXPECT_GT(counts[0], 5);
  EXPECT_GT(counts[1], 5);
  EXPECT_LT(fieldAgreement(fibers.model, g.fields[0], 0).meanErrorDegrees, 1e-6);
  EXPECT_LT(fieldAgreement(fibers.model, g.fields[1], 1).meanErrorDegrees, 1e-6);
  o.populations = GuidePopulations::One;
  const GuideFieldResult merged = guideOrientationFields(guides, o);
  ASSERT_TRUE(merged.ok());
  EXPECT_EQ(merged.fields.size(), 1u);
  EXPECT_TRUE(merged.bundles.empty());
  // A third bundle is one too many for ByBundle.
  guides.push_back(straightGuides(Vec3{ 0, 0, 1 }, { Vec3{ 5, 5, 0 } }, 3.0, 1.0, 11)[0]);
  o.populations = GuidePopulations::ByBundle;
  EXPECT_EQ(guideOrientationFields(guides, o).error,
    "GuidePopulations is 1 (ByBundle), but the guides have 3 bundle_id values (3, 7, 11); at most "
    "2 populations: use 0 (One)");
}

TEST(GuideField, BadInputNamesTheProperty)
{
  const std::vector<GuideLine> guides = straightGuides(Vec3{ 1, 0, 0 }, { Vec3{} }, 5.0, 1.0, 0);
  EXPECT_EQ(guideOrientationFields(guides, guideOptions(0.0, 0.5)).error,
    "GuideRadius is 0, must be > 0 (µm)");
  EXPECT_EQ(guideOrientationFields(guides, guideOptions(-1.0, 0.5)).error,
    "GuideRadius is -1, must be > 0 (µm)");
  EXPECT_NE(guideOrientationFields(guides, guideOptions(std::nan(""), 0.5))
              .error.find("GuideRadius is nan"),
    std::string::npos);
  EXPECT_EQ(guideOrientationFields(guides, guideOptions(2.0, 0.0)).error,
    "GuideSpacing is 0, must be > 0 (µm)");
  EXPECT_EQ(guideOrientationFields(guides, guideOptions(2.0, 3.0)).error,
    "GuideSpacing is 3 µm, must be at most GuideRadius (2 µm): a coarser grid can miss the guides");
  // No lines at all, or none with two distinct points.
  const std::string noLines = "Input: the guides have no line with two distinct points (a "
                              "vtkPolyData with polylines is needed, e.g. streamlines read from a "
                              ".tck file)";
  EXPECT_EQ(guideOrientationFields({}, guideOptions(2.0, 0.5)).error, noLines);
  GuideLine dot;
  dot.points = { Vec3{ 1, 1, 1 }, Vec3{ 1, 1, 1 } };
  EXPECT_EQ(guideOrientationFields({ dot }, guideOptions(2.0, 0.5)).error, noLines);
  std::vector<GuideLine> nan = guides;
  nan[0].points[3].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(guideOrientationFields(nan, guideOptions(2.0, 0.5)).error,
    "Input: point 3 of guide line 0 is not finite (NaN or infinite); every guide point must be a "
    "finite position in µm");
  GuideFieldOptions threads = guideOptions(2.0, 0.5);
  threads.threads = -1;
  EXPECT_NE(
    guideOrientationFields(guides, threads).error.find("NumberOfThreads is -1"), std::string::npos);
  // A grid beyond the memory budget is refused before it is allocated, naming GuideSpacing.
  const std::vector<GuideLine> long_ = straightGuides(Vec3{ 1, 1, 1 }, { Vec3{} }, 1e4, 100.0, 0);
  const fiberpli::testing::MemoryLimitGuard limit("64M");
  const std::string big = guideOrientationFields(long_, guideOptions(2.0, 0.5)).error;
  EXPECT_NE(big.find("GuideSpacing 0.5"), std::string::npos) << big;
  EXPECT_NE(big.find("memory budget"), std::string::npos) << big;
}

TEST(GuideField, ProgressCanStopIt)
{
  const std::vector<GuideLine> guides = arcBundle(20.0, { 0 }, { 0 });
  int calls = 0;
  const GuideFieldResult g =
    guideOrientationFields(guides, guideOptions(2.0, 0.5), [&](double) { return ++calls < 2; });
  EXPECT_TRUE(g.aborted);
  EXPECT_TRUE(g.error.empty());
  EXPECT_TRUE(g.fields.empty());
  EXPECT_EQ(calls, 2);
}
