#include "vtkPLIAnalysis.h"

#include "Analysis/PliAnalysis.h"
#include "ArrayValues.h"
#include "FiberCollective.h"
#include "FiberGuard.h"
#include "FiberFieldData.h"
#include "FiberProgress.h"
#include "Section/PLIFields.h"
#include "Section/TiltConvention.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <deque>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPLIAnalysis);

namespace
{
constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// Field data scalar, or `fallback` when the array is absent or empty.
double FieldValue(vtkDataObject* data, const char* name, double fallback)
{
  vtkDataArray* a = data->GetFieldData() ? data->GetFieldData()->GetArray(name) : nullptr;
  return a && a->GetNumberOfValues() > 0 ? a->GetComponent(0, 0) : fallback;
}

/// All values of a field data array (empty when absent).
std::vector<double> FieldValues(vtkDataObject* data, const char* name)
{
  std::vector<double> values;
  vtkDataArray* a = data->GetFieldData() ? data->GetFieldData()->GetArray(name) : nullptr;
  for (vtkIdType k = 0; a && k < a->GetNumberOfValues(); ++k)
  {
    values.push_back(a->GetComponent(k / a->GetNumberOfComponents(), static_cast<int>(k % a->GetNumberOfComponents())));
  }
  return values;
}

/// The tilted views of the input from its field data: `tilt_angles` and `tilt_directions` (one per
/// intensity_tilt_v), or the older one-angle form (`tilt_angle`, azimuths 0°, 90°, 180°, 270°).
/// Returns an error naming the field data array when the counts do not match the tilted stacks.
std::string ReadTiltViews(vtkDataObject* input, std::size_t stacks, std::vector<fiberpli::TiltView>& views)
{
  views.clear();
  if (stacks == 0)
  {
    return {};
  }
  std::vector<double> angles = FieldValues(input, fiberpli::plifield::kTiltAngles);
  std::vector<double> azimuths = FieldValues(input, fiberpli::plifield::kTiltDirections);
  const bool hasAngles = input->GetFieldData() && input->GetFieldData()->GetArray(fiberpli::plifield::kTiltAngles);
  if (!hasAngles)
  {
    angles.assign(stacks, FieldValue(input, fiberpli::plifield::kTiltAngle, 0.0));
  }
  if (azimuths.empty() && stacks == 4)
  {
    azimuths = { 0.0, 90.0, 180.0, 270.0 };
  }
  std::ostringstream msg;
  if (angles.size() != stacks)
  {
    msg << "field data '" << fiberpli::plifield::kTiltAngles << "' has " << angles.size() << " values for " << stacks
        << " tilted views (" << fiberpli::plifield::kIntensityTiltPrefix << "*)";
  }
  else if (azimuths.size() != stacks)
  {
    msg << "field data '" << fiberpli::plifield::kTiltDirections << "' has " << azimuths.size() << " values for "
        << stacks << " tilted views (" << fiberpli::plifield::kIntensityTiltPrefix << "*)";
  }
  if (!msg.str().empty())
  {
    return msg.str();
  }
  for (std::size_t v = 0; v < stacks; ++v)
  {
    views.push_back(fiberpli::TiltView{ angles[v] * kDeg, azimuths[v] * kDeg });
  }
  return {};
}


} // namespace

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
  return fiberpli::FiberCollective::RunCollectively(this, request, outputVector, "PLIAnalysis", [&] {
    // Guarded here already (FiberGuard.h), so that an exception still leaves this rank's reduction.
    const int rc = fiberpli::GuardRequest(
      this, outputVector, "PLIAnalysis", [&]() -> int { return this->ExecutePiece(inputVector, outputVector, reduced); });
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
    vtkWarningMacro(<< "PLIAnalysis: " << threadWarning);
  }
  if (!optionError.empty())
  {
    vtkErrorMacro(<< "PLIAnalysis: " << optionError);
    return 0;
  }
  if (!input || input->GetNumberOfPoints() == 0)
  {
    return 1; // empty input or piece: empty output, no error
  }
  int inExt[6], ext[6];
  input->GetExtent(inExt);
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
  for (int a = 0; a < 3; ++a)
  {
    ext[2 * a] = std::max(ext[2 * a], inExt[2 * a]);
    ext[2 * a + 1] = std::min(ext[2 * a + 1], inExt[2 * a + 1]);
  }
  if (inExt[5] != inExt[4])
  {
    vtkErrorMacro(<< "PLIAnalysis: the input has " << inExt[5] - inExt[4] + 1
                  << " slices along z; expected one slice (the PLISimulation image)");
    return 0;
  }
  vtkDataArray* intensity = input->GetPointData()->GetArray(fiberpli::plifield::kIntensity);
  if (!intensity)
  {
    vtkErrorMacro(<< "PLIAnalysis: the input has no point array '" << fiberpli::plifield::kIntensity
                  << "' (one component per polarizer angle)");
    return 0;
  }
  const int n = intensity->GetNumberOfComponents();
  std::vector<double> rho;
  if (vtkDataArray* angles = input->GetFieldData()->GetArray(fiberpli::plifield::kPolarizerAngles))
  {
    for (vtkIdType k = 0; k < angles->GetNumberOfValues(); ++k)
    {
      rho.push_back(angles->GetComponent(k / angles->GetNumberOfComponents(), static_cast<int>(k % angles->GetNumberOfComponents())) * kDeg);
    }
  }
  else
  {
    for (int k = 0; k < n; ++k)
    {
      rho.push_back(k * 180.0 / n * kDeg);
    }
  }
  if (rho.size() < 3)
  {
    vtkErrorMacro(<< "PLIAnalysis: " << rho.size() << " polarizer angles (field data '" << fiberpli::plifield::kPolarizerAngles
                  << "' or the components of '" << fiberpli::plifield::kIntensity << "'); at least 3 are needed");
    return 0;
  }
  if (static_cast<std::size_t>(n) != rho.size())
  {
    vtkErrorMacro(<< "PLIAnalysis: point array '" << fiberpli::plifield::kIntensity << "' has " << n
                  << " components but field data '" << fiberpli::plifield::kPolarizerAngles << "' has "
                  << rho.size() << " angles; they must be equal");
    return 0;
  }

  fiberpli::PliStack stack;
  stack.nx = inExt[1] - inExt[0] + 1;
  stack.ny = inExt[3] - inExt[2] + 1;
  stack.rho = rho;
  std::deque<std::vector<double>> buffers(1); // a deque never moves its elements: pointers stay valid
  stack.intensity = fiberpli::AsDoubles(intensity, buffers[0]);
  for (int v = 0;; ++v)
  {
    const std::string name = fiberpli::plifield::intensityTilt(static_cast<std::size_t>(v));
    vtkDataArray* a = input->GetPointData()->GetArray(name.c_str());
    if (!a)
    {
      break;
    }
    if (a->GetNumberOfComponents() != n)
    {
      vtkErrorMacro(<< "PLIAnalysis: point array '" << name << "' has " << a->GetNumberOfComponents()
                    << " components, '" << fiberpli::plifield::kIntensity << "' has " << n << "; they must be equal");
      return 0;
    }
    buffers.emplace_back();
    stack.tilts.push_back(fiberpli::AsDoubles(a, buffers.back()));
  }
  const std::string tiltError = ReadTiltViews(input, stack.tilts.size(), stack.tiltViews);
  if (!tiltError.empty())
  {
    vtkErrorMacro(<< "PLIAnalysis: " << tiltError);
    return 0;
  }
  // Views on the tilted sensor's grid are not pixel-aligned with the untilted view: a pixel's
  // tilted intensities would belong to other points of the section, so the tilt fit is refused.
  if (FieldValue(input, fiberpli::plifield::kTiltedSensor, 0.0) == 1.0 && !stack.tilts.empty())
  {
    if (this->InclinationMethod == TILT)
    {
      vtkErrorMacro(<< "PLIAnalysis: InclinationMethod Tilt needs tilted views registered onto the sample's pixel grid, "
                       "but these are on the tilted sensor's grid (field data "
                    << fiberpli::plifield::kTiltedSensor
                    << " = 1): simulate with TiltedSensor off, or use InclinationMethod Retardation");
      return 0;
    }
    stack.tilts.clear(); // Auto: the retardation method, from the untilted view alone
    stack.tiltViews.clear();
  }
  stack.convention = FieldValue(input, fiberpli::plifield::kTiltConvention, 0.0) == fiberpli::tiltConventionCode(fiberpli::TiltConvention::FastPLI) ? fiberpli::TiltConvention::FastPLI
                                                                       : fiberpli::TiltConvention::Physical;
  stack.noiseGain = FieldValue(input, fiberpli::plifield::kNoiseGain, -1.0);

  options.globalMaxRetardation = [&reduced, outInfo](double local) {
    reduced = true;
    return fiberpli::FiberCollective::GlobalMax(outInfo, local);
  };
  const fiberpli::GridRange range{ ext[0] - inExt[0], ext[1] - inExt[0] + 1, ext[2] - inExt[2], ext[3] - inExt[2] + 1 };

  this->SetProgressText("Analysing the polarizer stack");
  fiberpli::PliAnalysisMaps maps;
  const fiberpli::Status status = fiberpli::analysePli(stack, options, range, maps, fiberpli::MakeProgress(this));
  if (status.aborted)
  {
    return 1; // partial results are never passed on
  }
  if (!status.ok())
  {
    vtkErrorMacro(<< "PLIAnalysis: " << status.error);
    return 0;
  }

  output->SetExtent(ext);
  output->SetOrigin(input->GetOrigin());
  output->SetSpacing(input->GetSpacing());
  output->SetDirectionMatrix(input->GetDirectionMatrix());
  const vtkIdType count = static_cast<vtkIdType>(range.count());
  auto addMap = [&](const char* name, const std::vector<double>& map, double scale) {
    if (map.empty())
    {
      return;
    }
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->SetNumberOfValues(count);
    vtkIdType k = 0;
    for (std::int64_t j = range.j0; j < range.j1; ++j)
    {
      for (std::int64_t i = range.i0; i < range.i1; ++i)
      {
        a->SetValue(k++, map[static_cast<std::size_t>(i + stack.nx * j)] * scale);
      }
    }
    output->GetPointData()->AddArray(a);
  };
  addMap("transmittance", maps.transmittance, 1.0);
  addMap("direction", maps.direction, 1.0 / kDeg);
  addMap("retardation", maps.retardation, 1.0);
  addMap("inclination", maps.inclination, 1.0 / kDeg);
  addMap("inclination_signed", maps.inclinationSigned, 1.0 / kDeg);
  addMap("relative_thickness", maps.relativeThickness, 1.0);
  addMap("fit_chi2", maps.chi2, 1.0);
  output->GetPointData()->SetActiveScalars("direction");
  // Directions just below 180° can round to exactly 180 in degrees: keep the [0, 180) contract.
  auto* direction = vtkDoubleArray::SafeDownCast(output->GetPointData()->GetArray("direction"));
  for (vtkIdType k = 0; k < count; ++k)
  {
    if (direction->GetValue(k) >= 180.0)
    {
      direction->SetValue(k, direction->GetValue(k) - 180.0);
    }
  }

  fiberpli::AddFieldDoubles(output, fiberpli::plifield::kReferenceRetardation, { maps.referenceRetardation });
  fiberpli::AddFieldInt(output, fiberpli::plifield::kInclinationMethod, static_cast<int>(maps.method));
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
