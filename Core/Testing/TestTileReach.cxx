// The tile-reach rule of MPI tiles (Model/TileReach.h, PLI/PLIReach.h, groundTruthReach): a tile
// computed from only the fibers the rule selects equals the tile computed from the whole model,
// bit for bit, and no fiber the rule leaves out comes near a voxel the tile reads (brute force over
// every voxel centre of the link region), while far fibers are left out.
#include "Analysis/GroundTruth.h"
#include "Model/PeriodicTiling.h"
#include "Model/TileReach.h"
#include "PLI/PLIPipeline.h"
#include "PLI/PLIReach.h"
#include "PLI/Simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace fiberpli;
using namespace fiberpli::pli;

namespace
{
/// Random wavy fibers (bundles 0..2) in [-lo, lo]^3 with radii 0.4..1.0, a few links each.
FiberModel randomModel(int n, double lo, unsigned seed)
{
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-lo, lo), dir(-1.0, 1.0), rad(0.4, 1.0);
  FiberModel m;
  for (int f = 0; f < n; ++f)
  {
    Fiber fib;
    Vec3 p{ pos(rng), pos(rng), pos(rng) };
    Vec3 u{ dir(rng), dir(rng), dir(rng) };
    for (int k = 0; k < 5; ++k)
    {
      fib.points.push_back(p);
      fib.radii.push_back(rad(rng));
      p = p + 2.5 * u;
      u = u + Vec3{ 0.3 * dir(rng), 0.3 * dir(rng), 0.3 * dir(rng) };
    }
    fib.id = f;
    fib.bundle = f % 3;
    m.fibers.push_back(fib);
  }
  return m;
}

PLIOptions tiltedOptions()
{
  PLIOptions o;
  const double voi[6] = { -8, 8, -6, 6, -2, 2 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  o.voxelSize = 0.25;
  o.pixelSize = 0.5;
  o.numberOfRotations = 6;
  o.tiltAngle = 5.5;
  o.noiseGain = 3.0;
  o.seed = 9;
  o.opticalSigma = 0.71;
  o.numberOfThreads = 1;
  // A layer scale above 1 (with a warning): the tissue reaches 1.2 radii from the axis.
  o.layers = "0.6 -0.004 1 p; 1.2 -0.002 0.5 r";
  return o;
}

/// The fibers of `model` that reach `reach`, in model order.
FiberModel selected(const FiberModel& model, const TileReach& reach)
{
  FiberModel out;
  for (const Fiber& f : model.fibers)
    if (fiberReaches(f, reach))
      out.fibers.push_back(f);
  return out;
}

void expectSameImage(const PLIImage& a, const PLIImage& b)
{
  ASSERT_EQ(a.views.size(), b.views.size());
  for (std::size_t v = 0; v < a.views.size(); ++v)
  {
    ASSERT_EQ(a.views[v].data.size(), b.views[v].data.size());
    for (std::size_t k = 0; k < a.views[v].data.size(); ++k)
      ASSERT_EQ(a.views[v].data[k], b.views[v].data[k]) << "view " << v << " value " << k;
  }
}

/// Squared distance of p from the segment [a, b], from its definition.
double pointSegmentDistance2(const Vec3& p, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a, ap = p - a;
  const double l2 = dot(ab, ab);
  const double t = l2 > 0.0 ? std::max(0.0, std::min(1.0, dot(ap, ab) / l2)) : 0.0;
  const Vec3 d = ap - t * ab;
  return dot(d, d);
}

/// Whether some voxel centre of columns `c` (every depth of a lattice with lower corner `o`, voxel
/// size h and nz voxels deep) lies within S·r of a link of `fib`.
bool touchesVoxels(
  const Fiber& fib, const double o[3], double h, std::int64_t nz, const GridRange& c, double S)
{
  for (std::size_t k = 0; k + 1 < fib.size(); ++k)
  {
    const double r = S * fib.linkRadius(k);
    for (std::int64_t iz = 0; iz < nz; ++iz)
      for (std::int64_t j = c.j0; j < c.j1; ++j)
        for (std::int64_t i = c.i0; i < c.i1; ++i)
        {
          const Vec3 p{ o[0] + (i + 0.5) * h, o[1] + (j + 0.5) * h, o[2] + (iz + 0.5) * h };
          if (pointSegmentDistance2(p, fib.points[k], fib.points[k + 1]) <= r * r)
            return true;
        }
  }
  return false;
}

/// Brute force: no fiber of `model` missing from `part` (a selection in model order, ids
/// distinct) touches a voxel of the columns.
void expectLeftOutAreFar(const FiberModel& model, const FiberModel& part, const double o[3],
  double h, std::int64_t nz, const GridRange& c, double S)
{
  std::size_t next = 0;
  for (const Fiber& f : model.fibers)
  {
    if (next < part.fibers.size() && part.fibers[next].id == f.id)
    {
      ++next;
      continue;
    }
    EXPECT_FALSE(touchesVoxels(f, o, h, nz, c, S)) << "fiber " << f.id << " was left out";
  }
  EXPECT_EQ(next, part.fibers.size());
}
} // namespace

