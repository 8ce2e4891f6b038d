// Polydisperse disk packing (Tissue/DiskPacking): every packing checked against a brute-force
// pair scan over the minimum image written here, for periodic squares and walled strips.
#include "Tissue/DiskPacking.h"
#include "Tissue/RadiusDistribution.h"
#include "Util/Random.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace fiberpli;

namespace
{
// Gamma radii (mean 1, spread 0.5, as MEDUSA's α 4, β 0.25 µm) until their area reaches phi of
// the domain.
std::vector<double> gammaRadii(double area, double phi, std::uint64_t seed)
{
  std::vector<double> r;
  double covered = 0.0;
  for (std::uint64_t j = 0; covered < phi * area; ++j)
  {
    RandomStream rng(seed, 0, j);
    r.push_back(drawFiberRadius(rng, 1.0, 0.5, RadiusDistribution::Gamma, 100.0));
    covered += M_PI * r.back() * r.back();
  }
  return r;
}

double wrapped(double d, double period)
{
  return d - period * std::round(d / period);
}

// min over pairs of distance / (r_i + r_j) (minimum image along the periodic axes) and over walls
// of the room / r_i: the scale of DiskPacking, by brute force.
double bruteScale(const std::vector<double>& r, const std::vector<Seed2D>& c, const DiskDomain& d)
{
  double s = HUGE_VAL;
  for (std::size_t i = 0; i < r.size(); ++i)
  {
    if (!d.periodicHeight)
      s = std::min(s, std::min(c[i].y, d.height - c[i].y) / r[i]);
    for (std::size_t j = i + 1; j < r.size(); ++j)
    {
      const double dx = wrapped(c[j].x - c[i].x, d.width);
      const double dy = d.periodicHeight ? wrapped(c[j].y - c[i].y, d.height) : c[j].y - c[i].y;
      s = std::min(s, std::hypot(dx, dy) / (r[i] + r[j]));
    }
  }
  return s;
}
} // namespace

TEST(DiskPacking, GammaRadiiPackAboveTheRandomClosePackingInAPeriodicSquare)
{
  // 0.85 is above the 2-D random close packing of such disks (~0.84–0.86); swaps get past it.
  const DiskDomain square{ 20.0, 20.0, true };
  const std::vector<double> r = gammaRadii(400.0, 0.85, 3);
  const DiskPacking p = packDisks(r, square, 9, 1);
  ASSERT_EQ(p.centres.size(), r.size());
  for (const Seed2D& c : p.centres)
  {
    EXPECT_GE(c.x, 0.0);
    EXPECT_LT(c.x, square.width);
    EXPECT_GE(c.y, 0.0);
    EXPECT_LT(c.y, square.height);
  }
  const double brute = bruteScale(r, p.centres, square);
  EXPECT_GT(brute, 1.005) << "no overlap, with a gap of at least 0.5 % of the two radii";
  EXPECT_NEAR(p.scale, std::min(brute, 1.1), 1e-12);
}

TEST(DiskPacking, WalledStripKeepsEveryDiskBetweenTheWalls)
{
  const DiskDomain strip{ 24.0, 9.0, false };
  const std::vector<double> r = gammaRadii(24.0 * 9.0, 0.78, 5);
  const DiskPacking p = packDisks(r, strip, 2, 4);
  const double brute = bruteScale(r, p.centres, strip);
  EXPECT_GE(brute, 1.0);
  EXPECT_NEAR(p.scale, std::min(brute, 1.1), 1e-12);
  for (std::size_t i = 0; i < r.size(); ++i)
  {
    EXPECT_GE(p.centres[i].y - r[i], 0.0) << i;
    EXPECT_LE(p.centres[i].y + r[i], strip.height) << i;
  }
}

TEST(DiskPacking, DeterministicForTheStreamAndOtherStreamsDiffer)
{
  const DiskDomain square{ 12.0, 12.0, true };
  const std::vector<double> r = gammaRadii(144.0, 0.7, 8);
  const DiskPacking a = packDisks(r, square, 4, 6), b = packDisks(r, square, 4, 6),
                    c = packDisks(r, square, 4, 7);
  ASSERT_EQ(a.centres.size(), b.centres.size());
  bool differs = false;
  for (std::size_t i = 0; i < r.size(); ++i)
  {
    EXPECT_EQ(a.centres[i].x, b.centres[i].x);
    EXPECT_EQ(a.centres[i].y, b.centres[i].y);
    differs = differs || a.centres[i].x != c.centres[i].x;
  }
  EXPECT_TRUE(differs);
}

