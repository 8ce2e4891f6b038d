// Voxeliser (docs/pli-simulation.md §3.3, test vectors S-8) and axis interpolation (§4.5, S-9).
#include "Model/PeriodicTiling.h"
#include "PLI/AxisSampler.h"
#include "PLI/TissueSpec.h"
#include "PLI/Voxeliser.h"
#include "PLITestUtil.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

using namespace fiberpli;
using namespace fiberpli::pli;
using namespace plitest;

namespace
{
SectionLattice box(double x, double y, double z)
{
  SectionLattice l;
  l.voxel = 1.0;
  l.n[0] = static_cast<std::int64_t>(x);
  l.n[1] = static_cast<std::int64_t>(y);
  l.n[2] = static_cast<std::int64_t>(z);
  return l;
}

TissueSpec spec(std::vector<Layer> layers)
{
  TissueSpec s;
  s.bundleIds = { 0 };
  s.layers = { layers };
  return s;
}

FiberModel fiber(Vec3 a, Vec3 b, double r)
{
  FiberModel m;
  Fiber f;
  f.points = { a, b };
  f.radii = { r, r };
  m.fibers.push_back(f);
  return m;
}
} // namespace

TEST(PLIVoxeliser, S8aThinFiberRows)
{
  const SectionLattice lat = box(3, 5, 7);
  TissueBlock b;
  voxelise(fiber({ 1, 3, 0 }, { 1, 3, 7 }, 2), spec({ { 1, 0, 0, AxisModel::Parallel } }), lat,
    { 0, 3, 0, 5 }, b);
  const int expected[3][5] = { { 0, 1, 1, 1, 1 }, { 0, 1, 1, 1, 1 }, { 0, 0, 1, 1, 0 } };
  for (int k = 0; k < 7; ++k)
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 5; ++j)
      {
        ASSERT_EQ(b.label(i, j, k), expected[i][j]) << i << " " << j << " " << k;
        float a[3];
        b.axis(i, j, k, a);
        if (expected[i][j])
        {
          EXPECT_EQ(a[0], 0.0f);
          EXPECT_EQ(a[1], 0.0f);
          EXPECT_EQ(a[2], 1.0f);
        }
      }
}

TEST(PLIVoxeliser, S8bRadialAxes)
{
  const SectionLattice lat = box(15, 15, 15);
  TissueBlock b;
  voxelise(fiber({ 0, 2.5, -5000 }, { 0, 2.5, 5000 }, 10),
    spec({ { 1, 0.004, 1, AxisModel::Radial } }), lat, { 0, 15, 0, 15 }, b);
  for (int k = 0; k < 15; k += 7)
  {
    int count = 0;
    for (int i = 0; i < 15; ++i)
      for (int j = 0; j < 15; ++j)
      {
        const double x = i + 0.5, y = j + 0.5 - 2.5;
        const bool in = x * x + y * y <= 100;
        ASSERT_EQ(b.label(i, j, k), in ? 1 : 0) << i << " " << j;
        if (!in)
          continue;
        ++count;
        float a[3];
        b.axis(i, j, k, a);
        const double beta = std::atan2(y, x);
        EXPECT_NEAR(a[0], std::cos(beta), 1e-6);
        EXPECT_NEAR(a[1], std::sin(beta), 1e-6);
        EXPECT_NEAR(a[2], 0.0, 1e-6);
      }
    EXPECT_EQ(count, 103);
  }
}

TEST(PLIVoxeliser, S8cThreeLayers)
{
  const SectionLattice lat = box(15, 15, 15);
  TissueBlock b;
  voxelise(fiber({ 0, 2.5, -5000 }, { 0, 2.5, 5000 }, 10),
    spec({ { 0.3, -0.004, 1, AxisModel::Parallel }, { 0.6, 0, 1, AxisModel::Background },
      { 1, 0.004, 1, AxisModel::Radial } }),
    lat, { 0, 15, 0, 15 }, b);
  std::map<int, int> count;
  for (int i = 0; i < 15; ++i)
    for (int j = 0; j < 15; ++j)
    {
      const int l = b.label(i, j, 4);
      ++count[l];
      float a[3];
      b.axis(i, j, 4, a);
      if (l == 1)
      {
        EXPECT_EQ(a[2], 1.0f);
      }
      else if (l == 2)
      {
        EXPECT_TRUE(a[0] == 0 && a[1] == 0 && a[2] == 0);
      }
      else if (l == 3)
      {
        EXPECT_NEAR(a[0] * (i + 0.5) + a[1] * (j - 2.0), std::hypot(i + 0.5, j - 2.0), 1e-5);
      }
    }
  EXPECT_EQ(count[0], 122);
  EXPECT_EQ(count[1], 13);
  EXPECT_EQ(count[2], 29);
  EXPECT_EQ(count[3], 61);
}