TEST(TileReach, LinkReachesIsTheGrownBoxOverlap)
{
  Fiber f;
  f.points = { Vec3{ 0, 0, 0 }, Vec3{ 4, 0, 0 } };
  f.radii = { 0.5, 1.0 };
  TileReach r;
  const double box[6] = { 4.9, 6, -1, 1, -1, 1 };
  std::copy(box, box + 6, r.box);
  EXPECT_TRUE(linkReaches(f, r)); // 4 + max radius 1 >= 4.9
  r.box[0] = 5.1;
  EXPECT_FALSE(linkReaches(f, r));
  r.radiusScale = 1.2; // 4 + 1.2 >= 5.1
  EXPECT_TRUE(linkReaches(f, r));
  EXPECT_FALSE(linkReaches(f, r, Vec3{ -0.2, 0, 0 }));
  r.box[0] = 7, r.box[1] = 6; // an empty box reads nothing
  EXPECT_FALSE(linkReaches(f, r));
}

TEST(TileReach, SelectedFibersGiveTheSameTileAndLeaveOutOnlyFarFibers)
{
  const FiberModel model = randomModel(120, 12.0, 5);
  const PLIOptions o = tiltedOptions();
  PLIPlan plan;
  ASSERT_TRUE(planPLI(model, o, plan).ok());
  // Tiles of a 2 × 2 split and one of a single pixel row at the edge.
  const std::vector<fiberpli::GridRange> tiles = { { 0, 16, 0, 12 }, { 16, 32, 0, 12 },
    { 0, 16, 12, 24 }, { 16, 32, 12, 24 }, { 0, 32, 23, 24 } };
  for (const fiberpli::GridRange& px : tiles)
  {
    const TileReach reach = imageReach(plan, o, px);
    EXPECT_DOUBLE_EQ(reach.radiusScale, 1.2);
    const FiberModel part = selected(model, reach);
    EXPECT_LT(part.fibers.size(), model.fibers.size()) << "a tile must not need every fiber";
    EXPECT_GT(part.fibers.size(), 0u);
    PLIImage whole, tile;
    ASSERT_TRUE(runPLI(model, o, px, whole).ok());
    ASSERT_TRUE(runPLI(part, o, px, tile).ok());
    expectSameImage(whole, tile);
    // Brute force: a fiber left out has no link within S·r of any voxel centre the rays read.
    const GridRange region =
      linkRegion(plan.lattice, simParams(plan, o), plan.views, voxelColumnsFor(plan, o, px));
    expectLeftOutAreFar(
      model, part, plan.lattice.origin, plan.lattice.voxel, plan.lattice.n[2], region, 1.2);
  }
}

TEST(TileReach, TiltedSensorAndTissueExportPieces)
{
  const FiberModel model = randomModel(300, 10.0, 11);
  PLIOptions o = tiltedOptions();
  o.tiltedSensor = true;
  o.tiltAngles = { 4.0, 8.0 };
  PLIPlan plan;
  ASSERT_TRUE(planPLI(model, o, plan).ok());
  const fiberpli::GridRange px{ 20, 32, 0, 10 };
  const FiberModel part = selected(model, imageReach(plan, o, px));
  PLIImage whole, tile;
  ASSERT_TRUE(runPLI(model, o, px, whole).ok());
  ASSERT_TRUE(runPLI(part, o, px, tile).ok());
  expectSameImage(whole, tile);

  VoxelBox box;
  box.lo[0] = 10, box.hi[0] = 30, box.lo[1] = 5, box.hi[1] = 20, box.lo[2] = 3, box.hi[2] = 9;
  const FiberModel inBox = selected(model, tissueReach(plan, box));
  EXPECT_LT(inBox.fibers.size(), model.fibers.size());
  TissueVolume a, b;
  ASSERT_TRUE(exportTissue(model, plan, o, box, a).ok());
  ASSERT_TRUE(exportTissue(inBox, plan, o, box, b).ok());
  EXPECT_EQ(a.label, b.label);
  EXPECT_EQ(a.axis, b.axis);
  expectLeftOutAreFar(model, inBox, plan.lattice.origin, plan.lattice.voxel, plan.lattice.n[2],
    GridRange{ box.lo[0], box.hi[0], box.lo[1], box.hi[1] }, 1.2);
}

