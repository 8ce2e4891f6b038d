// Holding the solved tortuosity at the target from above too (Solver/TortuosityHold.h): the
// undulation scaling against closed forms, and the hold on a dense interwoven crossing whose plain
// solve ends well above its target, measured with this file's own path lengths and the
// independent periodic overlap count.

#include "Solver/TortuosityHold.h"

#include "PeriodicReference.h"
#include "SolverTestModels.h"
#include "ThreadComm.h"
#include "Tissue/CubeGenerator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

namespace
{
using namespace fiberpli;
using fiberpli_test::bitwiseEqual;
using fiberpli_test::refPeriodicCount;
using fiberpli_test::runRanks;

const double kPi = 3.14159265358979323846;

// Path length over |end − start| (or over |closure|), written out here.
double pathRatio(const Fiber& f, const Vec3* closure = nullptr)
{
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < f.size(); ++i)
  {
    const Vec3 d = f.points[i + 1] - f.points[i];
    length += std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
  }
  const Vec3 c = closure ? *closure : f.points.back() - f.points.front();
  return length / std::sqrt(c.x * c.x + c.y * c.y + c.z * c.z);
}

// y = a·sin(2πx/λ) sampled every h from x = 0 to span (an open fiber).
Fiber sineFiber(double a, double lambda, double span, double h)
{
  Fiber f;
  const int n = static_cast<int>(std::lround(span / h)) + 1;
  for (int i = 0; i < n; ++i)
  {
    const double x = span * i / (n - 1);
    f.points.push_back({ x, a * std::sin(2.0 * kPi * x / lambda), 0.0 });
    f.radii.push_back(0.5);
  }
  return f;
}

TEST(TortuosityHold, ScaleUndulationReachesTheTargetMovingPointsAcrossTheAxisOnly)
{
  // Open sine between fixed ends (whole periods: the chord is the x axis). The scaled fiber is the
  // same sine with amplitude k·a: every y scales by the one factor k, x and z stay.
  const Fiber in = sineFiber(1.5, 8.0, 32.0, 0.25);
  for (double target : { 1.05, 1.2, 1.6 })
  {
    Fiber f = in;
    const double k = scaleUndulation(f, target);
    EXPECT_NEAR(pathRatio(f), target, 1e-9 * target);
    EXPECT_EQ(f.points.front().y, in.points.front().y);
    EXPECT_EQ(f.points.back().x, in.points.back().x);
    for (std::size_t i = 1; i + 1 < f.size(); ++i)
    {
      EXPECT_NEAR(f.points[i].x, in.points[i].x, 1e-12);
      EXPECT_NEAR(f.points[i].y, k * in.points[i].y, 1e-12);
      EXPECT_EQ(f.points[i].z, 0.0);
    }
  }
  // The sine's own tortuosity: k = 1. Asking less than the axis itself has: straight (k = 0).
  Fiber same = in;
  EXPECT_NEAR(scaleUndulation(same, pathRatio(in)), 1.0, 1e-9);
  Fiber flat = in;
  EXPECT_EQ(scaleUndulation(flat, 1.0), 0.0);
  EXPECT_NEAR(pathRatio(flat), 1.0, 1e-12);
  // A straight fiber has nothing to scale.
  Fiber straight = sineFiber(0.0, 8.0, 32.0, 1.0);
  EXPECT_EQ(scaleUndulation(straight, 1.3), 1.0);
  EXPECT_EQ(pathRatio(straight), 1.0);
}

TEST(TortuosityHold, ScaleUndulationKeepsAClosedFiberClosed)
{
  // A helix of radius R and pitch P closed through a cell of edge P along z: tortuosity
  // √(1 + (2πR/P)²), so the target's radius is R' = P·√(τ² − 1)/(2π); its points' mean lies on
  // the axis, so the scaled helix has exactly that radius.
  const double P = 20.0, R = 1.0;
  Fiber f;
  const int n = 161;
  for (int i = 0; i < n; ++i)
  {
    const double s = static_cast<double>(i) / (n - 1);
    f.points.push_back({ 5.0 + R * std::cos(2 * kPi * s), 5.0 + R * std::sin(2 * kPi * s), P * s });
    f.radii.push_back(0.4);
  }
  f.points.back() = f.points.front() + Vec3{ 0.0, 0.0, P };
  const Vec3 closure{ 0.0, 0.0, P };
  const double target = 1.3;
  scaleUndulation(f, target, &closure);
  const Vec3 d = f.points.back() - f.points.front();
  EXPECT_EQ(d.x, 0.0);
  EXPECT_EQ(d.y, 0.0);
  EXPECT_EQ(d.z, P);
  EXPECT_NEAR(pathRatio(f, &closure), target, 1e-9);
  // Polygon of 160 sides: its radius for the target differs from the circle's by under 1e-3.
  const double expected = P * std::sqrt(target * target - 1.0) / (2 * kPi);
  for (std::size_t i = 0; i < f.size(); i += 20)
  {
    EXPECT_NEAR(std::hypot(f.points[i].x - 5.0, f.points[i].y - 5.0), expected, 1e-3 * expected);
  }
}

// A dense interwoven crossing in a (16 µm)³ cell whose fibers are made at tortuosity 1.25: the
// weave of the solve lengthens them well beyond it.
CubeOptions crossing()
{
  CubeOptions c;
  c.populations = 2;
  c.edgeLength = 16.0;
  c.periodic = true;
  c.volumeFraction = 0.55;
  c.fiberRadius = 0.8;
  c.segmentLength = 1.0;
  c.displacement = 0.0;
  c.seed = 5;
  c.arrangement = CubeArrangement::Interwoven;
  c.realism.tortuosity = 1.25;
  c.realism.undulationWavelength = 8.0;
  return c;
}

