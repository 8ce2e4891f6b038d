/// Thread count of one Core call: an explicit argument, 0 = all available cores. Never changes the
/// process-wide OpenMP setting (that belongs to the ParaView process, architecture.md §2).
#pragma once

#ifdef _OPENMP
#include <omp.h>
#endif

namespace fiberpli
{

inline int resolveThreadCount(int requested)
{
  if (requested > 0)
  {
    return requested;
  }
#ifdef _OPENMP
  return omp_get_num_procs();
#else
  return 1;
#endif
}

} // namespace fiberpli
