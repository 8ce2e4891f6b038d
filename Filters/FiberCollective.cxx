#include "FiberCollective.h"

#include <vtkCommunicator.h>
#include <vtkInformation.h>
#include <vtkMultiProcessController.h>
#include <vtkMultiProcessStream.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <climits>

namespace fiberpli
{

vtkMultiProcessController* FiberCollective::ControllerFor(vtkInformation* info)
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  if (!c || c->GetNumberOfProcesses() < 2 || !info ||
    !info->Has(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()))
  {
    return nullptr;
  }
  return info->Get(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES()) == c->GetNumberOfProcesses() ? c
                                                                                                             : nullptr;
}

std::string FiberCollective::AgreeOnError(vtkInformation* info, const std::string& who, const std::string& localError)
{
  vtkMultiProcessController* c = ControllerFor(info);
  if (!c)
  {
    return localError;
  }
  const int rank = c->GetLocalProcessId();
  const int mine = localError.empty() ? INT_MAX : rank;
  int first = INT_MAX;
  c->AllReduce(&mine, &first, 1, vtkCommunicator::MIN_OP);
  if (first == INT_MAX)
  {
    return {};
  }
  vtkMultiProcessStream message;
  if (rank == first)
  {
    message << localError;
  }
  c->Broadcast(message, first);
  if (!localError.empty())
  {
    return localError;
  }
  std::string text;
  message >> text;
  return who + ": rank " + std::to_string(first) + " failed, so no rank gives output: " + text;
}

} // namespace fiberpli
