// FiberBundleSource Core (docs/tissue-models.md §2, §5.4, §6, §7, §8): fibers inside the bundle,
// following a curved trajectory without twist, ids and bundle ids per shape, reproducibility,
// Ranvier profile, bad input messages.
#include "Tissue/BundleGenerator.h"
#include "Tissue/BundleShapes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

using namespace fiberpli;

namespace
{
BundleOptions quiet(BundleShape shape)
{
  BundleOptions o;
  o.shape = shape;
  o.displacement = 0.0;
  o.ranvierSpacing = 0.0;
  return o;
}

std::vector<Vec3> paperCurve() // f(t) = (t³, t, 0), scaled to µm
{
  std::vector<Vec3> f;
  for (int i = -20; i <= 20; ++i)
  {
    const double t = 0.1 * i;
    f.push_back({ 5.0 * t * t * t, 10.0 * t, 0.0 });
  }
  return f;
}

void expectIdsUniqueAndBundles(const FiberModel& m, const std::set<int>& bundles)
{
  ASSERT_TRUE(validateModel(m).empty()) << validateModel(m);
  std::set<std::int64_t> ids;
  std::set<int> seen;
  for (std::size_t i = 0; i < m.fibers.size(); ++i)
  {
    EXPECT_EQ(m.fibers[i].id, static_cast<std::int64_t>(i));
    ids.insert(m.fibers[i].id);
    seen.insert(m.fibers[i].bundle);
    if (i > 0)
    {
      EXPECT_LE(m.fibers[i - 1].bundle, m.fibers[i].bundle); // grouped bundle by bundle
    }
  }
  EXPECT_EQ(ids.size(), m.fibers.size());
  EXPECT_EQ(seen, bundles);
}

bool identical(const FiberModel& a, const FiberModel& b)
{
  if (a.fibers.size() != b.fibers.size())
  {
    return false;
  }
  for (std::size_t i = 0; i < a.fibers.size(); ++i)
  {
    if (a.fibers[i].points != b.fibers[i].points || a.fibers[i].radii != b.fibers[i].radii ||
      a.fibers[i].bundle != b.fibers[i].bundle)
    {
      return false;
    }
  }
  return true;
}
} // namespace

TEST(BundleGenerator, CylinderDefaultsFillTheBundleOnTheGrid)
{
  const BundleOptions o; // defaults: R 10, r 0.8, d 2, l 2, D 0.2, Length 60
  ASSERT_TRUE(validateBundleOptions(o).empty());
  const FiberModel m = generateBundle(o, nullptr);
  // 85 hexagonal lattice points (d = 2) within R − r = 9.2 (counted independently, see TestSeeds).
  ASSERT_EQ(m.fibers.size(), 85u);
  expectIdsUniqueAndBundles(m, { 0 });
  for (const Fiber& f : m.fibers)
  {
    ASSERT_EQ(f.points.size(), 31u); // round(60/2) + 1, Ranvier off by default for Cylinder
    for (std::size_t k = 0; k < f.points.size(); ++k)
    {
      const Vec3& p = f.points[k];
      EXPECT_LE(
        std::hypot(p.y, p.z), o.bundleRadius - o.fiberRadius + o.displacement * std::sqrt(3.0));
      EXPECT_NEAR(p.x, -30.0 + 2.0 * k, o.displacement + 1e-12);
      EXPECT_EQ(f.radii[k], 0.8);
    }
  }
}

TEST(BundleGenerator, UndisplacedGridFibersKeepTheSpacingAndTheirOffset)
{
  const FiberModel m = generateBundle(quiet(BundleShape::Cylinder), nullptr);
  ASSERT_FALSE(m.empty());
  for (std::size_t i = 0; i < m.fibers.size(); ++i)
  {
    const Fiber& f = m.fibers[i];
    const double rho = std::hypot(f.points[0].y, f.points[0].z);
    EXPECT_LE(rho, 9.2 + 1e-12);
    double nearest = 1e300;
    for (std::size_t j = 0; j < m.fibers.size(); ++j)
    {
      if (j != i)
      {
        nearest = std::min(nearest, distance(f.points[0], m.fibers[j].points[0]));
      }
    }
    EXPECT_NEAR(nearest, 2.0, 1e-9); // the triangular grid survives the transport
    for (const Vec3& p : f.points)
    {
      EXPECT_NEAR(std::hypot(p.y, p.z), rho, 1e-9); // straight and parallel to the axis
    }
  }
}

