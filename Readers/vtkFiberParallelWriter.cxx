#include "vtkFiberParallelWriter.h"

#include "FiberCollective.h"
#include "FiberGuard.h"
#include "vtkFiberWriter.h"

#include <vtkDataObject.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>

#include <string>

vtkStandardNewMacro(vtkFiberParallelWriter);

//------------------------------------------------------------------------------
int vtkFiberParallelWriter::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  auto* writer = vtkFiberWriter::SafeDownCast(this->GetWriter());
  if (writer)
  {
    writer->SetLastWriteError(nullptr);
  }
  // The pieces are gathered to one rank and written with one cell: a cell that is malformed on
  // a rank, or differs between ranks, fails every rank before the gather (FiberCollective.h).
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  const std::string cellError = fiberpli::FiberCollective::AgreeOnPeriodicCell(
    inInfo, "FiberWriter", vtkDataObject::GetData(inInfo));
  if (!cellError.empty())
  {
    vtkErrorMacro(<< cellError);
    return 0;
  }
  // Any exception escaping the write becomes a VTK error (FiberGuard.h), never an abort.
  const int rc = fiberpli::GuardRequest(this, nullptr, "FiberWriter",
    [&]() -> int { return this->Superclass::RequestData(request, inputVector, outputVector); });
  const bool reported = writer && writer->GetLastWriteError(); // by the inner writer, on this rank
  std::string local = reported ? writer->GetLastWriteError() : "";
  if (rc == 0 && local.empty())
  {
    local = "FiberWriter: writing " + std::string(this->GetFileName() ? this->GetFileName() : "") +
      " failed";
  }
  // The input's request is the piece of this rank in ParaView's parallel update.
  const std::string error = fiberpli::FiberCollective::AgreeOnError(
    inputVector[0]->GetInformationObject(0), "FiberWriter", local);
  if (error.empty())
  {
    return 1;
  }
  if (error != local || !reported)
  {
    vtkErrorMacro(<< error);
  }
  return 0;
}

//------------------------------------------------------------------------------
void vtkFiberParallelWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
