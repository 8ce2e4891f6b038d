#include "vtkFiberParallelWriter.h"

#include "FiberCollective.h"
#include "vtkFiberWriter.h"

#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>

#include <string>

vtkStandardNewMacro(vtkFiberParallelWriter);

//------------------------------------------------------------------------------
int vtkFiberParallelWriter::RequestData(vtkInformation* request, vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  auto* writer = vtkFiberWriter::SafeDownCast(this->GetWriter());
  if (writer)
  {
    writer->SetLastWriteError(nullptr);
  }
  const int rc = this->Superclass::RequestData(request, inputVector, outputVector);
  const bool reported = writer && writer->GetLastWriteError(); // by the inner writer, on this rank
  std::string local = reported ? writer->GetLastWriteError() : "";
  if (rc == 0 && local.empty())
  {
    local = "FiberWriter: writing " + std::string(this->GetFileName() ? this->GetFileName() : "") + " failed";
  }
  // The input's request is the piece of this rank in ParaView's parallel update.
  const std::string error =
    fiberpli::FiberCollective::AgreeOnError(inputVector[0]->GetInformationObject(0), "FiberWriter", local);
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