TEST(BundleGenerator, FollowsACurvedTrajectoryWithoutTwist)
{
  BundleOptions o = quiet(BundleShape::Trajectory);
  o.bundleRadius = 4.0;
  o.fiberSpacing = 1.6;
  o.segmentLength = 1.0;
  const std::vector<Vec3> curve = paperCurve();
  ASSERT_TRUE(validateBundleOptions(o, &curve).empty()) << validateBundleOptions(o, &curve);
  const FiberModel m = generateBundle(o, &curve);
  const ResampledTrajectory t = resampleTrajectory(curve, nullptr, o.segmentLength);
  const TrajectoryFrames fr = transportFrames(t.points);
  ASSERT_GT(m.fibers.size(), 10u);
  expectIdsUniqueAndBundles(m, { 0 });
  for (const Fiber& f : m.fibers)
  {
    ASSERT_EQ(f.points.size(), t.points.size());
    const Vec3 o0 = f.points[0] - t.points[0];
    const double rho = norm(o0);
    EXPECT_LE(rho, o.bundleRadius - o.fiberRadius + 1e-12);
    for (std::size_t k = 0; k < f.points.size(); ++k)
    {
      const Vec3 off = f.points[k] - t.points[k];
      EXPECT_NEAR(norm(off), rho, 1e-9);               // distance to the trajectory constant
      EXPECT_NEAR(dot(off, fr.tangent[k]), 0.0, 1e-9); // cross-section perpendicular
      EXPECT_NEAR(off.z, o0.z, 1e-9);                  // planar curve: no twist about the axis
    }
  }
}

TEST(BundleGenerator, ScaleSwellsTheBundle)
{
  BundleOptions o = quiet(BundleShape::Trajectory);
  const std::vector<Vec3> line{ { 0, 0, 0 }, { 0, 0, 20 }, { 0, 0, 40 } };
  const std::vector<double> scale{ 1.0, 2.0, 1.0 };
  const FiberModel m = generateBundle(o, &line, &scale);
  ASSERT_FALSE(m.empty());
  for (const Fiber& f : m.fibers)
  {
    const double rho = std::hypot(f.points.front().x, f.points.front().y);
    const Vec3& mid = f.points[f.points.size() / 2];
    EXPECT_NEAR(std::hypot(mid.x, mid.y), 2.0 * rho, 1e-9);
  }
}

TEST(BundleGenerator, RandomSeedsStayInsideAndAddingFibersKeepsTheOldOnes)
{
  BundleOptions o = quiet(BundleShape::Cylinder);
  o.numberOfFibers = 10;
  o.radiusSpread = 0.3;
  o.displacement = 0.3;
  const FiberModel ten = generateBundle(o, nullptr);
  o.numberOfFibers = 20;
  const FiberModel twenty = generateBundle(o, nullptr);
  ASSERT_EQ(ten.fibers.size(), 10u);
  ASSERT_EQ(twenty.fibers.size(), 20u);
  for (std::size_t i = 0; i < 10; ++i)
  {
    EXPECT_EQ(ten.fibers[i].points, twenty.fibers[i].points); // one stream per fiber (§7)
    EXPECT_EQ(ten.fibers[i].radii, twenty.fibers[i].radii);
  }
  for (const Fiber& f : twenty.fibers)
  {
    for (std::size_t k = 0; k < f.points.size(); ++k)
    {
      EXPECT_LE(std::hypot(f.points[k].y, f.points[k].z),
        o.bundleRadius - f.radii[k] + o.displacement * std::sqrt(3.0));
      EXPECT_LE(f.radii[k], o.bundleRadius);
    }
  }
}

