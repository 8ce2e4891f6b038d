// FiberOrientationGroundTruth's memory: 2500² pixels used to be killed, since every pixel
// carried a 162-bin histogram that the filter never outputs. Histograms are now opt-in and the
// whole estimate is checked against the memory budget before anything is allocated.
#include "MemoryLimitGuard.h"

#include "Analysis/GroundTruth.h"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace fiberpli;

namespace
{

FiberModel diagonalFiber(double length)
{
  FiberModel m;
  Fiber f;
  f.points = { { 0, 0, 0.5 }, { length, length, 0.5 } };
  f.radii = { 3.0, 3.0 };
  m.fibers.push_back(f);
  return m;
}

double peakRssBytes()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return 1024.0 * static_cast<double>(u.ru_maxrss);
}

} // namespace

TEST(GroundTruthMemory, HistogramsOnlyWhenAsked)
{
  const PixelGrid lat = latticeForPixelGrid({ 0, 0, 0 }, 1.0, 8, 8, 0.0, 1.0, 1);
  GroundTruthMaps maps;
  GroundTruthOptions o;
  o.threads = 1;
  ASSERT_EQ(computeGroundTruth(diagonalFiber(8), lat, o, GridRange{ 0, 8, 0, 8 }, maps).error, "");
  EXPECT_TRUE(maps.histogram.empty());
  EXPECT_EQ(maps.fraction.size(), 64u);
  o.histogram = true;
  ASSERT_EQ(computeGroundTruth(diagonalFiber(8), lat, o, GridRange{ 0, 8, 0, 8 }, maps).error, "");
  EXPECT_EQ(maps.histogram.size(), 64u * 18u * 9u);
}

TEST(GroundTruthMemory, SizeFollowsTheMemoryBudget)
{
  fiberpli::testing::MemoryLimitGuard limit("1M");
  const PixelGrid lat = latticeForPixelGrid({ 0, 0, 0 }, 1.0, 500, 500, 0.0, 1.0, 1);
  GroundTruthMaps maps;
  GroundTruthOptions o;
  o.threads = 1;
  const std::string err =
    computeGroundTruth(diagonalFiber(10), lat, o, GridRange{ 0, 500, 0, 500 }, maps).error;
  EXPECT_NE(err.find("500 x 500 pixels"), std::string::npos) << err;
  EXPECT_NE(err.find("memory budget"), std::string::npos) << err;
  EXPECT_TRUE(maps.fraction.empty()) << "allocated before the check";
}

// 1500² pixels: five maps are 90 MB; with the old histograms they were 2.9 GB more. The peak RSS
// of a child process doing only this stays far below the old cost.
TEST(GroundTruthMemory, LargeGridInBoundedMemory)
{
  const pid_t pid = fork();
  if (pid == 0)
  {
    const double before = peakRssBytes();
    const PixelGrid lat = latticeForPixelGrid({ 0, 0, 0 }, 1.0, 1500, 1500, 0.0, 1.0, 1);
    GroundTruthMaps maps;
    GroundTruthOptions o;
    o.threads = 1;
    const std::string err =
      computeGroundTruth(diagonalFiber(1500), lat, o, GridRange{ 0, 1500, 0, 1500 }, maps).error;
    const double grown = peakRssBytes() - before;
    const bool ok = err.empty() && maps.fraction[0] > 0.0 && grown < 400.0 * 1024 * 1024;
    if (!ok)
    {
      std::fprintf(
        stderr, "error '%s', peak RSS grew by %.0f MB\n", err.c_str(), grown / 1048576.0);
    }
    _exit(ok ? 0 : 1);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}
