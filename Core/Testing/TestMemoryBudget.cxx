// MemoryBudget: the budget follows the machine and FIBERPLI_MEMORY_LIMIT, and refuses NaN.
#include "Util/MemoryBudget.h"

#include "MemoryLimitGuard.h"

#include <gtest/gtest.h>

#include <sys/resource.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <string>

using EnvGuard = fiberpli::testing::MemoryLimitGuard;

TEST(MemoryBudget, HalfOfUsableMemoryAtMostPhysical)
{
  EnvGuard env(nullptr);
  const double physical =
    static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  const double usable = static_cast<double>(fiberpli::usableMemoryBytes());
  EXPECT_GT(usable, 0.0);
  EXPECT_LE(usable, physical);
  EXPECT_DOUBLE_EQ(fiberpli::memoryBudgetBytes(), 0.5 * usable);
}

TEST(MemoryBudget, AddressSpaceLimitLowersTheBudget)
{
  EnvGuard env(nullptr);
  rlimit old{};
  ASSERT_EQ(getrlimit(RLIMIT_AS, &old), 0);
  const double before = fiberpli::memoryBudgetBytes();
  rlimit capped = old;
  capped.rlim_cur = static_cast<rlim_t>(before); // equal to the old budget: the new one halves it
  if (old.rlim_max != RLIM_INFINITY && old.rlim_max < capped.rlim_cur)
  {
    GTEST_SKIP() << "hard address-space limit below the budget";
  }
  ASSERT_EQ(setrlimit(RLIMIT_AS, &capped), 0);
  const double after = fiberpli::memoryBudgetBytes();
  ASSERT_EQ(setrlimit(RLIMIT_AS, &old), 0);
  EXPECT_DOUBLE_EQ(after, 0.5 * before);
}

TEST(MemoryBudget, EnvironmentOverrideWithSuffixes)
{
  {
    EnvGuard env("3G");
    EXPECT_DOUBLE_EQ(fiberpli::memoryBudgetBytes(), 3.0 * 1024 * 1024 * 1024);
  }
  {
    EnvGuard env("512MiB");
    EXPECT_DOUBLE_EQ(fiberpli::memoryBudgetBytes(), 512.0 * 1024 * 1024);
  }
  {
    EnvGuard env("1000");
    EXPECT_DOUBLE_EQ(fiberpli::memoryBudgetBytes(), 1000.0);
    EXPECT_TRUE(fiberpli::checkMemoryBudget(1000.0, "x").empty());
    const std::string msg = fiberpli::checkMemoryBudget(1001.0, "The tissue");
    EXPECT_NE(msg.find("The tissue needs 1001 B"), std::string::npos) << msg;
    EXPECT_NE(msg.find("FIBERPLI_MEMORY_LIMIT"), std::string::npos) << msg;
  }
  {
    EnvGuard env("nonsense"); // malformed: ignored, the machine's budget applies
    EXPECT_GT(fiberpli::memoryBudgetBytes(), 1e6);
  }
}

TEST(MemoryBudget, NaNAndInfinityAreRefused)
{
  EXPECT_FALSE(fiberpli::checkMemoryBudget(std::nan(""), "x").empty());
  EXPECT_FALSE(fiberpli::checkMemoryBudget(INFINITY, "x").empty());
}

TEST(MemoryBudget, FormatBytes)
{
  EXPECT_EQ(fiberpli::formatBytes(17), "17 B");
  EXPECT_EQ(fiberpli::formatBytes(1536), "1.5 KiB");
  EXPECT_EQ(fiberpli::formatBytes(3.0 * 1024 * 1024 * 1024), "3 GiB");
}