CollisionSolverOptions holding(const CubeOptions& c)
{
  CollisionSolverOptions o;
  o.periodicCell = cubeCell(c);
  o.maxSteps = 4000;
  o.maxDisplacement = 0.4;
  o.tortuosity = 1.25;
  o.holdTortuosity = true;
  o.numberOfThreads = 1;
  return o;
}

// Mean path ratio over each bundle's fibers (all closed through the cell).
std::map<int, double> bundleMeans(const FiberModel& m, const PeriodicCell& cell)
{
  std::map<int, double> sum;
  std::map<int, int> count;
  for (const Fiber& f : m.fibers)
  {
    Vec3 closure;
    EXPECT_TRUE(isClosedFiber(f, cell, closure));
    sum[f.bundle] += pathRatio(f, &closure);
    count[f.bundle] += 1;
  }
  for (auto& [b, s] : sum)
  {
    s /= count[b];
  }
  return sum;
}

TEST(TortuosityHold, ACrossingSolvesAtTheTortuosityAskedInsteadOfAskedPlusItsWeave)
{
  const CubeOptions c = crossing();
  ASSERT_EQ(validateCubeOptions(c, 1), "");
  const FiberModel in = generateCube(c);
  const CollisionSolverOptions o = holding(c);
  const double tolerance = kTortuosityHoldTolerance * (o.tortuosity - 1.0);

  // Without the hold the weave comes on top of the undulation asked: beyond 10 % of the excess.
  FiberModel plain = in;
  CollisionSolverOptions once = o;
  once.holdTortuosity = false;
  const CollisionSolverResult p = solveCollisions(plain, once);
  ASSERT_EQ(p.error, "");
  ASSERT_TRUE(p.solved);
  for (const auto& [b, mean] : bundleMeans(plain, o.periodicCell))
  {
    EXPECT_GT(mean, o.tortuosity + 2.0 * tolerance) << "bundle " << b;
  }

  FiberModel held = in;
  const CollisionSolverResult r = solveHoldingTortuosity(held, o);
  ASSERT_EQ(r.error, "");
  EXPECT_TRUE(r.solved);
  EXPECT_GE(r.tortuositySolves, 2);
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
  EXPECT_EQ(refPeriodicCount(held, c.edgeLength), 0u);
  const std::map<int, double> means = bundleMeans(held, o.periodicCell);
  ASSERT_EQ(means.size(), 2u);
  for (const auto& [b, mean] : means)
  {
    EXPECT_NEAR(mean, o.tortuosity, tolerance) << "bundle " << b;
  }
  ASSERT_EQ(held.fibers.size(), in.fibers.size());
  for (std::size_t f = 0; f < held.fibers.size(); ++f)
  {
    EXPECT_EQ(held.fibers[f].id, in.fibers[f].id);
    EXPECT_EQ(held.fibers[f].radii.front(), plain.fibers[f].radii.front());
  }
}

TEST(TortuosityHold, SameBitsForAnyThreadAndRankCount)
{
  const CubeOptions c = crossing();
  const FiberModel in = generateCube(c);
  CollisionSolverOptions o = holding(c);
  FiberModel serial = in;
  const CollisionSolverResult s = solveHoldingTortuosity(serial, o);
  ASSERT_EQ(s.error, "");
  ASSERT_GE(s.tortuositySolves, 2);
  o.numberOfThreads = 2;
  FiberModel threads = in;
  EXPECT_EQ(solveHoldingTortuosity(threads, o).steps, s.steps);
  EXPECT_TRUE(bitwiseEqual(threads, serial));
  for (int ranks : { 2, 3 })
  {
    // Pieces of consecutive fibers, in rank order.
    std::vector<FiberModel> pieces(static_cast<std::size_t>(ranks));
    for (std::size_t f = 0; f < in.fibers.size(); ++f)
    {
      pieces[f * static_cast<std::size_t>(ranks) / in.fibers.size()].fibers.push_back(in.fibers[f]);
    }
    std::vector<CollisionSolverResult> results(static_cast<std::size_t>(ranks));
    runRanks(ranks,
      [&](Comm& comm)
      {
        const std::size_t r = static_cast<std::size_t>(comm.rank());
        results[r] = solveHoldingTortuosity(pieces[r], o, {}, &comm);
      });
    FiberModel joined;
    for (std::size_t r = 0; r < pieces.size(); ++r)
    {
      EXPECT_EQ(results[r].error, "");
      EXPECT_EQ(results[r].steps, s.steps) << ranks << " ranks";
      EXPECT_EQ(results[r].tortuositySolves, s.tortuositySolves) << ranks << " ranks";
      for (const Fiber& f : pieces[r].fibers)
      {
        joined.fibers.push_back(f);
      }
    }
    EXPECT_TRUE(bitwiseEqual(joined, serial)) << ranks << " ranks";
  }
}

TEST(TortuosityHold, NeedsATortuosityToHold)
{
  const CubeOptions c = crossing();
  const FiberModel in = generateCube(c);
  CollisionSolverOptions o = holding(c);
  o.tortuosity = 0.0;
  FiberModel m = in;
  const CollisionSolverResult r = solveHoldingTortuosity(m, o);
  EXPECT_NE(r.error.find("Tortuosity"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("HoldTortuosity"), std::string::npos) << r.error;
  EXPECT_TRUE(bitwiseEqual(m, in));
  EXPECT_EQ(validateCollisionSolverOptions(o), r.error);
}

} // namespace
