// The realism knobs in the two generators (docs/tissue-models.md §10): defaults leave the models
// untouched, each knob's statistic measured on the generated fibers, closure in periodic cells,
// pieces, and the errors naming the property.
#include "Tissue/Beading.h"
#include "Tissue/BundleGenerator.h"
#include "Tissue/CubeGenerator.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace fiberpli;

namespace
{
CubeOptions periodicCube()
{
  CubeOptions o;
  o.populations = 2;
  o.numberOfFibers = 60;
  o.edgeLength = 30.0;
  o.fiberRadius = 0.8;
  o.displacement = 0.1;
  o.periodic = true;
  o.seed = 17;
  return o;
}

double lengthOf(const Fiber& f)
{
  double len = 0.0;
  for (std::size_t i = 1; i < f.points.size(); ++i)
    len += distance(f.points[i - 1], f.points[i]);
  return len;
}

bool samePoints(const FiberModel& a, const FiberModel& b)
{
  if (a.fibers.size() != b.fibers.size())
    return false;
  for (std::size_t i = 0; i < a.fibers.size(); ++i)
    if (a.fibers[i].points != b.fibers[i].points || a.fibers[i].id != b.fibers[i].id)
      return false;
  return true;
}

bool sameModel(const FiberModel& a, const FiberModel& b)
{
  if (!samePoints(a, b))
    return false;
  for (std::size_t i = 0; i < a.fibers.size(); ++i)
    if (a.fibers[i].radii != b.fibers[i].radii || a.fibers[i].bundle != b.fibers[i].bundle)
      return false;
  return true;
}
} // namespace

TEST(RealismKnobs, MyelinAloneLeavesTheFibersAndBeadingOnlyTheRadii)
{
  for (bool periodic : { false, true })
  {
    CubeOptions o = periodicCube();
    o.periodic = periodic;
    o.radiusSpread = 0.3;
    o.radiusDistribution = RadiusDistribution::Gamma;
    const FiberModel plain = generateCube(o);
    o.realism.gRatio = 0.7;
    EXPECT_TRUE(sameModel(plain, generateCube(o)));
    o.realism.beadingCV = 0.2;
    const FiberModel beaded = generateCube(o);
    EXPECT_TRUE(samePoints(plain, beaded));
    EXPECT_FALSE(sameModel(plain, beaded));
  }
}

TEST(RealismKnobs, PeriodicCubeFibersReachTortuosityAndClose)
{
  CubeOptions o = periodicCube();
  o.realism.tortuosity = 1.05;
  o.realism.undulationWavelength = 12.0;
  std::string warning;
  const FiberModel m = generateCube(o, 0, 1, &warning);
  EXPECT_TRUE(warning.empty()) << warning;
  ASSERT_EQ(m.fibers.size(), 60u);
  const PeriodicCell cell = cubeCell(o);
  for (const Fiber& f : m.fibers)
  {
    Vec3 closure;
    ASSERT_TRUE(isClosedFiber(f, cell, closure));
    Vec3 expected;
    expected[f.bundle] = o.edgeLength;
    EXPECT_EQ(f.points.back(), f.points.front() + expected);
    EXPECT_NEAR(lengthOf(f) / o.edgeLength, 1.05, 1e-4);
    // Points about SegmentLength apart along the path.
    EXPECT_NEAR(lengthOf(f) / static_cast<double>(f.points.size() - 1), o.segmentLength, 0.1);
  }
}

TEST(RealismKnobs, BeadedCubeFibersHaveTheRequestedRadiusCV)
{
  CubeOptions o = periodicCube();
  o.realism.tortuosity = 1.1;
  o.realism.beadingCV = 0.25;
  o.realism.beadingLength = 4.0;
  const FiberModel m = generateCube(o);
  for (const Fiber& f : m.fibers)
  {
    // Closed fibers: the last point repeats the first.
    EXPECT_NEAR(coefficientOfVariation(f.radii, true), 0.25, 1e-9);
    double mean = 0.0;
    for (std::size_t i = 0; i + 1 < f.radii.size(); ++i)
      mean += f.radii[i];
    EXPECT_NEAR(mean / static_cast<double>(f.radii.size() - 1), o.fiberRadius, 1e-12);
    EXPECT_EQ(f.radii.back(), f.radii.front());
  }
}