TEST(PLIVoxeliser, S8dOrderAndSplitIndependence)
{
  // Touching and overlapping fibers of two bundles, so that the tie rule matters.
  FiberModel m;
  m.fibers.push_back(line({ 5, 5, 5 }, dirVec(10, 5), 30, 3.0, 0));
  m.fibers.push_back(line({ 9, 6, 5 }, dirVec(100, -20), 30, 2.5, 1));
  m.fibers.push_back(line({ 5, 9, 4 }, dirVec(45, 30), 30, 2.0, 0));
  TissueSpec s;
  s.bundleIds = { 0, 1 };
  s.layers = { { { 0.5, 0, 1, AxisModel::Background }, { 1, 0.004, 1, AxisModel::Radial } },
    { { 1, -0.002, 1, AxisModel::Parallel } } };
  const SectionLattice lat = box(14, 14, 10);
  TissueBlock whole;
  const VoxeliseStats st = voxelise(m, s, lat, { 0, 14, 0, 14 }, whole);
  EXPECT_TRUE(st.overlap);
  EXPECT_GT(st.labelled, 100);
  // Split into four blocks of different shapes: every voxel must match bit for bit.
  const GridRange parts[] = { { 0, 5, 0, 14 }, { 5, 14, 0, 3 }, { 5, 14, 3, 9 }, { 5, 14, 9, 14 } };
  for (const GridRange& c : parts)
  {
    TissueBlock part;
    voxelise(m, s, lat, c, part);
    for (std::int64_t j = c.j0; j < c.j1; ++j)
      for (std::int64_t i = c.i0; i < c.i1; ++i)
        for (int k = 0; k < 10; ++k)
        {
          ASSERT_EQ(part.label(i, j, k), whole.label(i, j, k));
          float a[3], b[3];
          part.axis(i, j, k, a);
          whole.axis(i, j, k, b);
          ASSERT_TRUE(a[0] == b[0] && a[1] == b[1] && a[2] == b[2]);
        }
  }
}

TEST(PLIVoxeliser, LateralBackgroundLeavesOutsideEmpty)
{
  const SectionLattice lat = box(4, 4, 4);
  TissueBlock b;
  voxelise(fiber({ -100, 2, 2 }, { 100, 2, 2 }, 1.5),
    spec({ { 1, -0.001, 0, AxisModel::Parallel } }), lat, { -3, 7, 0, 4 }, b,
    LateralOutside::Background);
  EXPECT_EQ(b.label(-1, 1, 1), 0);
  EXPECT_EQ(b.label(4, 1, 1), 0);
  EXPECT_EQ(b.label(0, 1, 1), 1);
  TissueBlock c;
  voxelise(fiber({ -100, 2, 2 }, { 100, 2, 2 }, 1.5),
    spec({ { 1, -0.001, 0, AxisModel::Parallel } }), lat, { -3, 7, 0, 4 }, c,
    LateralOutside::SampleFibers);
  EXPECT_EQ(c.label(-1, 1, 1), 1);
}

namespace
{
// S-9 field: 2×1×1 voxels of label 1 (or label 2 for voxel 1), axes a and b.
TissueBlock field(const float a[3], const float b[3], int label1 = 1)
{
  TissueBlock t;
  t.reset({ 0, 2, 0, 1 }, 1);
  t.setVoxel(0, 0, 0, 1, a);
  t.setVoxel(1, 0, 0, label1, b);
  return t;
}

void expectAxis(const TissueBlock& t, double px, Interp in, double x, double y)
{
  const double p[3] = { px, 0.5, 0.5 };
  double out[3];
  ASSERT_TRUE(sampleAxis(t, p, 1, in, t.cols, out));
  EXPECT_NEAR(out[0], x, 1e-6);
  EXPECT_NEAR(out[1], y, 1e-6);
  EXPECT_NEAR(out[2], 0.0, 1e-6);
}
} // namespace

