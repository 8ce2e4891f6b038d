#include "vtkFiberOrientationGroundTruth.h"

#include "Analysis/GroundTruth.h"
#include "FiberAdapter.h"
#include "FiberCollective.h"
#include "FiberFieldData.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
#include "FiberTileExchange.h"
#include "Model/PeriodicTiling.h"
#include "Model/VolumeOfInterest.h"
#include "PLIImage.h"
#include "Section/SectionPlan.h"

#include <vtkAlgorithmOutput.h>
#include <vtkImageData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>
#include <sstream>

vtkStandardNewMacro(vtkFiberOrientationGroundTruth);

//------------------------------------------------------------------------------
/// The section of the properties and the planned volume, made by RequestInformation once per change
/// of either and used by every RequestData.
struct vtkFiberOrientationGroundTruth::SectionPlanned
{
  PlanStamp stamp;
  fiberpli::SectionPlan section;
  std::string error; ///< of planSection
};

//------------------------------------------------------------------------------
// Construct with the section of vtkFiberSectionAlgorithm and all threads.
vtkFiberOrientationGroundTruth::vtkFiberOrientationGroundTruth() = default;
vtkFiberOrientationGroundTruth::~vtkFiberOrientationGroundTruth() = default;

//------------------------------------------------------------------------------
int vtkFiberOrientationGroundTruth::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  int extent[6] = { 0, -1, 0, -1, 0, -1 };
  double origin[3] = { 0, 0, 0 };
  bool noFibers = false; // the sentinel then stays the volume, and planSection names it
  const std::string error = this->VolumeToPlan(inputVector[0], this->PlannedVolume, noFibers);
  this->PlanSection();
  const fiberpli::SectionPlan& section = this->Plan->section;
  if (error.empty() && this->Plan->error.empty()) // errors are reported by RequestData
  {
    extent[1] = static_cast<int>(section.pixels[0] - 1),
    extent[3] = static_cast<int>(section.pixels[1] - 1), extent[5] = 0;
    std::copy(section.imageOrigin, section.imageOrigin + 3, origin);
  }
  const double spacing[3] = { this->PixelSize, this->PixelSize, this->PixelSize };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), extent, 6);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), origin, 3);
  outInfo->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  vtkDataObject::SetPointDataActiveScalarInfo(outInfo, VTK_DOUBLE, 1);
  return 1;
}

//------------------------------------------------------------------------------
void vtkFiberOrientationGroundTruth::PlanSection()
{
  if (this->Plan && this->PlanHolds(this->Plan->stamp, this->PlannedVolume))
  {
    return; // planned for these properties and this volume already
  }
  auto p = std::make_unique<SectionPlanned>();
  p->stamp = this->StampFor(this->PlannedVolume);
  p->error = fiberpli::planSection(
    fiberpli::FiberModel(), this->PlannedVolume, this->VoxelSize, this->PixelSize, p->section);
  this->Plan = std::move(p);
}

//------------------------------------------------------------------------------
int vtkFiberOrientationGroundTruth::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
  // Under MPI all ranks fail together (FiberCollective.h).
  return fiberpli::FiberCollective::RunCollectively(this, request, outputVector,
    fiberpli::ProxyName(this), [&] { return this->ExecutePiece(inputVector, outputVector); });
}

//------------------------------------------------------------------------------
int vtkFiberOrientationGroundTruth::ExecutePiece(
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  std::string localError;
  if (!fiberpli::CheckThreads(this, this->NumberOfThreads))
  {
    localError = fiberpli::ProxyMessage(this, fiberpli::validateThreadCount(this->NumberOfThreads));
  }
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkImageData* output = vtkImageData::GetData(outputVector);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  output->Initialize();
  fiberpli::GroundTruthOptions options;
  options.threads = this->NumberOfThreads;
  // The section RequestInformation planned and this piece's pixels (an empty range when nothing of
  // the image is requested).
  if (!this->Plan)
  {
    this->PlanSection(); // a data pass without an information pass
  }
  const fiberpli::SectionPlan& section = this->Plan->section;
  auto pieceRange = [&](fiberpli::GridRange& range)
  {
    const std::string& e = this->Plan->error;
    range = fiberpli::GridRange{ 0, section.pixels[0], 0, section.pixels[1] };
    if (outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT()))
    {
      int u[6];
      outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), u);
      range = fiberpli::GridRange{ std::max<std::int64_t>(0, u[0]),
        std::min<std::int64_t>(range.i1, u[1] + 1), std::max<std::int64_t>(0, u[2]),
        std::min<std::int64_t>(range.j1, u[3] + 1) };
    }
    return e.empty() ? e : fiberpli::ProxyMessage(this, e);
  };
  // Every rank takes part in the exchange, whatever its own state: under MPI it receives the
  // fibers its pixels read, in model order (FiberTileExchange.h).
  // A periodic cell is tiled into the volume of interest as PLISimulation tiles it (one rule,
  // Model/PeriodicTiling.h), so both see the same tissue pixel by pixel.
  const double* volume = this->Plan->stamp.volume;
  fiberpli::TileReach pieceReach;
  fiberpli::TileFibers c = fiberpli::FiberTileExchange::Receive(
    outInfo, input, fiberpli::ProxyName(this), localError,
    [&](const fiberpli::TileFibers& whole, fiberpli::TileReach& reach)
    {
      fiberpli::GridRange range;
      const std::string e = pieceRange(range);
      if (e.empty() && range.nx() > 0 && range.ny() > 0)
      {
        reach = fiberpli::groundTruthReach(section, options, range);
      }
      if (whole.periodic && whole.cellError.empty())
      {
        fiberpli::sectionTiling(reach, whole.cell, volume);
      }
      pieceReach = reach;
      return e;
    },
    this->Fibers.get());
  if (!c.ok())
  {
    if (localError.empty())
    {
      vtkErrorMacro(<< c.error);
    }
    return 0;
  }
  if (!c.warning.empty())
  {
    vtkWarningMacro(<< c.warning);
  }
  if (c.emptyInput)
  {
    return 1;
  }
  std::string cellError = c.cellError;
  if (c.periodic && cellError.empty())
  {
    cellError =
      fiberpli::tileSection(c.model, c.cell, volume, c.distributed ? &pieceReach : nullptr);
  }
  if (!cellError.empty())
  {
    fiberpliErrorMacro(<< cellError);
    return 0;
  }
  fiberpli::GridRange range;
  std::string err = pieceRange(range);
  const std::int64_t nx = section.pixels[0];
  if (!err.empty())
  {
    vtkErrorMacro(<< err);
    return 0;
  }
  if (range.nx() <= 0 || range.ny() <= 0)
  {
    return 1; // nothing of the image requested
  }
  int ext[6] = { static_cast<int>(range.i0), static_cast<int>(range.i1 - 1),
    static_cast<int>(range.j0), static_cast<int>(range.j1 - 1), 0, 0 };
  fiberpli::GroundTruthMaps maps;
  this->SetProgressText("Fiber orientation ground truth");
  const fiberpli::Status status = fiberpli::computeGroundTruth(
    c.model, section, options, range, maps, fiberpli::MakeProgress(this));
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
  output->SetOrigin(section.imageOrigin);
  output->SetSpacing(this->PixelSize, this->PixelSize, this->PixelSize);
  fiberpli::WriteGroundTruthMaps(maps, nx, range,
    { static_cast<double>(c.model.fibers.size()), static_cast<double>(c.modelFibers) }, output);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkFiberOrientationGroundTruth::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