TEST(RealismKnobs, VolumeFractionCountsTortuousLengthsAndBeads)
{
  CubeOptions o = periodicCube();
  o.volumeFraction = 0.5;
  const std::size_t straight = generateCube(o).fibers.size();
  o.realism.tortuosity = 1.2;
  const FiberModel tortuous = generateCube(o);
  // Every fiber is 1.2 periods long: the target needs about 1/1.2 as many.
  EXPECT_NEAR(static_cast<double>(tortuous.fibers.size()), straight / 1.2, 2.0);
  double volume = 0.0;
  for (const Fiber& f : tortuous.fibers)
    volume += M_PI * f.radii[0] * f.radii[0] * lengthOf(f);
  EXPECT_NEAR(volume / std::pow(o.edgeLength, 3), 0.5, 0.01);
}

TEST(RealismKnobs, PiecesConcatenateToTheSerialModel)
{
  CubeOptions o = periodicCube();
  o.realism.tortuosity = 1.04;
  o.realism.beadingCV = 0.2;
  const FiberModel serial = generateCube(o);
  FiberModel joined;
  for (int p = 0; p < 3; ++p)
  {
    const FiberModel piece = generateCube(o, p, 3);
    joined.fibers.insert(joined.fibers.end(), piece.fibers.begin(), piece.fibers.end());
  }
  EXPECT_TRUE(sameModel(serial, joined));
}

TEST(RealismKnobs, OpenCubeAndBundleFibersReachTortuosity)
{
  CubeOptions c = periodicCube();
  c.periodic = false;
  c.realism.tortuosity = 1.08;
  for (const Fiber& f : generateCube(c).fibers)
    EXPECT_NEAR(lengthOf(f) / distance(f.points.front(), f.points.back()), 1.08, 0.005);

  BundleOptions b;
  b.displacement = 0.1;
  b.realism.tortuosity = 1.06;
  b.realism.undulationWavelength = 15.0;
  b.realism.beadingCV = 0.2;
  const FiberModel m = generateBundle(b, nullptr);
  ASSERT_GT(m.fibers.size(), 50u);
  double sum = 0.0;
  for (const Fiber& f : m.fibers)
  {
    const double tau = lengthOf(f) / distance(f.points.front(), f.points.back());
    EXPECT_NEAR(tau, 1.06, 0.01);
    sum += tau;
    EXPECT_NEAR(coefficientOfVariation(f.radii, false), 0.2, 1e-9);
  }
  EXPECT_NEAR(sum / static_cast<double>(m.fibers.size()), 1.06, 0.002);
  // Bundle defaults are untouched by myelin; pieces are the serial model.
  BundleOptions d;
  const FiberModel plain = generateBundle(d, nullptr);
  d.realism.gRatio = 0.6;
  EXPECT_TRUE(sameModel(plain, generateBundle(d, nullptr)));
  FiberModel joined;
  for (int p = 0; p < 2; ++p)
  {
    const FiberModel piece = generateBundle(b, nullptr, nullptr, p, 2);
    joined.fibers.insert(joined.fibers.end(), piece.fibers.begin(), piece.fibers.end());
  }
  EXPECT_TRUE(sameModel(m, joined));
}

