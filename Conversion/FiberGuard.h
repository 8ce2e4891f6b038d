/**
 * @file FiberGuard.h
 * @brief the one exception guard around the work of every FiberPLI source, filter, reader and
 * writer
 *
 * The Core never throws across its interface, but the standard library still can (std::bad_alloc
 * when memory runs out beyond what the memory budget foresaw, std::length_error from a size
 * computed from absurd input). An exception that leaves RequestData passes through VTK's
 * executive and ends pvpython or the ParaView server. GuardRequest turns it into a VTK error
 * naming the algorithm ("<who>: out of memory …" / "<who>: internal error: …"), empties the
 * outputs and returns 0, so the pipeline stays usable. Every RequestData (and a writer's
 * WriteData) runs its work through it; FiberCollective::RunCollectively does so for the filters
 * that agree on errors over MPI ranks, so that the other ranks learn of the failure too.
 * TryInMemory is the same out-of-memory rule for a step that can say more than "out of memory"
 * (which file it was reading, how many fibers it was measuring).
 */
#ifndef FiberGuard_h
#define FiberGuard_h

#include <vtkAlgorithm.h>
#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>

#include <exception>
#include <new>
#include <string>

namespace fiberpli
{

/// Runs `work` and returns true, or false when it ran out of memory (std::bad_alloc); any other
/// exception is left to GuardRequest.
template <typename Work>
bool TryInMemory(Work&& work)
{
  try
  {
    work();
    return true;
  }
  catch (const std::bad_alloc&)
  {
    return false;
  }
}

/// Runs `work` (returns 1 on success, 0 on a reported error) and returns its result; an exception
/// escaping it becomes a VTK error of `self` naming `who`, the data objects of `outputs` (may be
/// null) are emptied, and 0 is returned.
template <typename Work>
int GuardRequest(
  vtkAlgorithm* self, vtkInformationVector* outputs, const std::string& who, Work&& work)
{
  std::string problem;
  try
  {
    return work();
  }
  catch (const std::bad_alloc&)
  {
    problem = who +
      ": out of memory (lower the size of the input or the properties that multiply it, "
      "or set FIBERPLI_MEMORY_LIMIT so that such requests are refused up front)";
  }
  catch (const std::exception& e)
  {
    problem = who + ": internal error: " + e.what() +
      " (the input or a property is out of what it can handle)";
  }
  catch (...)
  {
    problem = who + ": internal error (unknown exception)";
  }
  for (int p = 0; outputs && p < outputs->GetNumberOfInformationObjects(); ++p)
  {
    if (vtkDataObject* data = outputs->GetInformationObject(p)->Get(vtkDataObject::DATA_OBJECT()))
    {
      data->Initialize();
    }
  }
  vtkErrorWithObjectMacro(self, << problem);
  return 0;
}

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberGuard.h
