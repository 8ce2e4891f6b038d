// BeadProfile (docs/solver.md §5.4): a beaded closed fiber's radius as a function of arc length.
// Checked against what is known without the rule: a fiber slid along itself as a whole keeps its
// radii; a bead whose points were squeezed together keeps its length along the fiber (its excess
// volume ∫(r² − r₀²) ds, integrated here independently); the phase wraps through the closure; open
// fibers and constant radii are left alone. The solver with the rule: a dense beaded periodic cell
// solves with zero overlaps by an own periodic checker, keeps its beads' volume better than
// without the rule, and is bit for bit the same on 1 and 3 threads.
#include "PeriodicReference.h"
#include "Solver/BeadProfile.h"
#include "Solver/CollisionSolver.h"
#include "SolverTestModels.h"
#include "Tissue/Beading.h"
#include "Tissue/CubeGenerator.h"

#include <cmath>

#include <gtest/gtest.h>

using namespace fiberpli;

namespace
{
constexpr double kPi = 3.14159265358979323846;

// A fiber closed along z through a cell of edge 40: 21 points 2 µm apart (the last the first +
// (0, 0, 40)), radius 1 + 0.5·exp(−((s − 10)/2)²) at input index s (one bead of about 4 points'
// width around point 10), and its solver state as prepared for a run (source index = i).
struct BeadedFiber
{
  Fiber f;
  FiberPointState st;
  Vec3 closure{ 0.0, 0.0, 40.0 };
};

double bead(double s)
{
  return 1.0 + 0.5 * std::exp(-(s - 10.0) * (s - 10.0) / 4.0);
}

BeadedFiber beadedFiber()
{
  BeadedFiber b;
  for (int i = 0; i <= 20; ++i)
  {
    b.f.points.push_back(Vec3{ 3.0, -2.0, 2.0 * i });
    b.f.radii.push_back(i == 20 ? bead(0.0) : bead(i));
    b.st.source.push_back(static_cast<double>(i));
  }
  b.st.inputRadii = b.f.radii;
  b.st.velocity.assign(b.f.size(), Vec3{});
  return b;
}

// ∫(r² − 1) ds along the fiber, r linear between points, by a fine midpoint sum over every link
// (the bead's excess volume over π; independent of the rule's own arithmetic).
double excessVolume(const Fiber& f)
{
  double sum = 0.0;
  for (std::size_t k = 0; k + 1 < f.size(); ++k)
  {
    const double l = distance(f.points[k], f.points[k + 1]);
    for (int q = 0; q < 100; ++q)
    {
      const double t = (q + 0.5) / 100.0;
      const double r = (1.0 - t) * f.radii[k] + t * f.radii[k + 1];
      sum += (r * r - 1.0) * l / 100.0;
    }
  }
  return sum;
}
} // namespace

TEST(BeadProfile, PeriodicProfileWrapsThroughTheClosure)
{
  const std::vector<double> p{ 1.0, 2.0, 3.0, 1.0 }; // period 3
  EXPECT_DOUBLE_EQ(periodicProfileRadius(p, 0.5), 1.5);
  EXPECT_DOUBLE_EQ(periodicProfileRadius(p, 3.5), 1.5);
  EXPECT_DOUBLE_EQ(periodicProfileRadius(p, -0.5), 2.0); // 2.5: between 3 and 1
  EXPECT_DOUBLE_EQ(periodicProfileRadius(p, 2.75), 1.5);
}

TEST(BeadProfile, AFiberSlidAsAWholeKeepsItsRadii)
{
  // Every point slid by 0.7 µm along the fiber: the arc fractions are unchanged, the beads move
  // with the points, nothing changes.
  BeadedFiber b = beadedFiber();
  for (Vec3& p : b.f.points)
    p.z += 0.7;
  const std::vector<double> before = b.f.radii;
  EXPECT_FALSE(followBeadProfile(b.f, b.st));
  EXPECT_EQ(b.f.radii, before);
  for (int i = 0; i < 20; ++i)
    EXPECT_NEAR(b.st.source[static_cast<std::size_t>(i)], i, 1e-12);
}

TEST(BeadProfile, ASqueezedBeadKeepsItsLengthAlongTheFiber)
{
  // Points 7..13 pushed towards point 10 to half their spacing (the bead now lies in links half
  // as long), the links beside them stretched: carried radii lose half the bead's excess volume;
  // the rule puts the bead back onto its original length of arc.
  BeadedFiber b = beadedFiber();
  const double full = excessVolume(b.f);
  for (int i = 7; i <= 13; ++i)
    b.f.points[static_cast<std::size_t>(i)].z = 20.0 + (2.0 * i - 20.0) * 0.5;
  const double squeezed = excessVolume(b.f);
  EXPECT_LT(squeezed, 0.7 * full); // what the pushes did to the bead without the rule
  EXPECT_TRUE(followBeadProfile(b.f, b.st));
  EXPECT_NEAR(excessVolume(b.f), full, 0.12 * full);
  // Symmetric squeeze: no phase, the thickest point is still point 10 with the bead's peak.
  EXPECT_NEAR(b.st.source[10], 10.0, 1e-9);
  EXPECT_DOUBLE_EQ(b.f.radii[10], 1.5);
  EXPECT_EQ(b.f.radii.back(), b.f.radii.front());
}