TEST(BundleGenerator, SameSeedIsBitIdenticalOtherSeedDiffers)
{
  for (BundleShape shape :
    { BundleShape::Cylinder, BundleShape::Crossing, BundleShape::YShape, BundleShape::Chiasm })
  {
    BundleOptions o;
    o.shape = shape;
    o.radiusSpread = 0.1;
    o.seed = 1234;
    const FiberModel a = generateBundle(o, nullptr);
    const FiberModel b = generateBundle(o, nullptr);
    ASSERT_FALSE(a.empty()) << bundleShapeName(shape);
    EXPECT_TRUE(identical(a, b)) << bundleShapeName(shape);
    o.seed = 1235;
    EXPECT_FALSE(identical(a, generateBundle(o, nullptr))) << bundleShapeName(shape);
  }
}

TEST(BundleGenerator, CrossingBundlesRunAlongTheirAxes)
{
  BundleOptions o = quiet(BundleShape::Crossing);
  o.crossingAngle = 60.0;
  const FiberModel m = generateBundle(o, nullptr);
  expectIdsUniqueAndBundles(m, { 0, 1 });
  std::size_t count[2] = { 0, 0 };
  for (const Fiber& f : m.fibers)
  {
    ++count[f.bundle];
    const double a = f.bundle == 0 ? 0.0 : M_PI / 3.0;
    const Vec3 axis{ std::cos(a), std::sin(a), 0.0 };
    const Vec3 dir = normalized(f.points.back() - f.points.front());
    EXPECT_NEAR(dot(dir, axis), 1.0, 1e-12);
    EXPECT_NEAR(dot(f.points.front(), axis), -30.0, 1e-9);
    const Vec3 mid = f.points.front() - dot(f.points.front(), axis) * axis;
    EXPECT_LE(norm(mid), 9.2 + 1e-9);
  }
  EXPECT_EQ(count[0], 85u);
  EXPECT_EQ(count[1], 85u);
}

TEST(BundleGenerator, YShapeSplitsTheTrunkIntoTwoBranches)
{
  BundleOptions o = quiet(BundleShape::YShape);
  o.crossingAngle = 60.0;
  const FiberModel m = generateBundle(o, nullptr);
  expectIdsUniqueAndBundles(m, { 0, 1 });
  EXPECT_EQ(m.fibers.size(), 85u); // area conserved: every trunk seed goes to one branch
  const double half = 30.0 * M_PI / 180.0;
  for (const Fiber& f : m.fibers)
  {
    const double side = f.bundle == 0 ? -1.0 : 1.0;
    EXPECT_NEAR(f.points.front().y, -30.0, 1e-9);  // trunk starts at y = −H
    EXPECT_TRUE(side * f.points.front().x >= 0.0); // half-disc by the sign of x
    EXPECT_GT(side * f.points.back().x, 0.0);      // ends on its own side
    const Vec3 b{ side * std::sin(half), std::cos(half), 0.0 };
    const std::size_t n = f.points.size();
    EXPECT_NEAR(
      dot(normalized(f.points[n - 1] - f.points[n - 3]), b), 1.0, 1e-6); // leaves along b±
  }
}

TEST(BundleGenerator, ChiasmKeepsTheLateralFractionOnItsSide)
{
  BundleOptions o = quiet(BundleShape::Chiasm);
  o.ranvierSpacing = 0.0;
  const FiberModel m = generateBundle(o, nullptr);
  expectIdsUniqueAndBundles(m, { 0, 1, 2, 3 });
  std::size_t count[4] = { 0, 0, 0, 0 };
  const double H = 30.0, S = H * std::sin(M_PI / 4.0), C = H * std::cos(M_PI / 4.0);
  for (const Fiber& f : m.fibers)
  {
    ++count[f.bundle];
    const Vec3& a = f.points.front();
    const Vec3& e = f.points.back();
    EXPECT_LT(a.y, 0.0); // every nerve enters at the bottom
    const bool leftNerve = f.bundle == 0 || f.bundle == 2;
    const Vec3 entry{ leftNerve ? -S : S, -C, 0.0 };
    EXPECT_LE(distance(a, entry), 9.2 + 1e-9) << f.bundle;
    const bool endsLeft = f.bundle == 1 || f.bundle == 2;
    const Vec3 exit{ endsLeft ? -S : S, C, 0.0 };
    EXPECT_LE(distance(e, exit), 9.2 + 1e-9) << f.bundle;
  }
  // ⌈0.25·85⌉ = 22 uncrossed fibers per nerve.
  EXPECT_EQ(count[2], 22u);
  EXPECT_EQ(count[3], 22u);
  EXPECT_EQ(count[0], 63u);
  EXPECT_EQ(count[1], 63u);
  // The uncrossed fibers of the left nerve are its most lateral ones at the entry.
  const Vec3 nL = chiasmLateralNormal(M_PI / 2.0, false);
  const Vec3 entry{ -S, -C, 0.0 };
  double minUncrossed = 1e300, maxCrossing = -1e300;
  for (const Fiber& f : m.fibers)
  {
    const double key = dot(f.points.front() - entry, nL);
    if (f.bundle == 2)
    {
      minUncrossed = std::min(minUncrossed, key);
    }
    if (f.bundle == 0)
    {
      maxCrossing = std::max(maxCrossing, key);
    }
  }
  EXPECT_GE(minUncrossed, maxCrossing - 1e-9);
}

