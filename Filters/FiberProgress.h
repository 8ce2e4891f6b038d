/**
 * @file FiberProgress.h
 * @brief the one bridge from Core progress callbacks to VTK progress and abort
 *
 * MakeProgress(algorithm) returns a fiberpli::ProgressFn that calls UpdateProgress and returns
 * false when the user asked to abort. It is the only place with a VTK version check
 * (CheckAbort() exists from VTK 9.2.20220817 on; older VTK has GetAbortExecute()).
 */
#ifndef FiberProgress_h
#define FiberProgress_h

#include "Util/Progress.h"

#include <vtkAlgorithm.h>
#include <vtkVersion.h>

namespace fiberpli
{

/// Progress in [0, 1] of the whole algorithm is mapped to [begin, end] of the filter's progress.
inline ProgressFn MakeProgress(vtkAlgorithm* algorithm, double begin = 0.0, double end = 1.0)
{
  return [algorithm, begin, end](double fraction) {
    algorithm->UpdateProgress(begin + (end - begin) * fraction);
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 2, 20220817)
    return !algorithm->CheckAbort();
#else
    return !algorithm->GetAbortExecute();
#endif
  };
}

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberProgress.h