TEST(RealismKnobs, BadValuesNameTheProperty)
{
  const auto cubeError = [](auto set)
  {
    CubeOptions o = periodicCube();
    set(o.realism);
    return validateCubeOptions(o);
  };
  EXPECT_NE(cubeError([](ShapeOptions& s) { s.tortuosity = 0.9; }).find("Tortuosity is 0.9"),
    std::string::npos);
  EXPECT_NE(cubeError([](ShapeOptions& s) { s.tortuosity = NAN; }).find("Tortuosity is nan"),
    std::string::npos);
  EXPECT_NE(cubeError(
              [](ShapeOptions& s)
              {
                s.tortuosity = 1.1;
                s.undulationWavelength = 0.0;
              })
              .find("UndulationWavelength is 0"),
    std::string::npos);
  EXPECT_NE(cubeError([](ShapeOptions& s) { s.dispersionC2 = 0.3; }).find("DispersionC2 is 0.3"),
    std::string::npos);
  EXPECT_NE(cubeError([](ShapeOptions& s) { s.dispersionC2 = 1.2; }).find("DispersionC2 is 1.2"),
    std::string::npos);
  EXPECT_NE(cubeError([](ShapeOptions& s) { s.beadingCV = -0.1; }).find("BeadingCV is -0.1"),
    std::string::npos);
  EXPECT_NE(cubeError([](ShapeOptions& s) { s.beadingCV = 5.0; }).find("BeadingCV is 5"),
    std::string::npos);
  EXPECT_NE(cubeError(
              [](ShapeOptions& s)
              {
                s.beadingCV = 0.2;
                s.beadingLength = -1.0;
              })
              .find("BeadingLength is -1"),
    std::string::npos);
  EXPECT_NE(
    cubeError([](ShapeOptions& s) { s.gRatio = 1.0; }).find("GRatio is 1"), std::string::npos);
  EXPECT_NE(
    cubeError([](ShapeOptions& s) { s.gRatio = -0.5; }).find("GRatio is -0.5"), std::string::npos);
  EXPECT_TRUE(cubeError([](ShapeOptions&) {}).empty());
  BundleOptions b;
  b.realism.gRatio = 1.5;
  EXPECT_NE(validateBundleOptions(b).find("GRatio is 1.5"), std::string::npos);
}

TEST(RealismKnobs, TinyBeadingLengthAndShortWavelengthStayCheapAndAreWarned)
{
  // A correlation length far below the point spacing: modes are capped at the points' resolution,
  // the CV is still exact.
  CubeOptions o = periodicCube();
  o.realism.beadingCV = 0.2;
  o.realism.beadingLength = 1e-6;
  for (const Fiber& f : generateCube(o).fibers)
    EXPECT_NEAR(coefficientOfVariation(f.radii, true), 0.2, 1e-9);
  EXPECT_TRUE(shapeWarnings(o.realism, o.segmentLength).empty());
  o.realism.tortuosity = 1.05;
  o.realism.undulationWavelength = 3.0;
  std::string warning;
  generateCube(o, 0, 1, &warning);
  EXPECT_NE(
    warning.find("UndulationWavelength 3 is shorter than 4 x SegmentLength"), std::string::npos)
    << warning;
  BundleOptions b;
  b.realism = o.realism;
  EXPECT_NE(bundleWarnings(b, nullptr).find("UndulationWavelength 3"), std::string::npos);
  // Displacement alone above the target: the fibers stay unundulated, and the source says so.
  o.realism.undulationWavelength = 12.0;
  o.realism.tortuosity = 1.01;
  o.displacement = 0.6;
  generateCube(o, 0, 1, &warning);
  EXPECT_NE(warning.find("Tortuosity 1.01: the Displacement 0.6 alone"), std::string::npos)
    << warning;
}

