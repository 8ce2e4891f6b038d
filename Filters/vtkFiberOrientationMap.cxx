#include "vtkFiberOrientationMap.h"

#include "Analysis/FiberOrientationMap.h"
#include "ArrayValues.h"
#include "FiberAdapter.h"
#include "FiberCollective.h"
#include "FiberFieldData.h"
#include "FiberGuard.h"
#include "FiberProgress.h"
#include "Model/DataNames.h"

#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkStreamingDemandDrivenPipeline.h>
#include <vtkUnsignedCharArray.h>

#include <cstring>
#include <limits>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkFiberOrientationMap);

namespace
{
/// Empty when `a` has one component (a value per pixel), else the message naming it.
std::string OneComponent(vtkAlgorithm* self, vtkDataArray* a)
{
  return a->GetNumberOfComponents() == 1
    ? std::string()
    : fiberpli::ProxyMessage(self,
        std::string("the point array '") + a->GetName() + "' has " +
          std::to_string(a->GetNumberOfComponents()) + " components, must have 1");
}

/// The name of input array `idx` as set by SetInputArrayToProcess ("" when it is not set by name).
std::string SelectedName(vtkAlgorithm* self, int idx)
{
  vtkInformation* info = self->GetInputArrayInformation(idx);
  return info && info->Has(vtkDataObject::FIELD_NAME()) ? info->Get(vtkDataObject::FIELD_NAME())
                                                        : "";
}

} // namespace

//------------------------------------------------------------------------------
// Construct with ColorScheme HSV-black, LegendSize 256, all threads; two output ports (map,
// legend).
vtkFiberOrientationMap::vtkFiberOrientationMap()
{
  this->SetNumberOfOutputPorts(2);
  this->SetInputArrayToProcess(
    0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, fiberpli::plifield::kDirection);
  this->SetInputArrayToProcess(
    1, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, fiberpli::plifield::kInclination);
}

//------------------------------------------------------------------------------
int vtkFiberOrientationMap::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* mapInfo = outputVector->GetInformationObject(0);
  vtkDataObject::SetPointDataActiveScalarInfo(mapInfo, VTK_UNSIGNED_CHAR, 3);

  // The legend spans [−1, 1]²: pixel centres at −1 + (k + ½)·2/size.
  vtkInformation* legendInfo = outputVector->GetInformationObject(1);
  const int n = this->LegendSize;
  const int extent[6] = { 0, n - 1, 0, n - 1, 0, 0 };
  const double spacing[3] = { 2.0 / n, 2.0 / n, 2.0 / n };
  const double origin[3] = { -1.0 + 1.0 / n, -1.0 + 1.0 / n, 0.0 };
  legendInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  legendInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  legendInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(legendInfo, VTK_UNSIGNED_CHAR, 3);
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberOrientationMap::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // A request on the legend port must not become the input's extent: ask for what port 0 wants,
  // or the whole input when port 0 has no request.
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* mapInfo = outputVector->GetInformationObject(0);
  const auto key = vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT();
  if (mapInfo->Has(key))
  {
    inInfo->Set(key, mapInfo->Get(key), 6);
  }
  else if (inInfo->Has(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()))
  {
    inInfo->Set(key, inInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT()), 6);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberOrientationMap::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Any exception escaping the work becomes a VTK error (FiberGuard.h), never an abort.
  return fiberpli::GuardRequest(this, outputVector, fiberpli::ProxyName(this),
    [&]() -> int
    {
      const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
      // The mask's reference (the largest value) is taken over all pieces of a parallel update:
      // exactly one AllReduce per call on every rank, whatever path its piece takes, so none waits.
      bool reduced = false;
      const int rc = this->ExecutePiece(inputVector, outputVector, reduced);
      if (!reduced)
      {
        fiberpli::FiberCollective::GlobalMax(
          outputVector->GetInformationObject(0), -std::numeric_limits<double>::infinity());
      }
      return rc;
    });
}

