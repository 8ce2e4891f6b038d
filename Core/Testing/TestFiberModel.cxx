// Data contract checks of the Core fiber model (docs/data-contract.md §3).
#include "Model/FiberModel.h"
#include "Util/Random.h"

#include <gtest/gtest.h>

#include <limits>

using namespace fiberpli;

namespace
{
Fiber straightFiber(std::int64_t id, int n)
{
  Fiber f;
  f.id = id;
  for (int i = 0; i < n; ++i)
  {
    f.points.push_back({ static_cast<double>(i), 0.0, 0.0 });
    f.radii.push_back(0.5 + 0.1 * i);
  }
  return f;
}
} // namespace

TEST(FiberModel, CountsPointsAndLinks)
{
  FiberModel m;
  m.fibers = { straightFiber(0, 3), straightFiber(1, 5) };
  EXPECT_EQ(m.numberOfPoints(), 8u);
  EXPECT_EQ(m.numberOfLinks(), 6u);
  EXPECT_DOUBLE_EQ(m.fibers[1].linkRadius(2), 0.5 + 0.1 * 3);
}

TEST(FiberModel, BoundsIncludeRadiiOnRequest)
{
  FiberModel m;
  m.fibers = { straightFiber(0, 3) };
  Vec3 lo, hi;
  ASSERT_TRUE(modelBounds(m, false, lo, hi));
  EXPECT_EQ(lo.x, 0.0);
  EXPECT_EQ(hi.x, 2.0);
  ASSERT_TRUE(modelBounds(m, true, lo, hi));
  EXPECT_DOUBLE_EQ(lo.x, -0.5);
  EXPECT_DOUBLE_EQ(hi.x, 2.7);
  EXPECT_DOUBLE_EQ(hi.y, 0.7);
  EXPECT_FALSE(modelBounds(FiberModel{}, true, lo, hi));
}

TEST(FiberModel, ValidationNamesTheFiberAndPoint)
{
  FiberModel m;
  m.fibers = { straightFiber(10, 3), straightFiber(11, 3) };
  EXPECT_TRUE(validateModel(m).empty());

  m.fibers[1].radii[2] = 0.0;
  std::string msg = validateModel(m);
  EXPECT_NE(msg.find("fiber 1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("fiber_id 11"), std::string::npos) << msg;
  EXPECT_NE(msg.find("point 2"), std::string::npos) << msg;

  m.fibers[1].radii[2] = 1.0;
  m.fibers[0].points[1].y = std::numeric_limits<double>::quiet_NaN();
  msg = validateModel(m);
  EXPECT_NE(msg.find("fiber 0"), std::string::npos) << msg;
  EXPECT_NE(msg.find("non-finite"), std::string::npos) << msg;

  m.fibers[0] = straightFiber(10, 1);
  EXPECT_NE(validateModel(m).find("fewer than 2"), std::string::npos);
}

TEST(FiberModel, ShortFibersCanBeAllowedButTheOtherRulesStay)
{
  FiberModel m;
  m.fibers = { straightFiber(10, 3), straightFiber(11, 1), Fiber{} };
  std::size_t bad = 99;
  EXPECT_NE(validateModel(m, &bad).find("fewer than 2"), std::string::npos);
  EXPECT_EQ(bad, 1u);
  EXPECT_TRUE(validateModel(m, nullptr, ShortFibers::Allowed).empty());
  m.fibers[1].radii[0] = -1.0; // a short fiber still needs valid radii
  const std::string msg = validateModel(m, &bad, ShortFibers::Allowed);
  EXPECT_NE(msg.find("fiber 1"), std::string::npos) << msg;
  EXPECT_NE(msg.find("radius"), std::string::npos) << msg;
  m.fibers[1].radii.clear();
  EXPECT_NE(validateModel(m, nullptr, ShortFibers::Allowed).find("radii"), std::string::npos);
}

TEST(Random, StreamsAreKeyedAndUniform)
{
  RandomStream a(1, 2, 3), b(1, 2, 3), c(1, 2, 4);
  EXPECT_EQ(a.next(), b.next());
  EXPECT_NE(b.next(), c.next());
  RandomStream r(5);
  double sum = 0.0, sumSq = 0.0;
  const int n = 100000;
  for (int i = 0; i < n; ++i)
  {
    const double z = r.normal();
    sum += z;
    sumSq += z * z;
  }
  EXPECT_NEAR(sum / n, 0.0, 0.02);
  EXPECT_NEAR(sumSq / n, 1.0, 0.02);
}
