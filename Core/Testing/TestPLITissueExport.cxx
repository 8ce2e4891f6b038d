// Tissue export: the voxelised sub-volume equals a brute-force voxelisation written here from the
// definition (every voxel centre against every link, nearest capsule wins, ties to the later link
// in bundle / fiber / link order, layer by the first scale that contains the centre); boxes are
// checked and oversized ones refused before allocation.
#include "PLI/TissueExport.h"
#include "PLITestUtil.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>

using namespace fiberpli;
using namespace fiberpli::pli;

namespace
{
// Two bundles (ids 0 and 3) with different layers, a bent fiber with a tapered radius and two
// straight ones, one tapered, crossing it. Dyadic numbers, so the voxel-unit
// arithmetic of the Core and the µm arithmetic here give identical distances.
FiberModel model()
{
  FiberModel m;
  Fiber a;
  a.points = { { -8, -1.25, -0.5 }, { -1.5, 0.75, 0.25 }, { 2.25, 3.5, 1.5 }, { 9, 4.25, 2 } };
  a.radii = { 1.375, 1.625, 1.875, 1.5 };
  a.bundle = 0;
  m.fibers.push_back(a);
  Fiber b;
  b.points = { { 1.75, -9, -3 }, { 0.5, 9, 3.5 } };
  b.radii = { 1.125, 1.125 };
  b.bundle = 3;
  m.fibers.push_back(b);
  Fiber c;
  c.points = { { -9, -4.5, 2.5 }, { 9, -3.25, -2.75 } };
  c.radii = { 0.875, 1.25 };
  c.bundle = 0;
  m.fibers.push_back(c);
  return m;
}

PLIOptions options()
{
  PLIOptions o;
  const double voi[6] = { -6, 6, -6, 6, -4, 4 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  o.voxelSize = 0.5;
  o.pixelSize = 0.5;
  o.layers = "0: 0.5 -0.004 10 p; 0.75 0 5 b; 1 0.004 1 r | 3: 1 -0.002 2 p";
  return o;
}

struct Expected
{
  std::int32_t label = 0;
  double axis[3] = { 0, 0, 0 };
};

// The definition, voxel by voxel. Layers of bundle id 0 and 3 as in options().
Expected bruteForce(const FiberModel& m, const Vec3& c)
{
  struct L
  {
    double scale;
    char model;
  };
  const std::vector<std::vector<L>> layers = { { { 0.5, 'p' }, { 0.75, 'b' }, { 1.0, 'r' } },
    { { 1.0, 'p' } } };
  const int bundleIds[2] = { 0, 3 }, maxLayers = 3;
  Expected e;
  double best = std::numeric_limits<double>::infinity();
  for (int slot = 0; slot < 2; ++slot)
    for (const Fiber& f : m.fibers)
    {
      if (f.bundle != bundleIds[slot])
        continue;
      for (std::size_t s = 0; s + 1 < f.points.size(); ++s)
      {
        const Vec3 P = f.points[s], Q = f.points[s + 1];
        double t = dot(c - P, Q - P) / norm2(Q - P);
        t = std::min(1.0, std::max(0.0, t));
        const Vec3 X = P + t * (Q - P);
        const double r = (1 - t) * f.radii[s] + t * f.radii[s + 1];
        const double d2 = norm2(c - X);
        if (d2 > r * r || d2 > best) // outermost scale is 1 for both bundles
          continue;
        best = d2; // equal distance: the later link wins
        int l = 0;
        while (d2 > layers[slot][l].scale * layers[slot][l].scale * r * r)
          ++l;
        e.label = 1 + slot * maxLayers + l;
        const Vec3 u = layers[slot][l].model == 'p' ? normalized(Q - P) : normalized(c - X);
        const bool none =
          layers[slot][l].model == 'b' || (layers[slot][l].model == 'r' && norm(c - X) < 1e-9 * r);
        e.axis[0] = none ? 0 : u.x;
        e.axis[1] = none ? 0 : u.y;
        e.axis[2] = none ? 0 : u.z;
      }
    }
  return e;
}
} // namespace

// Tile size 64: the box is one tile; 5: many tiles not dividing the box (the export's own tiling).
class PLITissueExportTiles : public ::testing::TestWithParam<int>
{
};
INSTANTIATE_TEST_SUITE_P(TileSizes, PLITissueExportTiles, ::testing::Values(64, 5));

TEST_P(PLITissueExportTiles, SubVolumeEqualsBruteForceVoxelisation)
{
  const FiberModel m = model();
  PLIOptions o = options();
  o.tileSize = GetParam();
  PLIPlan plan;
  const Status ps = planPLI(m, o, plan);
  ASSERT_TRUE(ps.ok()) << ps.error;
  const double box[6] = { -3.2, 4.1, -6, 2, -1, 3.7 };
  VoxelBox vb;
  ASSERT_TRUE(tissueBox(plan, box, vb).ok());
  // Centres −5.75 + 0.5·k: x from −2.75 (k = 6) to 3.75 (k = 19), z from −0.75 to 3.25.
  EXPECT_EQ(vb.lo[0], 6);
  EXPECT_EQ(vb.hi[0], 20);
  EXPECT_EQ(vb.lo[1], 0);
  EXPECT_EQ(vb.hi[1], 16);
  EXPECT_EQ(vb.lo[2], 6);
  EXPECT_EQ(vb.hi[2], 15);
  TissueVolume tv;
  ASSERT_TRUE(exportTissue(m, plan, o, vb, tv).ok());
  ASSERT_EQ(tv.label.size(), static_cast<std::size_t>(vb.count()));
  std::size_t p = 0, labelled = 0, radial = 0, mismatches = 0;
  for (std::int64_t k = vb.lo[2]; k < vb.hi[2]; ++k)
    for (std::int64_t j = vb.lo[1]; j < vb.hi[1]; ++j)
      for (std::int64_t i = vb.lo[0]; i < vb.hi[0]; ++i, ++p)
      {
        const Vec3 c{ -6 + 0.5 * (i + 0.5), -6 + 0.5 * (j + 0.5), -4 + 0.5 * (k + 0.5) };
        const Expected e = bruteForce(m, c);
        if (tv.label[p] != e.label)
          ++mismatches;
        for (int d = 0; d < 3; ++d)
          EXPECT_NEAR(tv.axis[3 * p + d], e.axis[d], 1e-6) << i << " " << j << " " << k;
        labelled += e.label > 0 ? 1 : 0;
        radial += e.label == 3 ? 1 : 0;
      }
  EXPECT_EQ(mismatches, 0u);
  // The box is not trivial: fibers of both bundles and every layer are in it.
  EXPECT_GT(labelled, 200u);
  EXPECT_GT(radial, 50u);
}

TEST(PLITissueExport, BoxesAreCheckedAndOversizedOnesRefused)
{
  const FiberModel m = model();
  const PLIOptions o = options();
  PLIPlan plan;
  const Status ps = planPLI(m, o, plan);
  ASSERT_TRUE(ps.ok()) << ps.error;
  VoxelBox vb;
  const double whole[6] = { 1, -1, 1, -1, 1, -1 };
  ASSERT_TRUE(tissueBox(plan, whole, vb).ok());
  EXPECT_EQ(vb.count(), 24 * 24 * 16);
  const double mixed[6] = { 1, -1, 0, 1, 0, 1 }; // min > max on x only
  EXPECT_NE(tissueBox(plan, mixed, vb).error.find("TissueVolume x"), std::string::npos);
  const double nanBox[6] = { 0, 1, 0, NAN, 0, 1 };
  EXPECT_NE(tissueBox(plan, nanBox, vb).error.find("TissueVolume y"), std::string::npos);
  const double outside[6] = { 100, 200, 0, 1, 0, 1 };
  EXPECT_NE(tissueBox(plan, outside, vb).error.find("no voxel centre"), std::string::npos);

  ASSERT_TRUE(tissueBox(plan, whole, vb).ok());
  ::setenv("FIBERPLI_MEMORY_LIMIT", "64K", 1);
  TissueVolume tv;
  const Status st = exportTissue(m, plan, o, vb, tv);
  ::unsetenv("FIBERPLI_MEMORY_LIMIT");
  EXPECT_NE(st.error.find("TissueVolume"), std::string::npos) << st.error;
  EXPECT_NE(st.error.find("memory budget"), std::string::npos) << st.error;
  EXPECT_TRUE(tv.label.empty());
  EXPECT_TRUE(exportTissue(m, plan, o, vb, tv).ok());
}

// Progress between tiles, increasing from 0 to 1; returning false stops the export (empty arrays).
TEST(PLITissueExport, ReportsProgressAndAborts)
{
  const FiberModel m = model();
  PLIOptions o = options();
  o.tileSize = 4;
  PLIPlan plan;
  ASSERT_TRUE(planPLI(m, o, plan).ok());
  const double whole[6] = { 1, -1, 1, -1, 1, -1 };
  VoxelBox vb;
  ASSERT_TRUE(tissueBox(plan, whole, vb).ok());
  std::vector<double> seen;
  TissueVolume tv;
  const Status done = exportTissue(m, plan, o, vb, tv,
    [&seen](double f)
    {
      seen.push_back(f);
      return true;
    });
  ASSERT_TRUE(done.error.empty());
  EXPECT_FALSE(done.aborted);
  ASSERT_EQ(seen.size(), 6u * 6u + 1u); // 24 x 24 columns in tiles of 4, then 1
  EXPECT_EQ(seen.front(), 0.0);
  EXPECT_EQ(seen.back(), 1.0);
  for (std::size_t a = 1; a < seen.size(); ++a)
    EXPECT_GT(seen[a], seen[a - 1]);
  int calls = 0;
  const Status stopped = exportTissue(m, plan, o, vb, tv, [&calls](double) { return ++calls < 3; });
  ASSERT_TRUE(stopped.error.empty());
  EXPECT_TRUE(stopped.aborted);
  EXPECT_EQ(calls, 3);
  EXPECT_TRUE(tv.label.empty());
  EXPECT_TRUE(tv.axis.empty());
}
