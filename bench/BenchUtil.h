// Shared helpers of the benchmark drivers: wall clock and peak resident memory.
#pragma once

#include <chrono>
#include <sys/resource.h>

namespace fiberpli::bench
{

inline double seconds()
{
  using Clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

/// Peak resident set size of this process in MB (Linux reports ru_maxrss in kB).
inline double peakRssMB()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

} // namespace fiberpli::bench