TEST(BeadProfile, ThePhaseFollowsTheMeanSlideThroughTheClosure)
{
  // Every source index set 1.5 behind its arc fraction and shifted across the seam: the phase is
  // −1.5 (mod 20), each point's index wraps into [0, 20) and its radius is the profile there.
  BeadedFiber b = beadedFiber();
  for (int i = 0; i <= 20; ++i)
    b.st.source[static_cast<std::size_t>(i)] = std::fmod(i - 1.5 + 20.0, 20.0);
  followBeadProfile(b.f, b.st);
  for (int i = 0; i < 20; ++i)
  {
    const double s = std::fmod(i - 1.5 + 20.0, 20.0);
    EXPECT_NEAR(b.st.source[static_cast<std::size_t>(i)], s, 1e-9);
    EXPECT_GE(b.st.source[static_cast<std::size_t>(i)], 0.0);
    EXPECT_LT(b.st.source[static_cast<std::size_t>(i)], 20.0);
    const double lo = std::floor(s), t = s - lo; // linear between input points, by hand
    EXPECT_NEAR(b.f.radii[static_cast<std::size_t>(i)],
      (1.0 - t) * bead(lo) + t * bead(std::fmod(lo + 1.0, 20.0)),
      2e-9); // a radius moves by > 1e-9 of itself
  }
  EXPECT_EQ(b.f.radii.back(), b.f.radii.front());
  EXPECT_EQ(b.st.source.back(), b.st.source.front());
}

TEST(BeadProfile, ConstantRadiiAndShortFibersAreLeftAlone)
{
  BeadedFiber b = beadedFiber();
  b.st.inputRadii.assign(b.f.size(), 1.0);
  b.f.radii.assign(b.f.size(), 1.0);
  b.f.points[5].z += 0.9;
  const std::vector<double> src = b.st.source;
  EXPECT_FALSE(followBeadProfile(b.f, b.st));
  EXPECT_EQ(b.st.source, src);
}

namespace
{
// A dense beaded periodic cell: (14 µm)³, Gamma-like spread radii, undulating and beaded.
CubeOptions beadedCell()
{
  CubeOptions c = fiberpli_test::periodicCube(1, 14.0, 0.62, 5);
  c.fiberRadius = 1.0;
  c.displacement = 0.0;
  c.realism.tortuosity = 1.03;
  c.realism.undulationWavelength = 7.0;
  c.realism.beadingCV = 0.2;
  c.realism.beadingLength = 3.0;
  return c;
}

// Σ π ρ² l over the links (ρ the larger radius of the link's points), the solver's own count.
double capsuleVolume(const FiberModel& m)
{
  double v = 0.0;
  for (const Fiber& f : m.fibers)
    for (std::size_t k = 0; k + 1 < f.size(); ++k)
    {
      const double rho = std::max(f.radii[k], f.radii[k + 1]);
      v += kPi * rho * rho * distance(f.points[k], f.points[k + 1]);
    }
  return v;
}
} // namespace

TEST(BeadProfile, ADenseBeadedCellSolvesWithoutOverlapsAndKeepsItsBeads)
{
  const CubeOptions c = beadedCell();
  const FiberModel in = generateCube(c);
  CollisionSolverOptions o;
  o.periodicCell = cubeCell(c);
  o.tortuosity = 1.03;
  o.maxDisplacement = 0.4;
  o.maxSteps = 4000;
  o.numberOfThreads = 1;
  FiberModel carried = in;
  const CollisionSolverResult rc = solveCollisions(carried, o);
  o.keepBeads = true;
  FiberModel kept = in;
  const CollisionSolverResult rk = solveCollisions(kept, o);
  ASSERT_TRUE(rk.error.empty()) << rk.error;
  EXPECT_TRUE(rk.solved);
  EXPECT_EQ(fiberpli_test::refPeriodicCount(kept, c.edgeLength), 0u);
  // Every fiber's point radii keep the requested variation (the profile resampled along the arc).
  for (std::size_t f = 0; f < kept.fibers.size(); ++f)
    EXPECT_NEAR(coefficientOfVariation(kept.fibers[f].radii, true), 0.2, 0.04) << "fiber " << f;
  // The beads' volume: kept within 2 % with the rule, closer than the carried radii keep it.
  const double v0 = capsuleVolume(in);
  EXPECT_NEAR(capsuleVolume(kept), v0, 0.02 * v0);
  EXPECT_LT(std::fabs(capsuleVolume(kept) - v0), std::fabs(capsuleVolume(carried) - v0));
  (void)rc;
  // The same result on 3 threads, bit for bit.
  o.numberOfThreads = 3;
  FiberModel kept3 = in;
  const CollisionSolverResult r3 = solveCollisions(kept3, o);
  EXPECT_EQ(r3.steps, rk.steps);
  EXPECT_TRUE(fiberpli_test::bitwiseEqual(kept3, kept));
}
