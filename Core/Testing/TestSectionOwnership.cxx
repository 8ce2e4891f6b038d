// Guards the callers of the one ownership rule (ownerWins in Section/LinkTable.h,
// docs/pli-simulation.md §3.3): the voxeliser and the ground truth both ask it for a voxel's owner
// and must hand it the same voxel (same centre, same units), so the orientation a ground-truth
// pixel reports is the one the simulation voxelised, also for voxels whose centre is (nearly)
// equidistant from two fibers and for voxels on a capsule's surface, where a caller converting µm
// and voxel units differently would pick a different owner.
#include "Analysis/GroundTruth.h"
#include "PLI/Voxeliser.h"
#include "PLITestUtil.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace fiberpli;

namespace
{
// Lattices whose voxel size and origin are not dyadic, so a voxel centre lies within rounding of
// a tie or of a capsule surface and µm and voxel units can round differently.
struct Case
{
  double voxel, ox, oy;
};
} // namespace

TEST(SectionOwnership, GroundTruthOwnersAreTheVoxelisersOnNearTiesAndSurfaces)
{
  int tissue = 0, nearTies = 0, mismatches = 0;
  for (const Case& c : { Case{ 0.1, 0.3, 0.7 }, Case{ 0.07, -0.21, 0.49 }, Case{ 0.3, 0.9, -0.3 },
         Case{ 0.11, 0.33, 0.55 } })
  {
    const double h = c.voxel;
    const std::int64_t n = 40;
    const double z = 0.1 + 0.5 * h; // one voxel deep: the pixel (= voxel) holds one voxel
    // Voxel-centre coordinates of the lattice in µm: u·h + origin.
    auto at = [&](double ux, double uy) { return Vec3{ c.ox + ux * h, c.oy + uy * h, z }; };
    FiberModel m;
    // An X mirror-symmetric about the centre column x = 20.5 (a plane of voxel centres): every
    // centre on it is equidistant from both axes, in exact arithmetic.
    m.fibers.push_back(
      plitest::line(at(20.5, 20.5), normalized(Vec3{ 1, 1, 0 }), 40 * h, 6 * h, 0));
    m.fibers.push_back(
      plitest::line(at(20.5, 20.5), normalized(Vec3{ -1, 1, 0 }), 40 * h, 6 * h, 1));
    // Fibers through centres with radii of whole voxels: centres 3 voxels away lie on the surface.
    m.fibers.push_back(plitest::line(at(5.5, 20.0), Vec3{ 0, 1, 0 }, 40 * h, 3 * h, 2));
    m.fibers.push_back(plitest::line(at(20.0, 35.5), Vec3{ 1, 0, 0 }, 40 * h, 4 * h, 2));

    // The one lattice of both: the simulation's, here as the ground truth's pixel grid too.
    PixelGrid grid;
    SectionLattice& lat = grid.lattice;
    lat.origin[0] = c.ox;
    lat.origin[1] = c.oy;
    lat.origin[2] = 0.1;
    lat.voxel = h;
    lat.n[0] = lat.n[1] = n;
    lat.n[2] = 1;
    grid.pixelSize = h;
    pli::TissueSpec spec;
    spec.bundleIds = { 0, 1, 2 };
    spec.layers.assign(3, { pli::Layer{ 1.0, -0.001, 0.0, pli::AxisModel::Parallel } });
    pli::TissueBlock block;
    pli::voxelise(m, spec, lat, { 0, n, 0, n }, block);

    GroundTruthMaps maps;
    ASSERT_EQ(computeGroundTruth(m, grid, GroundTruthOptions{}, wholeImage(n, n), maps).error, "");

    for (std::int64_t j = 0; j < n; ++j)
      for (std::int64_t i = 0; i < n; ++i)
      {
        const std::size_t p = static_cast<std::size_t>(i + n * j);
        const bool voxelised = block.label(i, j, 0) > 0;
        tissue += voxelised;
        // Independently: is this centre within 1e-9 voxels of a tie between the X's axes?
        const Vec3 x = at(i + 0.5, j + 0.5);
        const double dA = std::fabs((x.x - x.y) - (c.ox - c.oy)) / std::sqrt(2.0);
        const double dB = std::fabs((x.x + x.y) - (c.ox + c.oy + 41 * h)) / std::sqrt(2.0);
        nearTies += voxelised && std::fabs(dA - dB) < 1e-9 * h;
        if (voxelised != (maps.fraction[p] > 0.0))
        {
          ++mismatches;
          ADD_FAILURE() << "voxel " << i << "," << j << " (h " << h << "): voxelised " << voxelised
                        << ", ground-truth fraction " << maps.fraction[p];
          continue;
        }
        if (!voxelised)
          continue;
        float a[3];
        block.axis(i, j, 0, a);
        double d = std::atan2(a[1], a[0]);
        d = d < 0 ? d + M_PI : d;
        d = d >= M_PI ? d - M_PI : d;
        const double e = std::fabs(d - maps.direction[p]);
        if (std::min(e, M_PI - e) > 1e-5)
        {
          ++mismatches;
          ADD_FAILURE() << "voxel " << i << "," << j << " (h " << h << "): voxelised axis at "
                        << d * 180 / M_PI << " deg, ground truth " << maps.direction[p] * 180 / M_PI
                        << " deg";
        }
      }
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(tissue, 1000); // the test looks at real tissue
  EXPECT_GT(nearTies, 20); // and at voxels on the tie plane of the X
}
