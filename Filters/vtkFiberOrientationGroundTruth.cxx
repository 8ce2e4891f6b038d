#include "vtkFiberOrientationGroundTruth.h"

#include "Analysis/GroundTruth.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
#include "Model/VolumeOfInterest.h"
#include "Section/SectionPlan.h"

#include <vtkAlgorithmOutput.h>
#include <vtkDoubleArray.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkFiberOrientationGroundTruth);

namespace
{
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

} // namespace

//------------------------------------------------------------------------------
// Construct with VolumeOfInterest 1 −1 1 −1 1 −1 (input bounds), VoxelSize 0.5, PixelSize 2,
// all threads.
vtkFiberOrientationGroundTruth::vtkFiberOrientationGroundTruth() = default;

//------------------------------------------------------------------------------
int vtkFiberOrientationGroundTruth::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberOrientationGroundTruth::RequestInformation(vtkInformation*, vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  // The image size depends on the fibers' bounds (VolumeOfInterest sentinel), so the fibers are
  // brought up to date here; RequestUpdateExtent then asks for the same piece 0 of 1.
  const bool sentinel = fiberpli::isBoundsSentinel(this->VolumeOfInterest);
  if (sentinel && this->GetNumberOfInputConnections(0) > 0)
  {
    fiberpli::FiberPolyData::UpdateAllFibers(this, inputVector[0]->GetInformationObject(0));
  }
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  int extent[6] = { 0, -1, 0, -1, 0, -1 };
  double origin[3] = { 0, 0, 0 };
  {
    // An explicit VolumeOfInterest does not need the fibers; the sentinel needs their bounds.
    fiberpli::FiberConversion c;
    if (sentinel && input && !fiberpli::FiberPolyData::IsEmpty(input))
    {
      c = fiberpli::FiberPolyData::ToModel(input, "FiberOrientationGroundTruth");
    }
    fiberpli::SectionPlan section;
    std::copy(this->VolumeOfInterest, this->VolumeOfInterest + 6, this->PlannedVolume);
    fiberpli::Vec3 lo, hi;
    if (sentinel && c.ok() && fiberpli::modelBounds(c.model, true, lo, hi))
    {
      const double bounds[6] = { lo.x, hi.x, lo.y, hi.y, lo.z, hi.z };
      std::copy(bounds, bounds + 6, this->PlannedVolume);
    }
    if (c.ok() && fiberpli::planSection(c.model, this->PlannedVolume, this->VoxelSize, this->PixelSize, section).empty())
    {
      extent[1] = static_cast<int>(section.pixels[0] - 1), extent[3] = static_cast<int>(section.pixels[1] - 1), extent[5] = 0;
      std::copy(section.imageOrigin, section.imageOrigin + 3, origin);
    }
  } // errors are reported by RequestData
  const double spacing[3] = { this->PixelSize, this->PixelSize, this->PixelSize };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_DOUBLE, 1);
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberOrientationGroundTruth::RequestUpdateExtent(vtkInformation*, vtkInformationVector** inputVector,
  vtkInformationVector*)
{
  fiberpli::FiberPolyData::RequestAllFibers(inputVector[0]->GetInformationObject(0));
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberOrientationGroundTruth::RequestData(vtkInformation*, vtkInformationVector** inputVector,
  vtkInformationVector* outputVector)
{
  const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
  if (!fiberpli::CheckThreads(this, "FiberOrientationGroundTruth", this->NumberOfThreads))
  {
    return 0;
  }
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  output->Initialize();
  if (!input || fiberpli::FiberPolyData::IsEmpty(input))
  {
    return 1;
  }
  const fiberpli::FiberConversion c = fiberpli::FiberPolyData::ToModel(input, "FiberOrientationGroundTruth");
  if (!c.ok())
  {
    vtkErrorMacro(<< c.error);
    return 0;
  }
  if (!c.warning.empty())
  {
    vtkWarningMacro(<< c.warning);
  }
  fiberpli::SectionPlan section;
  std::string err = fiberpli::planSection(c.model, this->PlannedVolume, this->VoxelSize, this->PixelSize, section);
  const std::int64_t nx = section.pixels[0], ny = section.pixels[1];
  if (!err.empty())
  {
    vtkErrorMacro(<< "FiberOrientationGroundTruth: " << err);
    return 0;
  }
  int ext[6] = { 0, static_cast<int>(nx - 1), 0, static_cast<int>(ny - 1), 0, 0 };
  if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
  {
    int u[6];
    outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), u);
    for (int a = 0; a < 2; ++a)
    {
      ext[2 * a] = std::max(ext[2 * a], u[2 * a]);
      ext[2 * a + 1] = std::min(ext[2 * a + 1], u[2 * a + 1]);
    }
  }
  if (ext[1] < ext[0] || ext[3] < ext[2])
  {
    return 1; // nothing of the image requested
  }
  const fiberpli::PixelRange range{ ext[0], ext[1] + 1, ext[2], ext[3] + 1 };
  fiberpli::GroundTruthOptions options;
  options.threads = this->NumberOfThreads;
  fiberpli::GroundTruthMaps maps;
  this->SetProgressText("Fiber orientation ground truth");
  err = fiberpli::computeGroundTruth(c.model, section, options, range, maps, fiberpli::MakeProgress(this));
  if (err == "cancelled")
  {
    return 1;
  }
  if (!err.empty())
  {
    vtkErrorMacro(<< "FiberOrientationGroundTruth: " << err);
    return 0;
  }

  output->SetExtent(ext);
  output->SetOrigin(section.imageOrigin);
  output->SetSpacing(this->PixelSize, this->PixelSize, this->PixelSize);
  auto addMap = [&](const char* name, const std::vector<double>& map, double scale) {
    vtkNew<vtkDoubleArray> a;
    a->SetName(name);
    a->SetNumberOfValues(static_cast<vtkIdType>(range.count()));
    vtkIdType k = 0;
    for (std::int64_t j = range.j0; j < range.j1; ++j)
    {
      for (std::int64_t i = range.i0; i < range.i1; ++i)
      {
        a->SetValue(k++, map[static_cast<std::size_t>(i + nx * j)] * scale);
      }
    }
    output->GetPointData()->AddArray(a);
  };
  addMap("direction", maps.direction, kRadToDeg);
  addMap("inclination", maps.inclination, kRadToDeg);
  addMap("inclination_signed", maps.inclinationSigned, kRadToDeg);
  addMap("fraction", maps.fraction, 1.0);
  addMap("anisotropy", maps.anisotropy, 1.0);
  output->GetPointData()->SetActiveScalars("direction");
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkFiberOrientationGroundTruth::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "VolumeOfInterest:";
  for (double v : this->VolumeOfInterest)
  {
    os << " " << v;
  }
  os << "\n" << indent << "VoxelSize: " << this->VoxelSize << "\n";
  os << indent << "PixelSize: " << this->PixelSize << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
