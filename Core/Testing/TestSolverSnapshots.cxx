// SolverSnapshots: which solver steps IterationsAsTime keeps, worked out by hand from the rule
// (keep every Δ-th step; when full, drop every second state and double Δ).
#include "Solver/SolverSnapshots.h"

#include <gtest/gtest.h>

using namespace fiberpli;

namespace
{
// A one-fiber model that says which step it is (its first point's x).
FiberModel modelAt(int step)
{
  FiberModel m;
  Fiber f;
  f.points = { Vec3{ static_cast<double>(step), 0.0, 0.0 },
    Vec3{ static_cast<double>(step), 0.0, 1.0 } };
  f.radii = { 1.0, 1.0 };
  m.fibers.push_back(f);
  return m;
}

void expectStates(const SolverSnapshots& s, const std::vector<int>& steps)
{
  ASSERT_EQ(s.steps, steps);
  ASSERT_EQ(s.models.size(), steps.size());
  for (std::size_t i = 0; i < steps.size(); ++i)
  {
    EXPECT_EQ(s.models[i].fibers[0].points[0].x, steps[i]) << i;
  }
}
} // namespace

TEST(SolverSnapshots, ThinsToEvenlySpacedStepsWhenFull)
{
  SolverSnapshots s;
  s.start(modelAt(0), 1, 4);
  // Capacity 4, Δ 1: steps 1–3 fill it; step 4 thins to 0, 2 and Δ 2 (then 4 is kept); step 6
  // fills it again; step 8 thins to 0, 4 and Δ 4 (then 8 is kept); 9 is no multiple of 4.
  for (int step = 1; step <= 9; ++step)
  {
    s.observe(step, modelAt(step));
  }
  expectStates(s, { 0, 4, 8 });
  EXPECT_EQ(s.interval(), 4);
  s.finish(modelAt(9), 9);
  expectStates(s, { 0, 4, 8, 9 });
}

TEST(SolverSnapshots, FinalStateReplacesTheSnapshotOfItsStep)
{
  SolverSnapshots s;
  s.start(modelAt(0), 5, 100);
  for (int step = 1; step <= 10; ++step)
  {
    s.observe(step, modelAt(step));
  }
  expectStates(s, { 0, 5, 10 });
  FiberModel final = modelAt(10);
  final.fibers[0].points[1].z = 2.0; // after the last shape control: not the snapshot
  s.finish(std::move(final), 10);
  expectStates(s, { 0, 5, 10 });
  EXPECT_EQ(s.models.back().fibers[0].points[1].z, 2.0);
}

TEST(SolverSnapshots, WithoutStartTheFinalStateIsTheOnlyOne)
{
  SolverSnapshots s;
  s.finish(modelAt(7), 7);
  expectStates(s, { 7 });
  EXPECT_EQ(s.atTime(0.0), 0u);
  EXPECT_EQ(s.atTime(100.0), 0u);
}

TEST(SolverSnapshots, TimeSelectsTheLastStateAtOrBefore)
{
  SolverSnapshots s;
  s.start(modelAt(0), 4, 10);
  for (int step = 1; step <= 12; ++step)
  {
    s.observe(step, modelAt(step));
  }
  s.finish(modelAt(13), 13); // steps 0, 4, 8, 12, 13
  EXPECT_EQ(s.atTime(-1.0), 0u);
  EXPECT_EQ(s.atTime(0.0), 0u);
  EXPECT_EQ(s.atTime(3.9), 0u);
  EXPECT_EQ(s.atTime(4.0), 1u);
  EXPECT_EQ(s.atTime(11.0), 2u);
  EXPECT_EQ(s.atTime(12.5), 3u);
  EXPECT_EQ(s.atTime(1e9), 4u);
}