TEST(PLIInterpolation, S9SlerpAndLerp)
{
  const float a[3] = { 1, 0, 0 }, b[3] = { 0, 1, 0 };
  const TissueBlock t = field(a, b);
  expectAxis(t, 0.9, Interp::Slerp, 0.809017, 0.587785);
  expectAxis(t, 0.9, Interp::Lerp, 0.832050, 0.554700);
  expectAxis(t, 1.0, Interp::Slerp, 0.707107, 0.707107);
  expectAxis(t, 1.0, Interp::Lerp, 0.707107, 0.707107);
  expectAxis(t, 0.9, Interp::NN, 1, 0);

  const float f[3] = { static_cast<float>(std::cos(2 * M_PI / 3)),
    static_cast<float>(std::sin(2 * M_PI / 3)), 0 };
  const TissueBlock u = field(a, f);
  // Float storage of b limits these to ~1e-7.
  expectAxis(u, 0.9, Interp::Slerp, 0.913545, -0.406737);
  expectAxis(u, 0.9, Interp::Lerp, 0.917663, -0.397360);
  expectAxis(u, 1.0, Interp::Slerp, 0.866025, -0.5);
  expectAxis(u, 1.0, Interp::Lerp, 0.866025, -0.5);

  const TissueBlock v = field(a, b, 2);
  expectAxis(v, 0.9, Interp::Slerp, 1, 0);
  expectAxis(v, 0.9, Interp::Lerp, 1, 0);
}

TEST(PLIInterpolation, NoAxisWhenAllNeighboursMissing)
{
  const float z[3] = { 0, 0, 0 };
  const TissueBlock t = field(z, z);
  const double p[3] = { 0.7, 0.5, 0.5 };
  double out[3];
  EXPECT_FALSE(sampleAxis(t, p, 1, Interp::Slerp, t.cols, out));
  EXPECT_FALSE(sampleAxis(t, p, 1, Interp::NN, t.cols, out));
}

TEST(PLILayers, GrammarAndValidation)
{
  TissueSpec s;
  Status st = makeTissueSpec("0.333 -0.004 10 p; 0.666 0 5 b; 1 0.004 1 r | 2: 1 -0.001 5 p",
    { 2, 0, 5, 0 }, -0.001, 0, 0.5, s);
  ASSERT_TRUE(st.ok()) << st.error;
  ASSERT_EQ(s.bundleIds, (std::vector<int>{ 0, 2, 5 }));
  EXPECT_EQ(s.layers[0].size(), 3u);
  EXPECT_EQ(s.layers[1].size(), 1u);
  EXPECT_EQ(s.layers[1][0].muPerMm, 5.0);
  EXPECT_EQ(s.labelCount(), 1 + 3 * 3);
  EXPECT_EQ(s.backgroundMu, 0.5);

  ASSERT_TRUE(makeTissueSpec("", { 1 }, -0.002, 3, 0, s).ok());
  EXPECT_EQ(s.layers[0][0].dn, -0.002);
  EXPECT_EQ(s.layers[0][0].muPerMm, 3.0);

  EXPECT_NE(makeTissueSpec("1 0.004 1 b", { 0 }, 0, 0, 0, s).error.find("'b'"), std::string::npos);
  EXPECT_FALSE(makeTissueSpec("0.5 0 0 p; 0.5 0 0 r", { 0 }, 0, 0, 0, s).ok());
  EXPECT_FALSE(makeTissueSpec("1 0 0 q", { 0 }, 0, 0, 0, s).ok());
  EXPECT_FALSE(makeTissueSpec("1 0 p", { 0 }, 0, 0, 0, s).ok());
  EXPECT_FALSE(makeTissueSpec("3: 1 0 0 p", { 0 }, 0, 0, 0, s).ok()); // bundle 0 has no group
  st = makeTissueSpec("1 0.004 1 r; 0.5 -0.004 1 p", { 0 }, 0, 0, 0, s);
  ASSERT_TRUE(st.ok());
  EXPECT_EQ(s.layers[0][0].scale, 0.5); // sorted, with a warning
  EXPECT_FALSE(st.warnings.empty());
  st = makeTissueSpec("1 0.004 1 p", { 0 }, 0, 0, 0, s);
  EXPECT_EQ(st.warnings.size(), 1u); // parallel with dn > 0
}