TEST(DiskPacking, InfeasibleDensityReportsTheOverlapItLeaves)
{
  // Equal disks at 0.95 > the hexagonal 0.907: they cannot be separated.
  const DiskDomain square{ 10.0, 10.0, true };
  const double r0 = std::sqrt(0.95 * 100.0 / (M_PI * 30.0));
  const std::vector<double> r(30, r0);
  const DiskPacking p = packDisks(r, square, 1, 1);
  EXPECT_LT(p.scale, 1.0);
  EXPECT_GT(p.scale, 0.9);
  EXPECT_NEAR(p.scale, bruteScale(r, p.centres, square), 1e-12);
}

TEST(DiskPacking, EmptyInputGivesAnEmptyPacking)
{
  EXPECT_TRUE(packDisks({}, DiskDomain{ 10.0, 10.0, true }, 1, 1).centres.empty());
  EXPECT_TRUE(packDisks({ 1.0 }, DiskDomain{ 0.0, 10.0, true }, 1, 1).centres.empty());
}

TEST(DiskPacking, RadiiThatAreNotFiniteAndPositiveGiveAnEmptyPacking)
{
  const DiskDomain square{ 10.0, 10.0, true };
  for (const double bad : { std::nan(""), HUGE_VAL, 0.0, -1.0 })
  {
    const DiskPacking p = packDisks({ 1.0, bad }, square, 1, 1);
    EXPECT_TRUE(p.centres.empty()) << bad;
    EXPECT_EQ(p.scale, 0.0) << bad;
  }
  EXPECT_TRUE(packDisks({ 1.0 }, DiskDomain{ HUGE_VAL, 10.0, true }, 1, 1).centres.empty());
}

TEST(DiskPacking, FewDisksInAHugeDomainUseAGridBoundedByTheDiskCount)
{
  // A grid of cells of 2 r̄ would have 2.5·10⁹ cells here (std::bad_alloc); bounded by the count it
  // has a few. Two disks of radius 1 and 1.5 in (10⁵)² are far apart: the scale is the cap 1.1.
  const std::vector<double> r{ 1.0, 1.5 };
  const DiskDomain square{ 1e5, 1e5, true };
  const DiskPacking p = packDisks(r, square, 1, 1);
  ASSERT_EQ(p.centres.size(), 2u);
  EXPECT_GE(bruteScale(r, p.centres, square), 1.0) << "no overlap";
  EXPECT_EQ(p.scale, std::min(1.1, bruteScale(r, p.centres, square)));
  // A walled slab 4 high and 10⁵ wide (a grid along its width only).
  const DiskDomain slab{ 1e5, 4.0, false };
  const DiskPacking q = packDisks(r, slab, 1, 1);
  ASSERT_EQ(q.centres.size(), 2u);
  EXPECT_GE(bruteScale(r, q.centres, slab), 1.0);
  EXPECT_GE(q.scale, 1.0);
  EXPECT_LT(diskPackingBytes(2.0), 4096.0);
}

TEST(DiskPacking, ProgressRisesAndAStopReturnsAnAbortedEmptyPacking)
{
  const DiskDomain square{ 30.0, 30.0, true };
  const std::vector<double> r = gammaRadii(900.0, 0.85, 42);
  std::vector<double> seen;
  const DiskPacking whole = packDisks(r, square, 42, 6,
    [&](double f)
    {
      seen.push_back(f);
      return true;
    });
  ASSERT_FALSE(seen.empty());
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_GE(seen.front(), 0.0);
  EXPECT_LE(seen.back(), 1.0);
  EXPECT_FALSE(whole.aborted);
  // A callback that only watches changes nothing.
  const DiskPacking plain = packDisks(r, square, 42, 6);
  ASSERT_EQ(plain.centres.size(), whole.centres.size());
  for (std::size_t i = 0; i < plain.centres.size(); ++i)
    EXPECT_TRUE(
      plain.centres[i].x == whole.centres[i].x && plain.centres[i].y == whole.centres[i].y)
      << i;
  EXPECT_EQ(plain.scale, whole.scale);
  int calls = 0;
  const DiskPacking stopped = packDisks(r, square, 42, 6, [&](double) { return ++calls < 3; });
  EXPECT_EQ(calls, 3);
  EXPECT_TRUE(stopped.aborted);
  EXPECT_TRUE(stopped.centres.empty());
  EXPECT_EQ(stopped.scale, 0.0);
}
