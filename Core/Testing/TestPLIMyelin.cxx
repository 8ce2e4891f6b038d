// Myelinated fibers in the PLI tissue (docs/pli-simulation.md §3.2): with inner radii and no Layers
// text the axon (inside inner_radius: isotropic) and the myelin sheath (up to radius: radial axis)
// are two layers, counted voxel by voxel against an independent count of lattice centres; without
// inner radii, or with a Layers text, the tissue is exactly what it was.
#include "PLI/PLIPipeline.h"
#include "PLI/TissueSpec.h"
#include "PLI/Voxeliser.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace fiberpli;
using namespace fiberpli::pli;

namespace
{

SectionLattice lattice(int n, int nz)
{
  SectionLattice l;
  l.voxel = 1.0;
  l.n[0] = n;
  l.n[1] = n;
  l.n[2] = nz;
  return l;
}

/// A straight fiber along z through (x, y) across the section, radius r, inner radius g·r (g = 0:
/// none).
FiberModel straightFiber(double x, double y, double r, double g)
{
  FiberModel m;
  Fiber f;
  f.points = { { x, y, -10.0 }, { x, y, 30.0 } };
  f.radii = { r, r };
  if (g > 0.0)
  {
    f.innerRadii = { g * r, g * r };
  }
  m.fibers.push_back(f);
  return m;
}

} // namespace

TEST(PLIMyelin, AxonAndSheathVoxelsAreTheLatticeCentresInsideTheirRadii)
{
  const double x = 10.3, y = 9.6, r = 7.2, g = 0.6;
  const FiberModel m = straightFiber(x, y, r, g);
  TissueSpec spec;
  ASSERT_TRUE(makeTissueSpec("", { 0 }, -0.001, 2.0, 0.0, spec, true).ok());
  ASSERT_EQ(spec.layers[0].size(), 2u);
  EXPECT_EQ(
    spec.layers[0][1].dn, 0.001); // radial sheath: the opposite sign of the parallel default
  EXPECT_EQ(spec.layers[0][0].dn, 0.0);
  const SectionLattice lat = lattice(21, 4);
  TissueBlock block;
  voxelise(m, spec, lat, { 0, 21, 0, 21 }, block);
  // Independent count: voxel centres (i + ½, j + ½) at distance ρ from the axis; axon ρ <= g·r,
  // sheath g·r < ρ <= r. Their areas are π(g·r)² and π(1 − g²)·r² up to the lattice's boundary
  // error.
  int axonExpected = 0, sheathExpected = 0;
  for (int i = 0; i < 21; ++i)
    for (int j = 0; j < 21; ++j)
    {
      const double d2 = std::pow(i + 0.5 - x, 2) + std::pow(j + 0.5 - y, 2);
      axonExpected += d2 <= g * g * r * r ? 1 : 0;
      sheathExpected += d2 > g * g * r * r && d2 <= r * r ? 1 : 0;
    }
  EXPECT_NEAR(axonExpected, M_PI * g * g * r * r, 2 * M_PI * g * r);
  EXPECT_NEAR(sheathExpected, M_PI * (1 - g * g) * r * r, 2 * M_PI * (1 + g) * r);
  for (int k = 0; k < 4; ++k)
  {
    int axon = 0, sheath = 0;
    for (int i = 0; i < 21; ++i)
      for (int j = 0; j < 21; ++j)
      {
        float a[3];
        block.axis(i, j, k, a);
        if (block.label(i, j, k) == 1)
        {
          ++axon;
          EXPECT_EQ(a[0] * a[0] + a[1] * a[1] + a[2] * a[2], 0.0f); // isotropic
        }
        else if (block.label(i, j, k) == 2)
        {
          ++sheath;
          // Radial: the unit vector from the axis to the centre.
          const double dx = i + 0.5 - x, dy = j + 0.5 - y, d = std::hypot(dx, dy);
          EXPECT_NEAR(a[0], dx / d, 1e-6);
          EXPECT_NEAR(a[1], dy / d, 1e-6);
          EXPECT_NEAR(a[2], 0.0, 1e-6);
        }
      }
    EXPECT_EQ(axon, axonExpected) << "slice " << k;
    EXPECT_EQ(sheath, sheathExpected) << "slice " << k;
  }
}