TEST(BundleGenerator, ChiasmHasRanvierNodesByDefault)
{
  BundleOptions o;
  o.shape = BundleShape::Chiasm;
  EXPECT_EQ(effectiveRanvierSpacing(o), 20.0);
  const FiberModel m = generateBundle(o, nullptr);
  ASSERT_FALSE(m.empty());
  const double lo = *std::min_element(m.fibers[0].radii.begin(), m.fibers[0].radii.end());
  EXPECT_NEAR(lo, 0.8 * 0.7, 1e-12);
  o.shape = BundleShape::Cylinder;
  EXPECT_EQ(effectiveRanvierSpacing(o), 0.0);
}

TEST(BundleGenerator, RanvierNodesHaveDepthAndSpacing)
{
  BundleOptions o = quiet(BundleShape::Cylinder);
  o.ranvierSpacing = 10.0;
  o.ranvierDepth = 0.4;
  o.ranvierLength = 1.0;
  const FiberModel m = generateBundle(o, nullptr);
  ASSERT_FALSE(m.empty());
  std::set<double> phases;
  for (const Fiber& f : m.fibers)
  {
    // Arc length along the undisplaced straight fiber = x + 30.
    std::vector<double> nodeMid;
    double runStart = -1.0, runEnd = -1.0;
    for (std::size_t k = 0; k < f.points.size(); ++k)
    {
      const double s = f.points[k].x + 30.0;
      EXPECT_GE(f.radii[k], 0.8 * 0.6 - 1e-12);
      EXPECT_LE(f.radii[k], 0.8 + 1e-12);
      const bool atMin = std::fabs(f.radii[k] - 0.8 * 0.6) < 1e-12;
      if (atMin)
      {
        runStart = runStart < 0.0 ? s : runStart;
        runEnd = s;
      }
      if ((!atMin || k + 1 == f.points.size()) && runStart >= 0.0)
      {
        // Only nodes whose flat part [c − w/2, c + w/2] lies well inside the fiber (insertions
        // within the snapping tolerance of an end point are dropped).
        if (runStart > 1.0 && runEnd < 59.0)
        {
          EXPECT_NEAR(runEnd - runStart, 1.0, 1e-9); // sampled at c ± w/2
          nodeMid.push_back(0.5 * (runStart + runEnd));
        }
        runStart = -1.0;
      }
      if (k > 0)
      {
        EXPECT_GT(f.points[k].x - f.points[k - 1].x, 0.1); // no tiny links from the insertions
      }
    }
    ASSERT_GE(nodeMid.size(), 4u);
    for (std::size_t i = 1; i < nodeMid.size(); ++i)
    {
      EXPECT_NEAR(nodeMid[i] - nodeMid[i - 1], 10.0, 1e-9);
    }
    phases.insert(std::fmod(nodeMid[0], 10.0));
    // Away from nodes the radius is the fiber's own.
    EXPECT_EQ(*std::max_element(f.radii.begin(), f.radii.end()), 0.8);
  }
  EXPECT_GT(phases.size(), m.fibers.size() / 2); // random phase per fiber
}

