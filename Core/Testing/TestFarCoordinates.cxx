// Fibers far from the origin (docs/solver.md §5.1): at |x| ~ 3e16 µm neighbouring doubles are
// 4 µm apart, so the midpoint of a 2 µm link rounds to one of its ends and split/merge used to
// split it forever (even with MaxSteps 0), and a distributed run with such a piece on one rank
// hung. Such input is refused up front by one rule, every rank reports it, and the split of one
// fiber ends on its own.
#include "Solver/CollisionSolver.h"
#include "Solver/ShapeControl.h"
#include "ThreadComm.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <future>
#include <memory>
#include <thread>

using namespace fiberpli;

namespace
{
// Two crossing fibers with 2 µm links, shifted by `offset` along x.
FiberModel crossingPair(double offset)
{
  FiberModel m;
  Fiber a, b;
  for (int k = 0; k < 5; ++k)
  {
    a.points.push_back({ offset + 2.0 * k, 0.0, 0.0 });
    b.points.push_back({ offset + 4.3, -4.0 + 2.0 * k, 0.5 });
  }
  a.radii.assign(5, 1.0);
  b.radii.assign(5, 1.0);
  a.id = 0;
  b.id = 1;
  m.fibers = { a, b };
  return m;
}

// Runs f on its own thread; a hang ends the test program with a message instead of blocking ctest.
void withinSeconds(int seconds, const std::function<void()>& f)
{
  auto done = std::make_shared<std::promise<void>>();
  std::future<void> finished = done->get_future();
  std::thread(
    [f, done]
    {
      f();
      done->set_value();
    })
    .detach();
  if (finished.wait_for(std::chrono::seconds(seconds)) != std::future_status::ready)
  {
    std::fprintf(stderr, "FAILED: not finished within %d s (hang)\n", seconds);
    std::_Exit(1);
  }
}
} // namespace

TEST(FarCoordinates, SplittingALinkDoublePrecisionCannotHalveEnds)
{
  // Points 8 µm apart at x = 3e16 (2 doubles apart): one split is exact (x + 4), after that the
  // midpoints round to the ends; the pass must end with the links it can make.
  Fiber f;
  f.points = { { 3e16, 0, 0 }, { 3e16 + 8.0, 0, 0 } };
  f.radii = { 1, 1 };
  FiberPointState st;
  st.velocity.assign(2, Vec3{});
  st.source = { 0, 1 };
  bool changed = false;
  withinSeconds(20, [&] { changed = controlSegmentLength(f, st, 2.0); });
  EXPECT_TRUE(changed);
  EXPECT_EQ(f.points.size(), 3u);
  EXPECT_EQ(f.points[1].x, 3e16 + 4.0);
  EXPECT_EQ(st.source.size(), 3u);
}

TEST(FarCoordinates, FarInputIsRefusedNamingFiberAndValue)
{
  FiberModel m = crossingPair(3e16);
  const FiberModel in = m;
  CollisionSolverOptions o;
  o.maxSteps = 0;
  o.numberOfThreads = 1;
  const CollisionSolverResult r = solveCollisions(m, o);
  EXPECT_NE(r.error.find("fiber 0 (fiber_id 0) point 0 has coordinate 3e+16"), std::string::npos)
    << r.error;
  EXPECT_NE(r.error.find("SegmentLength"), std::string::npos) << r.error;
  EXPECT_EQ(m.fibers[0].points, in.fibers[0].points);
  EXPECT_EQ(checkCoordinateResolution(m, 2.0).empty(), false);
  EXPECT_EQ(checkCoordinateResolution(m, -1.0), "") << "without split/merge nothing is split";
  // Just inside the limit the same fibers solve.
  FiberModel near = crossingPair(kMaxCoordinateOverSegment * 2.0 * 0.5);
  o.maxSteps = 50;
  const CollisionSolverResult ok = solveCollisions(near, o);
  EXPECT_EQ(ok.error, "");
}

TEST(FarCoordinates, AFarPieceOnOneRankFailsEveryRankWithoutHanging)
{
  std::vector<std::string> errors(2);
  withinSeconds(60,
    [&errors]
    {
      fiberpli_test::runRanks(2,
        [&errors](Comm& comm)
        {
          FiberModel piece = crossingPair(comm.rank() == 1 ? 3e16 : 0.0);
          for (Fiber& f : piece.fibers)
          {
            f.id += 2 * comm.rank();
          }
          CollisionSolverOptions o;
          o.maxSteps = 20;
          o.numberOfThreads = 1;
          errors[static_cast<std::size_t>(comm.rank())] =
            solveCollisions(piece, o, {}, {}, &comm).error;
        });
    });
  for (const std::string& e : errors)
  {
    EXPECT_NE(e.find("coordinate 3e+16"), std::string::npos) << e;
  }
}