TEST(RealismKnobs, NeighboursUndulateIndependently)
{
  // One population along x, undulated, no jitter: the transverse deviation (y, z minus the fiber's
  // mean) sampled at the same x for two fibers; over all pairs whose mean axes are more than 4 µm
  // apart the mean correlation is near 0 (a crystal bent as a whole would give 1).
  CubeOptions o = periodicCube();
  o.populations = 1;
  o.numberOfFibers = 40;
  o.displacement = 0.0;
  o.realism.tortuosity = 1.08;
  o.realism.undulationWavelength = 10.0;
  const FiberModel m = generateCube(o);
  const int samples = 60;
  std::vector<std::vector<double>> dev(m.fibers.size());
  std::vector<Vec3> centre(m.fibers.size());
  for (std::size_t f = 0; f < m.fibers.size(); ++f)
  {
    const std::vector<Vec3>& p = m.fibers[f].points;
    std::vector<double> y(samples), z(samples);
    std::size_t i = 0;
    for (int s = 0; s < samples; ++s)
    {
      const double x = p.front().x + o.edgeLength * (s + 0.5) / samples;
      while (i + 2 < p.size() && p[i + 1].x < x)
        ++i;
      const double t = (x - p[i].x) / (p[i + 1].x - p[i].x);
      y[static_cast<std::size_t>(s)] = p[i].y + t * (p[i + 1].y - p[i].y);
      z[static_cast<std::size_t>(s)] = p[i].z + t * (p[i + 1].z - p[i].z);
    }
    double my = 0.0, mz = 0.0;
    for (int s = 0; s < samples; ++s)
    {
      my += y[static_cast<std::size_t>(s)] / samples;
      mz += z[static_cast<std::size_t>(s)] / samples;
    }
    centre[f] = { 0.0, my, mz };
    for (int s = 0; s < samples; ++s)
    {
      dev[f].push_back(y[static_cast<std::size_t>(s)] - my);
      dev[f].push_back(z[static_cast<std::size_t>(s)] - mz);
    }
  }
  double sum = 0.0;
  int pairs = 0;
  for (std::size_t a = 0; a < dev.size(); ++a)
    for (std::size_t b = a + 1; b < dev.size(); ++b)
    {
      if (distance(centre[a], centre[b]) <= 4.0)
        continue;
      double ab = 0.0, aa = 0.0, bb = 0.0;
      for (std::size_t s = 0; s < dev[a].size(); ++s)
      {
        ab += dev[a][s] * dev[b][s];
        aa += dev[a][s] * dev[a][s];
        bb += dev[b][s] * dev[b][s];
      }
      sum += ab / std::sqrt(aa * bb);
      ++pairs;
    }
  ASSERT_GT(pairs, 300);
  EXPECT_LT(std::fabs(sum / pairs), 0.1);
}

TEST(RealismKnobs, InterwovenPopulationsFillEverySubCube)
{
  // Two populations at 45° in a periodic cell, Random seeding (interwoven): in each of the 27
  // sub-cubes of edge L/3 each population holds at least 20 % of the fiber length there (points
  // wrapped into the cell; equal radii, so length stands for volume). Sheets leaves sub-cubes
  // with one population only.
  for (CubeArrangement arrangement : { CubeArrangement::Auto, CubeArrangement::Sheets })
  {
    CubeOptions o = periodicCube();
    o.numberOfFibers = 300;
    o.crossingAngle = 45.0;
    o.arrangement = arrangement;
    o.realism.tortuosity = 1.05;
    o.realism.undulationWavelength = 10.0;
    const FiberModel m = generateCube(o);
    const double L = o.edgeLength;
    std::vector<double> length(27 * 2, 0.0);
    for (const Fiber& f : m.fibers)
      for (std::size_t i = 1; i < f.points.size(); ++i)
      {
        Vec3 mid = 0.5 * (f.points[i - 1] + f.points[i]);
        int cell = 0;
        for (int a = 0; a < 3; ++a)
        {
          const double u = mid[a] / L + 0.5;
          const int c = std::min(2, static_cast<int>(3.0 * (u - std::floor(u))));
          cell = 3 * cell + c;
        }
        length[static_cast<std::size_t>(2 * cell + f.bundle)] +=
          distance(f.points[i - 1], f.points[i]);
      }
    double worst = 1.0;
    for (int c = 0; c < 27; ++c)
    {
      const double total = length[2 * c] + length[2 * c + 1];
      worst = std::min({ worst, length[2 * c] / total, length[2 * c + 1] / total });
    }
    if (arrangement == CubeArrangement::Auto)
      EXPECT_GE(worst, 0.2);
    else
      EXPECT_LT(worst, 0.05);
  }
}

