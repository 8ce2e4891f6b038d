#include "FiberExecutions.h"

#include <vtkAlgorithm.h>

#include <algorithm>
#include <mutex>
#include <vector>

namespace fiberpli
{
namespace
{
std::mutex& lock()
{
  static std::mutex m;
  return m;
}
std::vector<vtkAlgorithm*>& running()
{
  static std::vector<vtkAlgorithm*> r;
  return r;
}
} // namespace

void FiberExecutions::Enter(vtkAlgorithm* algorithm)
{
  const std::lock_guard<std::mutex> guard(lock());
  running().push_back(algorithm);
}

void FiberExecutions::Leave(vtkAlgorithm* algorithm)
{
  const std::lock_guard<std::mutex> guard(lock());
  std::vector<vtkAlgorithm*>& r = running();
  const auto last = std::find(r.rbegin(), r.rend(), algorithm); // the innermost entry
  if (last != r.rend())
  {
    r.erase(std::next(last).base());
  }
}

bool FiberExecutions::Running()
{
  const std::lock_guard<std::mutex> guard(lock());
  return !running().empty();
}

int FiberExecutions::Abort()
{
  const std::lock_guard<std::mutex> guard(lock());
  for (vtkAlgorithm* algorithm : running())
  {
    // Also stamps the abort time, so that CheckAbort of filters downstream sees it.
    algorithm->SetAbortExecuteAndUpdateTime();
  }
  return static_cast<int>(running().size());
}

} // namespace fiberpli
