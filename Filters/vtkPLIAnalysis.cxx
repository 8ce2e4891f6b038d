#include "vtkPLIAnalysis.h"

#include "FiberAdapter.h"
#include "Analysis/PliAnalysis.h"
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

//------------------------------------------------------------------------------
// Construct with InclinationMethod Auto, ReferenceRetardation 0 (automatic), NoiseGain −1 (field
// data), all threads.
vtkPLIAnalysis::vtkPLIAnalysis() = default;

//------------------------------------------------------------------------------
int vtkPLIAnalysis::RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_DOUBLE, 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkPLIAnalysis::RequestData(vtkInformation* request, vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  // Exactly one AllReduce per call on every rank, whatever path this rank takes, then one
  // agreement on the error state (FiberCollective.h): all ranks fail together or none does.
  bool reduced = false;
  return fiberpli::FiberCollective::RunCollectively(this, request, outputVector, fiberpli::ProxyName(this), [&] {
    // Guarded here already (FiberGuard.h), so that an exception still leaves this rank's reduction.
    const int rc = fiberpli::GuardRequest(
      this, outputVector, fiberpli::ProxyName(this), [&]() -> int { return this->ExecutePiece(inputVector, outputVector, reduced); });
    if (!reduced)
    {
      fiberpli::FiberCollective::GlobalMax(outInfo, 0.0);
    }
    return rc;
  });
}

//------------------------------------------------------------------------------
int vtkPLIAnalysis::ExecutePiece(vtkInformationVector** inputVector, vtkInformationVector* outputVector, bool& reduced)
{
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  output->Initialize();

  fiberpli::PliAnalysisOptions options;
  std::string optionError = fiberpli::inclinationMethodFromCode(this->InclinationMethod, options.method);
  options.referenceRetardation = this->ReferenceRetardation;
  options.noiseGain = this->NoiseGain;
  options.threads = this->NumberOfThreads;
  if (optionError.empty())
  {
    optionError = fiberpli::checkPliAnalysisOptions(options);
  }
  if (optionError.empty()) // inside the collective path: a bad value on one rank must not hang the others
  {
    optionError = fiberpli::validateThreadCount(this->NumberOfThreads);
  }
  const std::string threadWarning = fiberpli::threadCountWarning(this->NumberOfThreads);
  if (optionError.empty() && !threadWarning.empty())
  {
    fiberpliWarningMacro(<< threadWarning);
  }
  if (!optionError.empty())
  {
    fiberpliErrorMacro(<< optionError);
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
  options.globalMaxRetardation = [&reduced, outInfo](double local) {
    reduced = true;
    return fiberpli::FiberCollective::GlobalMax(outInfo, local);
  };
  const fiberpli::GridRange range{ ext[0] - inExt[0], ext[1] - inExt[0] + 1, ext[2] - inExt[2], ext[3] - inExt[2] + 1 };

  this->SetProgressText("Analysing the polarizer stack");
  fiberpli::PliAnalysisMaps maps;
  const fiberpli::Status status = fiberpli::analysePli(in.stack, options, range, maps, fiberpli::MakeProgress(this));
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
