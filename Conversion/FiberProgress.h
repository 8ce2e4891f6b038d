/**
 * @file FiberProgress.h
 * @brief the one bridge from Core progress callbacks to VTK progress and abort, for every
 * FiberPLI filter, source, reader and writer
 *
 * MakeProgress(algorithm) returns a fiberpli::ProgressFn that calls UpdateProgress and returns
 * false when the user asked to abort. It is the only place with a VTK version check
 * (CheckAbort() exists from VTK 9.2.20220817 on; older VTK has GetAbortExecute()).
 * AbortScope, the first line of every RequestData, makes an abort apply to one execution only.
 */
#ifndef FiberProgress_h
#define FiberProgress_h

#include "FiberExecutions.h"
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

/// Clears the abort request when the execution ends. VTK leaves AbortExecute set after an abort
/// (from a progress observer or the GUI), so every later update of this algorithm, and of every
/// algorithm downstream (CheckAbort looks upstream), would stop at once and pass empty output on.
/// The aborted execution itself is still reported to the executive (its output is marked aborted
/// and is made again by the next update). While the scope lasts the execution is listed in
/// FiberExecutions, where the GUI's abort button finds it.
class AbortScope
{
public:
  explicit AbortScope(vtkAlgorithm* algorithm)
    : Algorithm(algorithm)
  {
    FiberExecutions::Enter(algorithm);
  }
  ~AbortScope()
  {
    FiberExecutions::Leave(this->Algorithm);
    if (this->Algorithm->GetAbortExecute())
    {
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 2, 20220817)
      this->Algorithm->CheckAbort(); // marks the output as aborted
#endif
      this->Algorithm->SetAbortExecute(0);
    }
  }
  AbortScope(const AbortScope&) = delete;
  AbortScope& operator=(const AbortScope&) = delete;

private:
  vtkAlgorithm* Algorithm;
};

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberProgress.h