//------------------------------------------------------------------------------
int vtkFiberOrientationMap::ExecutePiece(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector, bool& reduced)
{
  if (!fiberpli::CheckThreads(this, this->NumberOfThreads))
  {
    return 0;
  }
  fiberpli::FomScheme scheme;
  fiberpli::FomMask kind;
  if (!fiberpli::CheckEnum(
        this, this->ColorScheme, RGB, "ColorScheme", "0 (HSV-black) or 1 (RGB)", scheme) ||
    !fiberpli::CheckEnum(this, this->Mask, MASK_TRANSMITTANCE, "Mask",
      "0 (None), 1 (Retardation) or 2 (Transmittance)", kind))
  {
    return 0;
  }
  vtkImageData* input = vtkImageData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector, 0);
  vtkImageData* legend = vtkImageData::GetData(outputVector, 1);
  output->Initialize();
  legend->Initialize();

  // Legend first: it does not depend on the input.
  std::vector<std::uint8_t> rgb;
  std::string err = fiberpli::fomLegend(this->LegendSize, scheme, rgb);
  if (!err.empty())
  {
    fiberpliErrorMacro(<< "LegendSize " << this->LegendSize << ": " << err);
    return 0;
  }
  const int n = this->LegendSize;
  legend->SetExtent(0, n - 1, 0, n - 1, 0, 0);
  legend->SetSpacing(2.0 / n, 2.0 / n, 2.0 / n);
  legend->SetOrigin(-1.0 + 1.0 / n, -1.0 + 1.0 / n, 0.0);
  vtkNew<vtkUnsignedCharArray> legendFom;
  legendFom->SetName(fiberpli::plifield::kFom);
  legendFom->SetNumberOfComponents(3);
  legendFom->SetNumberOfTuples(static_cast<vtkIdType>(n) * n);
  std::memcpy(legendFom->GetPointer(0), rgb.data(), rgb.size());
  legend->GetPointData()->SetScalars(legendFom);

  if (!input || input->GetNumberOfPoints() == 0)
  {
    return 1; // empty input or piece: empty map, no error
  }
  vtkDataArray* direction = this->GetInputArrayToProcess(0, input);
  vtkDataArray* inclination = this->GetInputArrayToProcess(1, input);
  if (!direction || !inclination)
  {
    fiberpliErrorMacro(<< "the input has no point array '" << SelectedName(this, direction ? 1 : 0)
                       << "' (degrees; PLIAnalysis or FiberOrientationGroundTruth make it)");
    output->Initialize();
    return 0;
  }
  if (inclination->GetNumberOfTuples() != direction->GetNumberOfTuples() ||
    direction->GetNumberOfTuples() != input->GetNumberOfPoints())
  {
    fiberpliErrorMacro(<< "the point arrays '" << direction->GetName() << "' ("
                       << direction->GetNumberOfTuples() << " tuples) and '"
                       << inclination->GetName() << "' (" << inclination->GetNumberOfTuples()
                       << " tuples) differ in length or from the " << input->GetNumberOfPoints()
                       << " points");
    output->Initialize();
    return 0;
  }
  const std::string components = OneComponent(this, direction) + OneComponent(this, inclination);
  if (!components.empty())
  {
    vtkErrorMacro(<< components);
    output->Initialize();
    return 0;
  }
  output->ShallowCopy(input);
  std::vector<double> directionBuffer, inclinationBuffer;
  const double* d = fiberpli::AsDoubles(direction, directionBuffer);
  const double* i = fiberpli::AsDoubles(inclination, inclinationBuffer);
  const auto count = static_cast<std::size_t>(direction->GetNumberOfTuples());
  vtkNew<vtkUnsignedCharArray> fom;
  fom->SetName(fiberpli::plifield::kFom);
  fom->SetNumberOfComponents(3);
  fom->SetNumberOfTuples(static_cast<vtkIdType>(count));
  this->UpdateProgress(0.0);
  err = fiberpli::fomMap(d, i, count, scheme, this->NumberOfThreads, fom->GetPointer(0));
  if (!err.empty())
  {
    fiberpliErrorMacro(<< err);
    output->Initialize();
    return 0;
  }
  if (this->Mask != MASK_NONE)
  {
    const char* name = this->Mask == MASK_RETARDATION ? fiberpli::plifield::kRetardation
                                                      : fiberpli::plifield::kTransmittance;
    vtkDataArray* values = input->GetPointData()->GetArray(name);
    if (!values)
    {
      fiberpliErrorMacro(<< "Mask "
                         << (this->Mask == MASK_RETARDATION ? "Retardation" : "Transmittance")
                         << " needs the point array '" << name << "' (PLIAnalysis makes it)");
      output->Initialize();
      return 0;
    }
    if (values->GetNumberOfTuples() != direction->GetNumberOfTuples())
    {
      fiberpliErrorMacro(<< "the Mask array '" << name << "' has " << values->GetNumberOfTuples()
                         << " tuples, '" << direction->GetName() << "' has "
                         << direction->GetNumberOfTuples() << " (they must match)");
      output->Initialize();
      return 0;
    }
    if (!OneComponent(this, values).empty())
    {
      vtkErrorMacro(<< OneComponent(this, values));
      output->Initialize();
      return 0;
    }
    std::vector<double> valueBuffer;
    const double* v = fiberpli::AsDoubles(values, valueBuffer);
    const double largest = fiberpli::FiberCollective::GlobalMax(
      outputVector->GetInformationObject(0), fiberpli::fomMaskReference(v, count));
    reduced = true;
    double threshold = 0.0;
    vtkNew<vtkUnsignedCharArray> mask;
    mask->SetName(fiberpli::plifield::kMask);
    mask->SetNumberOfTuples(static_cast<vtkIdType>(count));
    err = fiberpli::fomMaskThreshold(kind, this->MaskThreshold, largest, threshold);
    if (err.empty())
    {
      err =
        fiberpli::fomApplyMask(v, count, kind, threshold, fom->GetPointer(0), mask->GetPointer(0));
    }
    if (!err.empty())
    {
      fiberpliErrorMacro(<< "MaskThreshold " << this->MaskThreshold << ": " << err);
      output->Initialize();
      return 0;
    }
    output->GetPointData()->AddArray(mask);
    fiberpli::AddFieldDoubles(output, fiberpli::plifield::kMaskThreshold, { threshold });
  }
  output->GetPointData()->AddArray(fom);
  output->GetPointData()->SetActiveScalars(fiberpli::plifield::kFom);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkFiberOrientationMap::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "ColorScheme: "
     << fiberpli::fomSchemeName(
          this->ColorScheme == RGB ? fiberpli::FomScheme::Rgb : fiberpli::FomScheme::HsvBlack)
     << "\n";
  os << indent << "LegendSize: " << this->LegendSize << "\n";
  os << indent << "Mask: " << this->Mask << "\n";
  os << indent << "MaskThreshold: " << this->MaskThreshold << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
