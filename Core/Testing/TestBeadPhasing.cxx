// BeadPhasing (docs/tissue-models.md §10.3): a profile is turned so that its beads avoid the
// beads of the fibers next to it; an isolated fiber keeps its profile. In a beaded periodic
// lattice cell the phasing only permutes each fiber's radii cyclically (same values, same
// volume) and leaves fewer overlapping capsule pairs (an own brute-force periodic count).
#include "PeriodicReference.h"
#include "Tissue/BeadPhasing.h"
#include "Tissue/CubeGenerator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

using namespace fiberpli;

TEST(BeadPhasing, ABeadAvoidsItsNeighboursBead)
{
  // Two fibers 2.2 µm apart, radius 1 with a bead of 1.5 at point 3 of 10: beads side by side
  // overlap (1.5 + 1.5 > 2.2), a bead beside a thin part does not (1.5 + 1 > 2.2 by 0.3, the
  // least possible); a third fiber far away keeps its profile.
  std::vector<double> r(10, 1.0);
  r[3] = 1.5;
  const std::vector<std::vector<double>> radii{ r, r, r };
  const std::vector<Seed2D> centres{ { 0.0, 0.0 }, { 2.2, 0.0 }, { 10.0, 10.0 } };
  const std::vector<std::size_t> s = beadPhases(radii, centres, 20.0);
  EXPECT_EQ(s[0], 0u);
  EXPECT_NE((3 + 10 - s[1]) % 10, 3u); // fiber 1's bead is not at fiber 0's bead
  EXPECT_EQ(s[1], 1u);                 // the smallest shift that moves it away
  EXPECT_EQ(s[2], 0u);
  // Through the periodic boundary: the neighbour at 19 is 1 away from the one at 0.
  const std::vector<Seed2D> wrapped{ { 0.0, 0.0 }, { 19.0, 0.0 } };
  EXPECT_EQ(beadPhases({ r, r }, wrapped, 20.0)[1], 1u);
}

TEST(BeadPhasing, ALatticeCellKeepsItsRadiiAndOverlapsLess)
{
  CubeOptions o;
  o.populations = 1;
  o.edgeLength = 20.0;
  o.periodic = true;
  o.volumeFraction = 0.7;
  o.fiberRadius = 1.0;
  o.radiusSpread = 0.5;
  o.radiusDistribution = RadiusDistribution::Gamma;
  o.seeding = CubeSeeding::Lattice;
  o.segmentLength = 2.0;
  o.displacement = 0.0;
  o.seed = 3;
  o.realism.beadingCV = 0.2;
  o.realism.beadingLength = 4.0;
  const FiberModel drawn = generateCube(o);
  o.beadPhasing = true;
  const FiberModel phased = generateCube(o);
  ASSERT_EQ(phased.fibers.size(), drawn.fibers.size());
  for (std::size_t f = 0; f < drawn.fibers.size(); ++f)
  {
    EXPECT_EQ(phased.fibers[f].points, drawn.fibers[f].points);
    std::vector<double> a = drawn.fibers[f].radii, b = phased.fibers[f].radii;
    EXPECT_EQ(b.back(), b.front());
    a.pop_back();
    b.pop_back();
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << "fiber " << f;
  }
  const std::size_t before = fiberpli_test::refPeriodicCount(drawn, o.edgeLength);
  const std::size_t after = fiberpli_test::refPeriodicCount(phased, o.edgeLength);
  EXPECT_LT(after, before);
}
