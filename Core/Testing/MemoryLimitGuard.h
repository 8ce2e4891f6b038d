// Sets (or unsets, for nullptr) FIBERPLI_MEMORY_LIMIT for the lifetime of the object and restores
// the previous value: tests of the size guards run under a small, known budget.
#pragma once

#include <cstdlib>
#include <string>

namespace fiberpli
{
namespace testing
{

struct MemoryLimitGuard
{
  explicit MemoryLimitGuard(const char* value)
  {
    if (const char* old = std::getenv("FIBERPLI_MEMORY_LIMIT"))
    {
      saved = old;
      had = true;
    }
    if (value)
    {
      setenv("FIBERPLI_MEMORY_LIMIT", value, 1);
    }
    else
    {
      unsetenv("FIBERPLI_MEMORY_LIMIT");
    }
  }
  ~MemoryLimitGuard()
  {
    if (had)
    {
      setenv("FIBERPLI_MEMORY_LIMIT", saved.c_str(), 1);
    }
    else
    {
      unsetenv("FIBERPLI_MEMORY_LIMIT");
    }
  }
  MemoryLimitGuard(const MemoryLimitGuard&) = delete;
  MemoryLimitGuard& operator=(const MemoryLimitGuard&) = delete;

  std::string saved;
  bool had = false;
};

} // namespace testing
} // namespace fiberpli