TEST(RealismKnobs, TargetShapesRebuildTheFibersAndScaleTowardsThem)
{
  // cubeFiberShape is what the generator builds the fiber from: its points() are the fiber's, and
  // a fraction of the amplitude gives the same fiber less tortuous (for a later continuation).
  CubeOptions o = periodicCube();
  o.realism.tortuosity = 1.1;
  o.realism.undulationWavelength = 12.0;
  o.realism.dispersionC2 = 0.9;
  const FiberModel m = generateCube(o);
  for (const Fiber& f : m.fibers)
  {
    const int k = f.bundle;
    const int j = static_cast<int>(f.id) - (k == 0 ? 0 : cubePopulationSize(o, 0));
    const FiberShape shape = cubeFiberShape(o, k, j);
    EXPECT_EQ(shape.points(), f.points);
    const std::vector<Vec3> half = shape.points(0.5);
    EXPECT_EQ(half.back(), half.front() + shape.base.closure);
    Fiber h;
    h.points = half;
    const double tauHalf = lengthOf(h) / norm(shape.base.closure);
    EXPECT_GT(tauHalf, 1.0);
    EXPECT_LT(tauHalf, 1.1 - 0.02);
  }
  BundleOptions b;
  b.displacement = 0.1;
  b.realism.tortuosity = 1.07;
  const std::vector<CrossSectionFiber> cs = makeCrossSection(b, 0);
  const ResampledTrajectory t =
    resampleTrajectory({ { -30, 0, 0 }, { 30, 0, 0 } }, nullptr, b.segmentLength);
  const TrajectoryFrames fr = transportFrames(t.points);
  const FiberModel bundle = generateBundle(b, nullptr);
  ASSERT_EQ(bundle.fibers.size(), cs.size());
  for (std::size_t i = 0; i < cs.size(); ++i)
  {
    const FiberShape shape =
      bundleFiberShape(t, fr, cs[i], b.displacement, b.realism, b.segmentLength, b.seed);
    EXPECT_EQ(shape.points(), bundle.fibers[i].points);
  }
}

TEST(RealismKnobs, EveryBundleShapeTakesTheKnobs)
{
  const std::vector<Vec3> path = { { 0, 0, 0 }, { 15, 5, 0 }, { 30, 0, 5 } };
  for (BundleShape shape : { BundleShape::Cylinder, BundleShape::Trajectory, BundleShape::Crossing,
         BundleShape::YShape, BundleShape::Chiasm })
  {
    BundleOptions b;
    b.shape = shape;
    b.bundleRadius = 4.0;
    b.length = 40.0;
    b.crossingAngle = shape == BundleShape::Crossing ? 90.0 : 60.0;
    b.displacement = 0.05;
    b.ranvierSpacing = 10.0;
    b.realism.tortuosity = 1.06;
    b.realism.undulationWavelength = 10.0;
    b.realism.dispersionC2 = 0.95;
    b.realism.beadingCV = 0.2;
    const std::vector<Vec3>* trajectory = shape == BundleShape::Trajectory ? &path : nullptr;
    ASSERT_EQ(validateBundleOptions(b, trajectory), "");
    const FiberModel m = generateBundle(b, trajectory);
    ASSERT_FALSE(m.fibers.empty()) << bundleShapeName(shape);
    EXPECT_EQ(validateModel(m), "") << bundleShapeName(shape);
    for (const Fiber& f : m.fibers)
    {
      // Beading and nodes of Ranvier multiply: the radii vary, stay positive, and average near r.
      double mean = 0.0;
      for (double r : f.radii)
        mean += r / static_cast<double>(f.radii.size());
      EXPECT_GT(coefficientOfVariation(f.radii, false), 0.1);
      EXPECT_NEAR(mean, b.fiberRadius, 0.15 * b.fiberRadius);
    }
  }
}
