// The cube's shared undulation field (UndulationCoherence, docs/tissue-models.md §10.1): in a
// periodic cell every fiber still reaches its tortuosity and closes exactly; the deviations of
// neighbours correlate strongly and those of fibers far apart do not (measured here from the
// points, by correlating the transverse deviations sampled along the axis); 0 leaves the cube as
// it was; bad values name the property.
#include "Tissue/CubeGenerator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace fiberpli;

namespace
{
CubeOptions coherentCell(double coherence)
{
  CubeOptions o;
  o.populations = 1;
  o.edgeLength = 30.0;
  o.periodic = true;
  o.volumeFraction = 0.5;
  o.fiberRadius = 1.0;
  o.segmentLength = 2.0;
  o.displacement = 0.0;
  o.seed = 7;
  o.realism.tortuosity = 1.04;
  o.realism.undulationWavelength = 10.0;
  o.undulationCoherence = coherence;
  return o;
}

// A fiber along x: its (y, z) deviation from its mean, linearly interpolated at 60 positions of
// x over one period, and its mean (y, z).
struct Deviation
{
  std::vector<double> y, z;
  double cy = 0.0, cz = 0.0;
};

Deviation deviationOf(const Fiber& f, double L)
{
  Deviation d;
  const std::size_t n = f.size() - 1; // the last point repeats the first
  for (std::size_t i = 0; i < n; ++i)
  {
    d.cy += f.points[i].y / n;
    d.cz += f.points[i].z / n;
  }
  for (int s = 0; s < 60; ++s)
  {
    double x = f.points[0].x + L * (s + 0.5) / 60.0;
    std::size_t i = 0;
    while (i + 1 < f.size() && f.points[i + 1].x < x)
      ++i;
    const double t = (x - f.points[i].x) / (f.points[i + 1].x - f.points[i].x);
    d.y.push_back((1 - t) * f.points[i].y + t * f.points[i + 1].y - d.cy);
    d.z.push_back((1 - t) * f.points[i].z + t * f.points[i + 1].z - d.cz);
  }
  return d;
}

// Mean correlation of the deviations of fiber pairs whose axes are in [lo, hi) apart
// (minimum image across the cell). The sampling starts at each fiber's first x, so the fibers
// are compared at the same x only when they start at the same x (every fiber of the cube does).
double meanCorrelation(const std::vector<Deviation>& d, double L, double lo, double hi, int& pairs)
{
  double sum = 0.0;
  pairs = 0;
  for (std::size_t a = 0; a < d.size(); ++a)
    for (std::size_t b = a + 1; b < d.size(); ++b)
    {
      double dy = d[a].cy - d[b].cy, dz = d[a].cz - d[b].cz;
      dy -= L * std::round(dy / L);
      dz -= L * std::round(dz / L);
      const double r = std::hypot(dy, dz);
      if (r < lo || r >= hi)
        continue;
      double ab = 0.0, aa = 0.0, bb = 0.0;
      for (std::size_t s = 0; s < d[a].y.size(); ++s)
      {
        ab += d[a].y[s] * d[b].y[s] + d[a].z[s] * d[b].z[s];
        aa += d[a].y[s] * d[a].y[s] + d[a].z[s] * d[a].z[s];
        bb += d[b].y[s] * d[b].y[s] + d[b].z[s] * d[b].z[s];
      }
      sum += ab / std::sqrt(aa * bb);
      ++pairs;
    }
  return pairs ? sum / pairs : 0.0;
}
} // namespace

TEST(UndulationField, NeighboursUndulateTogetherFarFibersDoNot)
{
  const CubeOptions o = coherentCell(4.0);
  const FiberModel m = generateCube(o);
  ASSERT_GT(m.fibers.size(), 30u);
  std::vector<Deviation> d;
  for (const Fiber& f : m.fibers)
  {
    // Every fiber reaches its tortuosity and closes on its lattice vector exactly.
    double len = 0.0;
    for (std::size_t i = 0; i + 1 < f.size(); ++i)
      len += distance(f.points[i], f.points[i + 1]);
    EXPECT_NEAR(len / o.edgeLength, 1.04, 1e-5);
    EXPECT_EQ(f.points.back().x, f.points.front().x + o.edgeLength);
    EXPECT_EQ(f.points.back().y, f.points.front().y);
    d.push_back(deviationOf(f, o.edgeLength));
  }
  int near = 0, far = 0;
  // exp(−r²/2ξ²) is above 0.88 below 2 µm and below 0.11 beyond 8.4 µm (ξ = 4 µm).
  EXPECT_GT(meanCorrelation(d, o.edgeLength, 0.0, 2.0, near), 0.75);
  EXPECT_LT(std::fabs(meanCorrelation(d, o.edgeLength, 9.0, 100.0, far)), 0.2);
  EXPECT_GT(near, 0);
  EXPECT_GT(far, 100);
  // Without the field, neighbours are as independent as far fibers.
  const FiberModel independent = generateCube(coherentCell(0.0));
  std::vector<Deviation> e;
  for (const Fiber& f : independent.fibers)
    e.push_back(deviationOf(f, o.edgeLength));
  EXPECT_LT(std::fabs(meanCorrelation(e, o.edgeLength, 0.0, 2.0, near)), 0.3);
}

TEST(UndulationField, BadValuesNameTheProperty)
{
  CubeOptions o = coherentCell(-1.0);
  EXPECT_NE(validateCubeOptions(o).find("UndulationCoherence is -1"), std::string::npos);
  o.undulationCoherence = NAN;
  EXPECT_NE(validateCubeOptions(o).find("UndulationCoherence is nan"), std::string::npos);
  o = coherentCell(3.0);
  o.populations = 2;
  o.crossingAngle = 45.0;
  EXPECT_NE(validateCubeOptions(o).find("UndulationCoherence is 3"), std::string::npos);
  EXPECT_TRUE(validateCubeOptions(coherentCell(3.0)).empty());
}