TEST(TileReach, GroundTruthTileFromSelectedFibers)
{
  const FiberModel model = randomModel(300, 10.0, 17);
  // 16 x 12 pixels of 1 um, 4 x 4 voxel columns of 0.25 um each, 4 um deep.
  const PixelGrid lat = latticeForPixelGrid(Vec3{ -8, -6, 0 }, 1.0, 16, 12, -2.0, 2.0, 4);
  GroundTruthOptions opt;
  opt.threads = 1;
  for (const fiberpli::GridRange range : { fiberpli::GridRange{ 0, 8, 0, 6 },
         fiberpli::GridRange{ 8, 16, 6, 12 }, fiberpli::GridRange{ 5, 6, 0, 12 } })
  {
    const FiberModel part = selected(model, groundTruthReach(lat, opt, range));
    EXPECT_LT(part.fibers.size(), model.fibers.size());
    GroundTruthMaps a, b;
    ASSERT_EQ(computeGroundTruth(model, lat, opt, range, a).error, "");
    ASSERT_EQ(computeGroundTruth(part, lat, opt, range, b).error, "");
    int tissuePixels = 0;
    for (std::int64_t j = range.j0; j < range.j1; ++j)
      for (std::int64_t i = range.i0; i < range.i1; ++i)
      {
        const std::size_t p = static_cast<std::size_t>(i + a.nx * j);
        tissuePixels += a.fraction[p] > 0.0 ? 1 : 0;
        // NaN == NaN bit for bit: compare through the representation.
        EXPECT_EQ(std::isnan(a.direction[p]), std::isnan(b.direction[p]));
        if (!std::isnan(a.direction[p]))
        {
          EXPECT_EQ(a.direction[p], b.direction[p]);
          EXPECT_EQ(a.inclinationSigned[p], b.inclinationSigned[p]);
        }
        EXPECT_EQ(a.fraction[p], b.fraction[p]);
      }
    EXPECT_GT(tissuePixels, 0) << "no fiber in the tile: not a real comparison";
    // The voxels that bin into the range: centres inside its pixels.
    const GridRange voxels{ range.i0 * 4, range.i1 * 4, range.j0 * 4, range.j1 * 4 };
    expectLeftOutAreFar(
      model, part, lat.lattice.origin, lat.lattice.voxel, lat.lattice.n[2], voxels, 1.0);
  }
}

TEST(TileReach, PeriodicTranslatesAgainstEveryTranslate)
{
  // A 10 µm cell tiled into a 30 × 20 µm section: the tile rule per link against a loop over
  // every translate of the tiling; the tile of the restricted tiling equals the whole tiling's.
  PeriodicCell cell;
  cell.lo = Vec3{ -5, -5, -5 };
  cell.hi = Vec3{ 5, 5, 5 };
  const FiberModel model = randomModel(60, 5.0, 23);
  PLIOptions o = tiltedOptions();
  const double voi[6] = { -15, 15, -10, 10, -2, 2 };
  std::copy(voi, voi + 6, o.volumeOfInterest);
  FiberModel tiled = model;
  ASSERT_EQ(tileModel(tiled, cell, voi), "");
  PLIPlan plan;
  ASSERT_TRUE(planPLI(tiled, o, plan).ok());
  const fiberpli::GridRange px{ 40, 60, 0, 15 };
  TileReach reach = imageReach(plan, o, px);
  reach.periodic = true;
  reach.cell = cell;
  std::copy(voi, voi + 6, reach.tiling);
  FiberModel part;
  for (const Fiber& f : model.fibers)
  {
    bool some = false; // brute force: every translate tileModel makes of this fiber
    FiberModel one;
    one.fibers = { f };
    ASSERT_EQ(tileModel(one, cell, voi), "");
    for (const Fiber& t : one.fibers)
      some = some || linkReaches(t, reach);
    const bool rule = fiberReaches(f, reach);
    EXPECT_TRUE(!some || rule) << "fiber " << f.id
                               << " has a translate in the tile but was left out";
    if (rule)
      part.fibers.push_back(f);
  }
  EXPECT_LT(part.fibers.size(), model.fibers.size());
  FiberModel partTiled = part;
  ASSERT_EQ(tileModel(partTiled, cell, voi, &reach), "");
  EXPECT_LT(partTiled.fibers.size(), tiled.fibers.size() / 2)
    << "the tile makes only its own translates";
  PLIOptions same = o;
  same.bundleIds = { 0, 1, 2 };
  PLIImage whole, tile;
  ASSERT_TRUE(runPLI(tiled, same, px, whole).ok());
  ASSERT_TRUE(runPLI(partTiled, same, px, tile).ok());
  expectSameImage(whole, tile);
}