TEST(BundleGenerator, RanvierFactorMatchesTheProfile)
{
  RanvierOptions r;
  r.spacing = 20.0;
  r.depth = 0.3;
  r.length = 2.0;
  // Phase 5: centres at 15, 35, ...; flat over ±1, cosine taper to ±2.
  EXPECT_DOUBLE_EQ(ranvierFactor(15.0, 5.0, r), 0.7);
  EXPECT_DOUBLE_EQ(ranvierFactor(35.9, 5.0, r), 0.7);
  EXPECT_NEAR(ranvierFactor(16.5, 5.0, r), 1.0 - 0.3 * 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(ranvierFactor(17.0, 5.0, r), 1.0);
  EXPECT_DOUBLE_EQ(ranvierFactor(25.0, 5.0, r), 1.0);
  EXPECT_DOUBLE_EQ(ranvierFactor(-5.0, 5.0, r), 0.7); // periodic also before the phase
  r.spacing = 0.0;
  EXPECT_EQ(ranvierFactor(15.0, 5.0, r), 1.0);
}

TEST(BundleGenerator, BadInputGivesMessagesNamingTheProblem)
{
  BundleOptions o;
  o.bundleRadius = 0.5;
  std::string e = validateBundleOptions(o);
  EXPECT_NE(e.find("BundleRadius 0.5 is smaller than FiberRadius 0.8"), std::string::npos) << e;
  EXPECT_TRUE(generateBundle(o, nullptr).empty());

  o = BundleOptions();
  o.fiberSpacing = 1e-4;
  e = validateBundleOptions(o);
  EXPECT_NE(e.find("fibers, more than the limit"), std::string::npos) << e;

  o = BundleOptions();
  o.segmentLength = 1e-7;
  e = validateBundleOptions(o);
  EXPECT_NE(e.find("points, more than the limit"), std::string::npos) << e;

  o = BundleOptions();
  o.shape = BundleShape::Trajectory;
  EXPECT_NE(validateBundleOptions(o).find("needs an input polyline"), std::string::npos);
  const std::vector<Vec3> repeated{ { 0, 0, 0 }, { 5, 0, 0 }, { 5, 0, 0 } };
  e = validateBundleOptions(o, &repeated);
  EXPECT_NE(e.find("point 2"), std::string::npos) << e;
  EXPECT_TRUE(generateBundle(o, &repeated).empty());
  const std::vector<Vec3> one{ { 0, 0, 0 } };
  EXPECT_NE(validateBundleOptions(o, &one).find("needs at least 2"), std::string::npos);

  o = BundleOptions();
  o.shape = BundleShape::YShape;
  o.crossingAngle = 180.0;
  EXPECT_NE(validateBundleOptions(o).find("CrossingAngle is 180"), std::string::npos);
  o.shape = BundleShape::Crossing;
  EXPECT_TRUE(validateBundleOptions(o).empty());

  o = BundleOptions();
  o.radiusDistribution = RadiusDistribution::Uniform;
  o.radiusSpread = 1.0;
  EXPECT_NE(validateBundleOptions(o).find("RadiusSpread is 1"), std::string::npos);

  o = BundleOptions();
  o.ranvierSpacing = 1.5;
  EXPECT_NE(validateBundleOptions(o).find("RanvierLength is 1"), std::string::npos);
  o.ranvierSpacing = 10.0;
  o.ranvierDepth = 1.0;
  EXPECT_NE(validateBundleOptions(o).find("RanvierDepth is 1"), std::string::npos);

  o = BundleOptions();
  o.displacement = std::nan("");
  EXPECT_NE(validateBundleOptions(o).find("Displacement"), std::string::npos);
  o = BundleOptions();
  o.numberOfFibers = -3;
  EXPECT_NE(validateBundleOptions(o).find("NumberOfFibers is -3"), std::string::npos);
  o = BundleOptions();
  o.shape = BundleShape::Chiasm;
  o.uncrossedFraction = 1.5;
  EXPECT_NE(validateBundleOptions(o).find("UncrossedFraction is 1.5"), std::string::npos);
}

TEST(BundleGenerator, WarnsWhenTheBundleFoldsAtABend)
{
  BundleOptions o;
  o.shape = BundleShape::Trajectory;
  const std::vector<Vec3> corner{ { 0, 0, 0 }, { 20, 0, 0 }, { 20, 20, 0 } };
  EXPECT_NE(bundleWarnings(o, &corner).find("radius of curvature"), std::string::npos);
  const std::vector<Vec3> straight{ { 0, 0, 0 }, { 20, 0, 0 }, { 40, 0, 0 } };
  EXPECT_TRUE(bundleWarnings(o, &straight).empty());
  o.shape = BundleShape::Cylinder;
  EXPECT_TRUE(bundleWarnings(o, nullptr).empty());
}

TEST(BundleGenerator, ShapeNamesRoundTrip)
{
  for (BundleShape s : { BundleShape::Cylinder, BundleShape::Trajectory, BundleShape::Crossing,
         BundleShape::YShape, BundleShape::Chiasm })
  {
    BundleShape parsed = BundleShape::Cylinder;
    EXPECT_TRUE(parseBundleShape(bundleShapeName(s), parsed));
    EXPECT_EQ(parsed, s);
  }
  BundleShape unused;
  EXPECT_FALSE(parseBundleShape("Helix", unused));
}

TEST(BundleGenerator, ChiasmSidePathIsATangentArcAndNoUncrossedFiberFolds)
{
  // Path geometry: from −H·d0 to +H·d1, the arc of radius 20 centred at (−20/cos 45°, 0).
  const double H = 30.0, w = M_PI / 2.0, rt = 20.0;
  const std::vector<Vec3> path = chiasmSidePath(H, w, rt, false, 0.5);
  const double S = H * std::sin(w / 2.0), C = H * std::cos(w / 2.0);
  EXPECT_NEAR(distance(path.front(), Vec3{ -S, -C, 0.0 }), 0.0, 1e-9);
  EXPECT_NEAR(distance(path.back(), Vec3{ -S, C, 0.0 }), 0.0, 1e-9);
  const Vec3 centre{ -rt / std::cos(w / 2.0), 0.0, 0.0 };
  double minFromCentre = 1e300;
  for (std::size_t k = 0; k + 1 < path.size(); ++k)
  {
    EXPECT_LE(distance(path[k], path[k + 1]), 0.5 + 1e-9);
    minFromCentre = std::min(minFromCentre, distance(path[k], centre));
  }
  EXPECT_NEAR(minFromCentre, rt, 1e-9); // the path never comes closer to the turn centre than rt
  double tip = -1e300;
  for (const Vec3& p : path)
  {
    tip = std::max(tip, p.x);
  }
  EXPECT_NEAR(tip, -rt / std::cos(w / 2.0) + rt, 0.01); // the arc's tip, on the x axis
  const std::vector<Vec3> mirrored = chiasmSidePath(H, w, rt, true, 0.5);
  EXPECT_EQ(mirrored.front().x, -path.front().x);
  // Too short a nerve for the arc: the radius shrinks to H/tan(ω/2).
  EXPECT_NEAR(chiasmTurnRadius(10.0, w, rt), 10.0, 1e-12);

  // Default sizes: no uncrossed fiber bends tighter than BundleRadius (fastPLI's curve: 0.144·H =
  // 4.3 µm, folding 32 of 44), and no folding warning.
  BundleOptions o = quiet(BundleShape::Chiasm);
  EXPECT_TRUE(bundleWarnings(o, nullptr).empty()) << bundleWarnings(o, nullptr);
  const FiberModel m = generateBundle(o, nullptr);
  int uncrossed = 0;
  for (const Fiber& f : m.fibers)
  {
    if (f.bundle >= 2)
    {
      ++uncrossed;
      EXPECT_GE(minimumCircumradius(f.points), o.bundleRadius) << f.id;
    }
  }
  EXPECT_EQ(uncrossed, 44);
  // A nerve too short for the arc still warns.
  o.length = 10.0;
  EXPECT_NE(
    bundleWarnings(o, nullptr).find("Chiasm side path radius of curvature"), std::string::npos);
}
