// Shared helpers of the benchmark drivers: wall clock, CPU time and peak resident memory.
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

/// User + system CPU seconds of this process (all its threads).
inline double cpuSeconds()
{
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
    1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

/// Peak resident set size of this process in MB (Linux reports ru_maxrss in kB).
inline double peakRssMB()
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;
}

} // namespace fiberpli::bench