namespace
{
// A closed fiber along x through the cell [0, 20]³ (last point = first + (20, 0, 0)), waving in y.
Fiber closedWave(double y, double z, double r, int bundle)
{
  Fiber f;
  for (int i = 0; i <= 10; ++i)
  {
    const double x = 2.0 * i;
    f.points.push_back({ x, y + 2.0 * std::sin(2.0 * M_PI * x / 20.0), z });
    f.radii.push_back(r);
  }
  f.bundle = bundle;
  return f;
}

PeriodicCell cell(double ex, double ey, double ez)
{
  PeriodicCell c;
  c.lo = { 0, 0, 0 };
  c.hi = { ex, ey, ez };
  return c;
}

// The cell's model tiled over the cell itself (as PLISimulation tiles its volume of interest),
// voxelised with one parallel layer on a 1 µm lattice over the cell.
VoxeliseStats voxeliseTiledCell(FiberModel m, const PeriodicCell& c)
{
  const double b[6] = { 0, c.hi.x, 0, c.hi.y, 0, c.hi.z };
  EXPECT_EQ(tileModel(m, c, b), "");
  TissueSpec s;
  s.bundleIds = bundlesOf(m);
  s.layers.assign(s.bundleIds.size(), { { 1, 0, 1, AxisModel::Parallel } });
  const SectionLattice lat = box(c.hi.x, c.hi.y, c.hi.z);
  TissueBlock block;
  return voxelise(m, s, lat, { 0, lat.n[0], 0, lat.n[1] }, block);
}
} // namespace

// The translates of a closed fiber by its closure are one endless fiber: its copies meet end to
// start at the cell faces and share the voxels round the joint, which is no overlap.
TEST(PLIVoxeliser, ClosedFiberTranslatesAreOneStrand)
{
  FiberModel m;
  m.fibers.push_back(closedWave(10, 10, 3, 0));
  const double b[6] = { 0, 20, 0, 20, 0, 20 };
  FiberModel tiled = m;
  ASSERT_EQ(tileModel(tiled, cell(20, 20, 20), b), "");
  ASSERT_EQ(tiled.fibers.size(), 3u); // shifts -1, 0, +1 along x
  const std::vector<std::int32_t> strands = fiberStrands(tiled);
  EXPECT_EQ(strands, std::vector<std::int32_t>(3, 0));
  EXPECT_FALSE(voxeliseTiledCell(m, cell(20, 20, 20)).overlap);
  // A second closed fiber, parallel and 8 µm apart (gap 2 µm): still no overlap, two strands.
  m.fibers.push_back(closedWave(10, 2, 3, 1));
  EXPECT_FALSE(voxeliseTiledCell(m, cell(20, 20, 20)).overlap);
  // Fibers that merely touch end to start without being translates stay different fibers.
  FiberModel pair;
  pair.fibers.push_back(line({ 6, 5, 5 }, { 1, 0, 0 }, 6, 2.0, 0));   // (0,5,5) → (12,5,5)
  pair.fibers.push_back(line({ 12, 11, 5 }, { 0, 1, 0 }, 6, 2.0, 0)); // (12,5,5) → (12,17,5)
  EXPECT_EQ(fiberStrands(pair), (std::vector<std::int32_t>{ 0, 1 }));
}

// A real overlap of two fibers of a periodic cell still counts: a fiber crossing the closed one,
// and the translate by a lattice vector other than the closure (a cell narrower than the fiber).
TEST(PLIVoxeliser, OverlapInAPeriodicCellStillCounts)
{
  FiberModel m;
  m.fibers.push_back(closedWave(10, 10, 3, 0));
  Fiber across;
  for (int i = 0; i <= 10; ++i)
  {
    across.points.push_back({ 10, 2.0 * i, 10 });
    across.radii.push_back(2);
  }
  m.fibers.push_back(across);
  EXPECT_TRUE(voxeliseTiledCell(m, cell(20, 20, 20)).overlap);
  // Straight closed fiber of radius 3 in a cell 4 µm wide in y: its y-translates overlap it.
  FiberModel narrow;
  narrow.fibers.push_back(line({ 10, 2, 10 }, { 1, 0, 0 }, 10, 3.0, 0)); // (0,2,10) → (20,2,10)
  EXPECT_TRUE(voxeliseTiledCell(narrow, cell(20, 4, 20)).overlap);
  // The same cell 8 µm wide: the translates are 2 µm apart, no overlap.
  EXPECT_FALSE(voxeliseTiledCell(narrow, cell(20, 8, 20)).overlap);
}