TEST(PLIMyelin, TaperedInnerRadiusFollowsTheLinkLikeTheRadius)
{
  // A link whose inner radius grows from 2 to 4 (outer 6 throughout) along z: at the axis
  // parameter t the axon holds the centres within 2 + 2t of the axis.
  FiberModel m = straightFiber(10.3, 10.6, 6.0, 0.0);
  m.fibers[0].points = { { 10.3, 10.6, 0.0 }, { 10.3, 10.6, 10.0 } };
  m.fibers[0].innerRadii = { 2.0, 4.0 };
  TissueSpec spec;
  ASSERT_TRUE(makeTissueSpec("", { 0 }, -0.001, 0.0, 0.0, spec, true).ok());
  TissueBlock block;
  voxelise(m, spec, lattice(21, 10), { 0, 21, 0, 21 }, block);
  for (int k = 0; k < 10; ++k)
  {
    const double ri = 2.0 + 2.0 * (k + 0.5) / 10.0;
    for (int i = 0; i < 21; ++i)
      for (int j = 0; j < 21; ++j)
      {
        const double d2 = std::pow(i + 0.5 - 10.3, 2) + std::pow(j + 0.5 - 10.6, 2);
        const int expected = d2 <= ri * ri ? 1 : (d2 <= 36.0 ? 2 : 0);
        ASSERT_EQ(block.label(i, j, k), expected) << i << " " << j << " " << k;
      }
  }
}

TEST(PLIMyelin, WithoutInnerRadiiOrWithLayersTheTissueIsUnchanged)
{
  const FiberModel plain = straightFiber(10.3, 9.6, 7.2, 0.0);
  const FiberModel myelinated = straightFiber(10.3, 9.6, 7.2, 0.6);
  PLIOptions o;
  o.voxelSize = 1.0;
  PLIPlan plain1, myelin1, layered1, layered2;
  ASSERT_TRUE(planPLITissue(plain, o, plain1).ok());
  ASSERT_TRUE(planPLITissue(myelinated, o, myelin1).ok());
  EXPECT_EQ(plain1.tissue.maxLayers(), 1);  // today's single parallel layer
  EXPECT_EQ(myelin1.tissue.maxLayers(), 2); // axon + sheath, from the data alone
  o.myelin = true;                          // an MPI tile told the whole model is myelinated
  ASSERT_TRUE(planPLITissue(plain, o, layered1).ok());
  EXPECT_EQ(layered1.tissue.maxLayers(), 2);
  // A Layers text is used as it is: the inner radii change nothing.
  o.myelin = false;
  o.layers = "0.5 0 0 b; 1 0.004 0 r";
  ASSERT_TRUE(planPLITissue(plain, o, layered1).ok());
  ASSERT_TRUE(planPLITissue(myelinated, o, layered2).ok());
  const SectionLattice lat = lattice(21, 3);
  TissueBlock a, b, c, d;
  voxelise(plain, layered1.tissue, lat, { 0, 21, 0, 21 }, a);
  voxelise(myelinated, layered2.tissue, lat, { 0, 21, 0, 21 }, b);
  EXPECT_EQ(a.words, b.words);
  // No inner radii, default layers: the words of today's single layer.
  TissueSpec today;
  today.bundleIds = { 0 };
  today.layers = { { Layer{ 1.0, -0.001, 0.0, AxisModel::Parallel } } };
  voxelise(plain, today, lat, { 0, 21, 0, 21 }, c);
  voxelise(plain, plain1.tissue, lat, { 0, 21, 0, 21 }, d);
  EXPECT_EQ(c.words, d.words);
}
