/**
 * @file FiberProgress.h
 * @brief the one bridge from Core progress callbacks to VTK progress and abort, for every
 * FiberPLI filter, source, reader and writer
 *
 * MakeProgress(algorithm) returns a fiberpli::ProgressFn that calls UpdateProgress and returns
 * false when the user asked to abort. It is the only place with a VTK version check
 * (CheckAbort() exists from VTK 9.2.20220817 on; older VTK has GetAbortExecute()).
 * AbortScope, the first line of every RequestData, makes an abort apply to one execution only and
 * ends it as a finished execution with empty outputs and a warning (no new run by the next
 * request).
 */
#ifndef FiberProgress_h
#define FiberProgress_h

#include "FiberExecutions.h"
#include "Util/Progress.h"

#include <vtkAlgorithm.h>
#include <vtkDataObject.h>
#include <vtkExecutive.h>
#include <vtkVersion.h>

namespace fiberpli
{

/// Progress in [0, 1] of the whole algorithm is mapped to [begin, end] of the filter's progress.
inline ProgressFn MakeProgress(vtkAlgorithm* algorithm, double begin = 0.0, double end = 1.0)
{
  return [algorithm, begin, end](double fraction)
  {
    algorithm->UpdateProgress(begin + (end - begin) * fraction);
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 2, 20220817)
    return !algorithm->CheckAbort();
#else
    return !algorithm->GetAbortExecute();
#endif
  };
}

/// Ends an aborted execution as a finished one. VTK leaves AbortExecute set after an abort (from a
/// progress observer or the GUI), so every later update of this algorithm, and of every algorithm
/// downstream (CheckAbort looks upstream), would stop at once; and an output marked ABORTED is made
/// again by the very next pipeline request, which in the GUI is the view's update right after the
/// aborted Apply: a new run would start from 0 % and need a second click. So an aborted execution
/// leaves its outputs empty, says so once (a warning, shown in the GUI's Output Messages), clears
/// the request and counts as done: the filter runs again when its input or a property changes.
/// While the scope lasts the execution is listed in FiberExecutions, where the GUI's abort button
/// finds it.
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
      this->Algorithm->SetAbortExecute(0);
#if VTK_VERSION_NUMBER >= VTK_VERSION_CHECK(9, 2, 20220817)
      this->Algorithm->SetAbortOutput(false); // not ABORTED: no new run at the next request
#endif
      for (int port = 0; port < this->Algorithm->GetNumberOfOutputPorts(); ++port)
      {
        if (vtkDataObject* output = this->Algorithm->GetExecutive()->GetOutputData(port))
        {
          output->Initialize(); // a partial result is never passed on
        }
      }
      std::string name = this->Algorithm->GetClassName();
      if (name.rfind("vtk", 0) == 0)
      {
        name.erase(0, 3);
      }
      vtkWarningWithObjectMacro(this->Algorithm,
        << name
        << ": aborted by the user; the output stays "
           "empty until the input or a property changes (then Apply runs it again)");
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
