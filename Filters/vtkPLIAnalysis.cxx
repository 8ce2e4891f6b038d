#include "vtkPLIAnalysis.h"

#include "Analysis/PliAnalysis.h"
#include "FiberAdapter.h"
#include "FiberCollective.h"
#include "FiberGuard.h"
#include "FiberProgress.h"
#include "PLIImage.h"

#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <string>

vtkStandardNewMacro(vtkPLIAnalysis);

namespace
{
/// The Core options of the properties: "" or the error naming the first bad property.
std::string MakeOptions(vtkPLIAnalysis* self, fiberpli::PliAnalysisOptions& options)
{
  const std::string method =
    fiberpli::inclinationMethodFromCode(self->GetInclinationMethod(), options.method);
  options.referenceRetardation = self->GetReferenceRetardation();
  options.noiseGain = self->GetNoiseGain();
  options.threads = self->GetNumberOfThreads();
  return method.empty() ? fiberpli::checkPliAnalysisOptions(options) : method;
}
} // namespace

//------------------------------------------------------------------------------
// Construct with InclinationMethod Auto, ReferenceRetardation 0 (automatic), NoiseGain −1 (field
// data), all threads.
vtkPLIAnalysis::vtkPLIAnalysis() = default;

//------------------------------------------------------------------------------
int vtkPLIAnalysis::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_DOUBLE, 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkPLIAnalysis::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  // Exactly one AllReduce per call on every rank, whatever path this rank takes, then one
  // agreement on the error state (FiberCollective.h): all ranks fail together or none does.
  bool reduced = false;
  return fiberpli::FiberCollective::RunCollectively(this, request, outputVector,
    fiberpli::ProxyName(this),
    [&]
    {
      // Guarded here already (FiberGuard.h), so that an exception still leaves this rank's
      // reduction.
      const int rc = fiberpli::GuardRequest(this, outputVector, fiberpli::ProxyName(this),
        [&]() -> int { return this->ExecutePiece(inputVector, outputVector, reduced); });
      if (!reduced)
      {
        fiberpli::FiberCollective::GlobalMax(outInfo, 0.0);
      }
      return rc;
    });
}

//------------------------------------------------------------------------------
int vtkPLIAnalysis::ExecutePiece(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector, bool& reduced)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  output->Initialize();

  // Checked inside the collective path: a bad value on one rank must not hang the others.
  fiberpli::PliAnalysisOptions options;
  const std::string optionError = MakeOptions(this, options);
  if (!optionError.empty())
  {
    fiberpliErrorMacro(<< optionError);
    return 0;
  }
  if (!fiberpli::CheckThreads(this, this->NumberOfThreads))
  {
    return 0;
  }
  if (!input || input->GetNumberOfPoints() == 0)
  {
    return 1; // empty input or piece: empty output, no error
  }
  // The whole input is the stack; this piece analyses the update extent's pixels of it.
  fiberpli::PliStackInput in;
  const std::string stackError = fiberpli::ReadPliStack(input, options.method, in);
  if (!stackError.empty())
  {
    fiberpliErrorMacro(<< stackError);
    return 0;
  }
  int inExt[6], ext[6];
  input->GetExtent(inExt);
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
  for (int a = 0; a < 3; ++a)
  {
    ext[2 * a] = std::max(ext[2 * a], inExt[2 * a]);
    ext[2 * a + 1] = std::min(ext[2 * a + 1], inExt[2 * a + 1]);
  }
  options.globalMaxRetardation = [&reduced, outInfo](double local)
  {
    reduced = true;
    return fiberpli::FiberCollective::GlobalMax(outInfo, local);
  };
  const fiberpli::GridRange range{ ext[0] - inExt[0], ext[1] - inExt[0] + 1, ext[2] - inExt[2],
    ext[3] - inExt[2] + 1 };

  this->SetProgressText("Analysing the polarizer stack");
  fiberpli::PliAnalysisMaps maps;
  const fiberpli::Status status =
    fiberpli::analysePli(in.stack, options, range, maps, fiberpli::MakeProgress(this));
  if (status.aborted)
  {
    return 1; // partial results are never passed on
  }
  if (!status.ok())
  {
    fiberpliErrorMacro(<< status.error);
    return 0;
  }

  output->SetExtent(ext);
  output->SetOrigin(input->GetOrigin());
  output->SetSpacing(input->GetSpacing());
  output->SetDirectionMatrix(input->GetDirectionMatrix());
  fiberpli::WriteAnalysisMaps(maps, in.stack.nx, range, output);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkPLIAnalysis::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "InclinationMethod: " << this->InclinationMethod << "\n";
  os << indent << "ReferenceRetardation: " << this->ReferenceRetardation << "\n";
  os << indent << "NoiseGain: " << this->NoiseGain << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
