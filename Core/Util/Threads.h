/// Thread count of one Core call: an explicit argument, 0 = all available cores. Never changes the
/// process-wide OpenMP setting (that belongs to the ParaView process, docs/architecture.md §2).
/// One rule for every NumberOfThreads property: 0 to kMaxThreads is accepted (validateThreadCount),
/// and more than 4 × the cores is clamped to that (threadCountWarning says so): results never
/// depend on the thread count, only the memory for per-thread buffers and stacks grows with it.
#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

#include <string>

namespace fiberpli
{

/// Largest NumberOfThreads accepted (the XML range's maximum).
constexpr int kMaxThreads = 1024;

inline int availableCores()
{
#ifdef _OPENMP
  return omp_get_num_procs();
#else
  return 1;
#endif
}

/// Threads actually used: requested (clamped to 4 × the cores), or all cores for 0.
inline int resolveThreadCount(int requested)
{
  if (requested > 0)
  {
    return requested < 4 * availableCores() ? requested : 4 * availableCores();
  }
  return availableCores();
}

/// Empty when `requested` is a valid NumberOfThreads, else the message naming it.
inline std::string validateThreadCount(int requested)
{
  if (requested < 0 || requested > kMaxThreads)
  {
    return "NumberOfThreads is " + std::to_string(requested) + ", must be in [0, " +
      std::to_string(kMaxThreads) + "] (0 = all cores)";
  }
  return {};
}

/// Non-empty when resolveThreadCount clamps `requested`.
inline std::string threadCountWarning(int requested)
{
  if (requested > 4 * availableCores())
  {
    return "NumberOfThreads " + std::to_string(requested) + " is more than 4 x the " +
      std::to_string(availableCores()) + " cores: using " + std::to_string(4 * availableCores());
  }
  return {};
}

} // namespace fiberpli
