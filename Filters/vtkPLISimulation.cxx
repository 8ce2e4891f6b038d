#include "vtkPLISimulation.h"

#include "FiberAdapter.h"
#include "FiberCollective.h"
#include "FiberFieldData.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
#include "FiberTileExchange.h"
#include "Model/PeriodicTiling.h"
#include "Model/VolumeOfInterest.h"
#include "PLI/OptionLimits.h"
#include "PLI/PLIPipeline.h"
#include "PLI/PLIReach.h"
#include "PLI/TissueExport.h"
#include "PLIImage.h"
#include "Section/TiltConvention.h"

#include <vtkAlgorithmOutput.h>
#include <vtkDataObject.h>
#include <vtkExecutive.h>
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
#include <cstring>
#include <string>

vtkStandardNewMacro(vtkPLISimulation);

namespace
{
/// The Core options of the properties; "" or the error naming the property whose value the Core
/// options cannot hold (an enumeration code, a switch or a negative Seed).
std::string MakeOptions(vtkPLISimulation* self, fiberpli::pli::PLIOptions& o)
{
  o = fiberpli::pli::PLIOptions();
  std::string error = fiberpli::tiltConventionFromCode(self->GetTiltConvention(), o.tiltConvention);
  if (error.empty())
    error = fiberpli::pli::interpolationFromCode(self->GetInterpolation(), o.interpolation);
  bool exportTissue = false; // only checked here: the tissue port reads the property itself
  if (error.empty())
    error = fiberpli::switchFromCode(self->GetTiltedSensor(), "TiltedSensor", o.tiltedSensor);
  if (error.empty())
    error = fiberpli::switchFromCode(self->GetExportTissue(), "ExportTissue", exportTissue);
  if (error.empty())
    error = fiberpli::validateSeed(self->GetSeed());
  self->GetVolumeOfInterest(o.volumeOfInterest);
  o.voxelSize = self->GetVoxelSize();
  o.pixelSize = self->GetPixelSize();
  o.wavelength = self->GetWavelength();
  o.lightIntensity = self->GetLightIntensity();
  o.numberOfRotations = self->GetNumberOfRotations();
  for (int i = 0; i < self->GetNumberOfRotationAngles(); ++i)
  {
    o.rotationAngles.push_back(self->GetRotationAngle(i));
  }
  o.tiltAngle = self->GetTiltAngle();
  for (int i = 0; i < self->GetNumberOfTiltAngles(); ++i)
  {
    o.tiltAngles.push_back(self->GetTiltAngleValue(i));
  }
  for (int i = 0; i < self->GetNumberOfTiltAzimuths(); ++i)
  {
    o.tiltAzimuths.push_back(self->GetTiltAzimuth(i));
  }
  o.birefringence = self->GetBirefringence();
  o.absorption = self->GetAbsorption();
  o.seed = static_cast<std::uint64_t>(self->GetSeed());
  o.layers = self->GetLayers() ? self->GetLayers() : "";
  o.backgroundAbsorption = self->GetBackgroundAbsorption();
  o.stepSize = self->GetStepSize();
  o.opticalSigma = self->GetOpticalSigma();
  o.noiseGain = self->GetNoiseGain();
  o.refractiveIndex = self->GetRefractiveIndex();
  o.numberOfThreads = self->GetNumberOfThreads();
  return error;
}

/// Resizes a list property; returns true when the size changed. A count outside [0, max] is an
/// error (it used to allocate n doubles, 16 GB for 2^31 - 1): the list gets max + 1 entries, which
/// planPLI refuses by name, so the filter fails instead of running with a stale list.
bool ResizeList(vtkPLISimulation* self, std::vector<double>& list, int n, int max, const char* name)
{
  std::size_t size = static_cast<std::size_t>(std::max(0, n));
  if (n < 0 || n > max)
  {
    vtkErrorWithObjectMacro(self, << fiberpli::ProxyName(self) << ": " << name << " has " << n
                                  << " values, at most " << max << " are allowed");
    size = static_cast<std::size_t>(max) + 1;
  }
  if (list.size() == size)
  {
    return false;
  }
  list.resize(size, 0.0);
  return true;
}

/// Sets one value of a list property (out-of-range indices are ignored); true when it changed.
bool SetListValue(std::vector<double>& list, int i, double v)
{
  if (i < 0 || static_cast<std::size_t>(i) >= list.size() ||
    std::memcmp(&list[static_cast<std::size_t>(i)], &v, sizeof(double)) == 0)
  {
    return false;
  }
  list[static_cast<std::size_t>(i)] = v;
  return true;
}

double ListValue(const std::vector<double>& list, int i)
{
  return i >= 0 && static_cast<std::size_t>(i) < list.size() ? list[static_cast<std::size_t>(i)]
                                                             : 0.0;
}

/// The update extent of an output port inside its whole extent (false when nothing is left): a
/// failed run (e.g. a piece above the memory budget) leaves its update extent in the pipeline;
/// after the image shrank it may reach beyond the new whole extent.
bool RequestedExtent(vtkInformation* outInfo, int ext[6])
{
  int whole[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
  outInfo->Get(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole);
  for (int a = 0; a < 6; a += 2)
  {
    ext[a] = std::max(ext[a], whole[a]);
    ext[a + 1] = std::min(ext[a + 1], whole[a + 1]);
  }
  return ext[0] <= ext[1] && ext[2] <= ext[3] && ext[4] <= ext[5];
}

/// What this rank's piece reads (FiberTileExchange.h): the image tile and/or the tissue piece
/// requested, tiled modulo a periodic cell into the volume of interest as ExecutePiece tiles it.
std::string PieceReach(vtkPLISimulation* self, const fiberpli::TileFibers& whole,
  const fiberpli::pli::PLIOptions& options, const fiberpli::pli::PLIPlan& plan,
  vtkInformationVector* outputVector, bool image, bool tissue, const std::string& tissueError,
  fiberpli::TileReach& reach)
{
  int ext[6];
  if (image && RequestedExtent(outputVector->GetInformationObject(0), ext))
  {
    reach = fiberpli::pli::imageReach(
      plan, options, fiberpli::GridRange{ ext[0], ext[1] + 1, ext[2], ext[3] + 1 });
  }
  fiberpli::pli::VoxelBox box;
  if (tissue && self->GetExportTissue() && tissueError.empty() &&
    fiberpli::pli::tissueBox(plan, self->GetTissueVolume(), box).ok() &&
    RequestedExtent(outputVector->GetInformationObject(1), ext))
  {
    for (int a = 0; a < 3; ++a)
    {
      box.lo[a] = std::max<std::int64_t>(box.lo[a], ext[2 * a]);
      box.hi[a] = std::max(box.lo[a],
        std::min<std::int64_t>(box.hi[a], static_cast<std::int64_t>(ext[2 * a + 1]) + 1));
    }
    reach = fiberpli::unite(reach, fiberpli::pli::tissueReach(plan, box));
  }
  if (whole.periodic && whole.cellError.empty())
  {
    fiberpli::sectionTiling(reach, whole.cell, options.volumeOfInterest);
  }
  return {};
}

} // namespace

//------------------------------------------------------------------------------
/// The image part of the plan: made once per change of the properties or of the input's bounds
/// (sentinel), by RequestInformation, and used by every RequestData.
struct vtkPLISimulation::ImagePlan
{
  PlanStamp stamp;                   ///< the time and (resolved) volume the plan is for
  fiberpli::pli::PLIOptions options; ///< the properties, VolumeOfInterest resolved for the sentinel
  fiberpli::pli::PLIPlan plan;       ///< planPLIImage of the options
  std::string error;                 ///< the options' or the plan's error, reported by RequestData
  bool noFibers = false;             ///< the sentinel met a model without points: empty output
};

//------------------------------------------------------------------------------
vtkPLISimulation::vtkPLISimulation()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(2); // 0: the image stack, 1: the voxelised tissue (ExportTissue)
}

//------------------------------------------------------------------------------
vtkPLISimulation::~vtkPLISimulation()
{
  this->SetLayers(nullptr);
}

//------------------------------------------------------------------------------
// The list properties: ParaView sets the count first, then every value by index.
#define FIBERPLI_LIST_ACCESSORS(SetCount, SetValue, GetValue, list, max)                           \
  void vtkPLISimulation::SetCount(int n)                                                           \
  {                                                                                                \
    if (ResizeList(this, this->list, n, max, #list))                                               \
      this->Modified();                                                                            \
  }                                                                                                \
  void vtkPLISimulation::SetValue(int i, double v)                                                 \
  {                                                                                                \
    if (SetListValue(this->list, i, v))                                                            \
      this->Modified();                                                                            \
  }                                                                                                \
  double vtkPLISimulation::GetValue(int i) const                                                   \
  {                                                                                                \
    return ListValue(this->list, i);                                                               \
  }
FIBERPLI_LIST_ACCESSORS(SetNumberOfRotationAngles, SetRotationAngle, GetRotationAngle,
  RotationAngles, fiberpli::pli::kMaxRotationAngles)
FIBERPLI_LIST_ACCESSORS(SetNumberOfTiltAngles, SetTiltAngleValue, GetTiltAngleValue, TiltAngles,
  fiberpli::pli::kMaxTiltAngles)
FIBERPLI_LIST_ACCESSORS(SetNumberOfTiltAzimuths, SetTiltAzimuth, GetTiltAzimuth, TiltAzimuths,
  fiberpli::pli::kMaxTiltAzimuths)
#undef FIBERPLI_LIST_ACCESSORS

//------------------------------------------------------------------------------
int vtkPLISimulation::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  vtkInformation* tissueInfo = outputVector->GetInformationObject(1);
  this->TissueError.clear();
  const int empty[6] = { 0, -1, 0, -1, 0, -1 };
  for (vtkInformation* info : { outInfo, tissueInfo })
  {
    info->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), empty, 6);
    info->Set(vtkAlgorithm::CAN_PRODUCE_SUB_EXTENT(), 1);
  }

  this->PlanImage(inputVector[0]);
  if (!this->Plan->error.empty() || this->Plan->noFibers)
  {
    return 1; // the error is reported by RequestData
  }
  const fiberpli::pli::PLIOptions& options = this->Plan->options;
  const fiberpli::pli::PLIPlan& plan = this->Plan->plan;
  const int whole[6] = { 0, static_cast<int>(plan.pixels[0] - 1), 0,
    static_cast<int>(plan.pixels[1] - 1), 0, 0 };
  const double spacing[3] = { options.pixelSize, options.pixelSize, plan.thickness };
  outInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), whole, 6);
  outInfo->Set(vtkDataObject::SPACING(), spacing, 3);
  outInfo->Set(vtkDataObject::ORIGIN(), plan.imageOrigin, 3);
  vtkDataObject::SetPointDataActiveScalarInfo(
    outInfo, VTK_DOUBLE, static_cast<int>(plan.rho.size()));

  // The tissue port: voxel centres of TissueVolume on the simulation lattice (global indices). A
  // bad or oversized box shows as an empty extent here and as an error when the port is updated.
  fiberpli::pli::VoxelBox box;
  if (this->ExportTissue)
  {
    this->TissueError = fiberpli::pli::tissueBox(plan, this->TissueVolume, box).error;
    if (this->TissueError.empty())
    {
      this->TissueError = fiberpli::pli::checkTissueBudget(plan, options, box);
    }
  }
  if (this->ExportTissue && this->TissueError.empty())
  {
    const int tissueWhole[6] = { static_cast<int>(box.lo[0]), static_cast<int>(box.hi[0] - 1),
      static_cast<int>(box.lo[1]), static_cast<int>(box.hi[1] - 1), static_cast<int>(box.lo[2]),
      static_cast<int>(box.hi[2] - 1) };
    const double voxel = plan.lattice.voxel;
    const double tissueSpacing[3] = { voxel, voxel, voxel };
    const double tissueOrigin[3] = { plan.lattice.origin[0] + 0.5 * voxel,
      plan.lattice.origin[1] + 0.5 * voxel, plan.lattice.origin[2] + 0.5 * voxel };
    tissueInfo->Set(vtkStreamingDemandDrivenPipeline::WHOLE_EXTENT(), tissueWhole, 6);
    tissueInfo->Set(vtkDataObject::SPACING(), tissueSpacing, 3);
    tissueInfo->Set(vtkDataObject::ORIGIN(), tissueOrigin, 3);
  }
  return 1;
}

//------------------------------------------------------------------------------
void vtkPLISimulation::PlanImage(vtkInformationVector* inputVector)
{
  fiberpli::pli::PLIOptions options;
  std::string error = MakeOptions(this, options);
  error = error.empty() ? error : fiberpli::ProxyMessage(this, error);
  bool noFibers = false;
  if (error.empty()) // the same properties on every rank: all of them skip the bounds, or none
  {
    error = this->VolumeToPlan(inputVector, options.volumeOfInterest, noFibers);
  }
  if (error.empty() && !noFibers && this->Plan && this->Plan->error.empty() &&
    !this->Plan->noFibers && this->PlanHolds(this->Plan->stamp, options.volumeOfInterest))
  {
    return; // planned for these properties and this volume already
  }
  auto p = std::make_unique<ImagePlan>();
  p->stamp = this->StampFor(options.volumeOfInterest);
  p->options = options;
  p->error = error;
  p->noFibers = noFibers;
  if (error.empty() && !noFibers)
  {
    // RequestData uses this volume, so its pixels match WHOLE_EXTENT even if the fibers move later.
    const fiberpli::Status st =
      fiberpli::pli::planPLIImage(fiberpli::FiberModel(), options, p->plan);
    p->error = st.ok() ? "" : fiberpli::ProxyMessage(this, st.error);
  }
  this->Plan = std::move(p);
}

//------------------------------------------------------------------------------
vtkTypeBool vtkPLISimulation::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // A request on one port leaves the other port's data as it is (and not up to date), so showing
  // the tissue never re-runs the simulation and vice versa.
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_NOT_GENERATED()) &&
    request->Has(vtkExecutive::FROM_OUTPUT_PORT()))
  {
    const int port = request->Get(vtkExecutive::FROM_OUTPUT_PORT());
    for (int p = 0; p < this->GetNumberOfOutputPorts(); ++p)
    {
      if (port >= 0 && p != port)
      {
        outputVector->GetInformationObject(p)->Set(
          vtkDemandDrivenPipeline::DATA_NOT_GENERATED(), 1);
      }
    }
    return 1;
  }
  return this->Superclass::ProcessRequest(request, inputVector, outputVector);
}

//------------------------------------------------------------------------------
int vtkPLISimulation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
  // Under MPI all ranks fail together (FiberCollective.h): a rank-local failure would leave the
  // other ranks waiting downstream, e.g. in PLIAnalysis's reduction.
  return fiberpli::FiberCollective::RunCollectively(this, request, outputVector,
    fiberpli::ProxyName(this),
    [&] { return this->ExecutePiece(request, inputVector, outputVector); });
}

//------------------------------------------------------------------------------
int vtkPLISimulation::ExecutePiece(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Plan)
  {
    this->PlanImage(inputVector[0]); // a data pass without an information pass
  }
  const int port = request->Has(vtkExecutive::FROM_OUTPUT_PORT())
    ? request->Get(vtkExecutive::FROM_OUTPUT_PORT())
    : -1;
  if (port == 1 && !this->ExportTissue)
  {
    // The tissue port without ExportTissue computes nothing: an error of the properties is the
    // image port's to report (once, not again for every port an update asks for).
    vtkImageData::GetData(outputVector, 1)->Initialize();
    return 1;
  }
  std::string localError = this->Plan->error;
  if (!fiberpli::CheckThreads(this, this->NumberOfThreads))
  {
    localError = fiberpli::ProxyMessage(this, fiberpli::validateThreadCount(this->NumberOfThreads));
  }
  else if (!localError.empty())
  {
    vtkErrorMacro(<< localError);
  }
  const bool wantImage = port != 1;
  const bool wantTissue = port != 0;
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkImageData* image = vtkImageData::GetData(outputVector, 0);
  vtkImageData* tissue = vtkImageData::GetData(outputVector, 1);
  if (wantImage)
  {
    image->Initialize();
  }
  if (wantTissue)
  {
    tissue->Initialize();
  }
  // The plan of RequestInformation; the tissue part (layers of the whole model's bundles) is
  // planned once here, for the fibers' reach under MPI or else for the fibers received.
  fiberpli::pli::PLIOptions options = this->Plan->options;
  fiberpli::pli::PLIPlan plan = this->Plan->plan;
  fiberpli::Status tissueStatus;
  bool tissuePlanned = false;
  const bool work = wantImage || (wantTissue && this->ExportTissue);
  // Every rank takes part in the exchange, whatever its own state: under MPI it receives the
  // fibers its piece reads, in model order (FiberTileExchange.h).
  fiberpli::TileReach reach;
  fiberpli::TileFibers in = fiberpli::FiberTileExchange::Receive(
    outputVector->GetInformationObject(std::max(port, 0)), input, fiberpli::ProxyName(this),
    localError,
    [&](const fiberpli::TileFibers& whole, fiberpli::TileReach& r)
    {
      if (!work)
      {
        return std::string(); // this request computes nothing: no fiber is needed
      }
      options.bundleIds = whole.bundleIds;
      options.myelin = whole.myelinated;
      tissueStatus = fiberpli::pli::planPLITissue(fiberpli::FiberModel(), options, plan);
      tissuePlanned = true;
      if (!tissueStatus.ok())
      {
        return fiberpli::ProxyMessage(this, tissueStatus.error);
      }
      const std::string e = PieceReach(
        this, whole, options, plan, outputVector, wantImage, wantTissue, this->TissueError, r);
      reach = r;
      return e;
    },
    this->Fibers.get());
  if (!in.ok())
  {
    if (localError.empty())
    {
      vtkErrorMacro(<< in.error);
    }
    return 0;
  }
  if (!in.warning.empty())
  {
    vtkWarningMacro(<< in.warning);
  }
  if (in.emptyInput || this->Plan->noFibers || !work)
  {
    return 1;
  }
  // The layer table and labels of the whole model, also on a rank that holds some bundles only.
  options.bundleIds = in.bundleIds;
  options.myelin = in.myelinated; // the same layer table on every rank
  // A periodic cell (field data periodic_cell) owns its tissue modulo the cell: the volume of
  // interest is filled with the lattice translates of its fibers, so a larger one tiles the cell
  // (under MPI only the translates this rank's piece reads).
  std::string cellError = in.cellError;
  if (in.periodic && cellError.empty())
  {
    cellError = fiberpli::tileSection(
      in.model, in.cell, options.volumeOfInterest, in.distributed ? &reach : nullptr);
  }
  if (!cellError.empty())
  {
    fiberpliErrorMacro(<< cellError);
    return 0;
  }
  if (!tissuePlanned)
  {
    tissueStatus = fiberpli::pli::planPLITissue(in.model, options, plan);
  }
  else
  {
    const std::string w = fiberpli::pli::resolutionWarning(in.model, options);
    if (!w.empty())
    {
      tissueStatus.warnings.push_back(w);
    }
  }
  if (!tissueStatus.ok())
  {
    fiberpliErrorMacro(<< tissueStatus.error);
    return 0;
  }
  this->NumberOfTileFibers = static_cast<double>(in.model.fibers.size());
  this->NumberOfModelFibers = static_cast<double>(in.modelFibers);
  int ok = 1;
  // Whether the input claims to be collision-free decides a warning only: under MPI the rank that
  // holds the solver's piece decides for itself, no collective is needed.
  if (wantImage)
  {
    ok = this->SimulateImage(in.model, options, plan, tissueStatus.warnings,
      outputVector->GetInformationObject(0), image, fiberpli::ClaimsCollisionFree(input));
  }
  if (wantTissue && this->ExportTissue && ok)
  {
    ok =
      this->VoxeliseTissue(in.model, options, plan, outputVector->GetInformationObject(1), tissue);
  }
  return ok;
}

//------------------------------------------------------------------------------
int vtkPLISimulation::SimulateImage(const fiberpli::FiberModel& model,
  const fiberpli::pli::PLIOptions& options, const fiberpli::pli::PLIPlan& plan,
  const std::vector<std::string>& planWarnings, vtkInformation* outInfo, vtkImageData* output,
  bool claimsSolved)
{
  int ext[6];
  if (!RequestedExtent(outInfo, ext))
  {
    return 1;
  }
  const fiberpli::GridRange range{ ext[0], ext[1] + 1, ext[2], ext[3] + 1 };
  fiberpli::pli::PLIImage image;
  const fiberpli::ProgressFn vtkProgress = fiberpli::MakeProgress(this);
  bool inOptics = false;
  this->SetProgressText("Voxelising and propagating light");
  fiberpli::Status st = fiberpli::pli::runPLI(model, options, plan, range, image,
    [&](double f)
    {
      if (f >= 0.95 && !inOptics)
      {
        inOptics = true;
        this->SetProgressText("Optics: blur, binning, noise");
      }
      return vtkProgress(f);
    });
  if (!st.error.empty())
  {
    fiberpliErrorMacro(<< st.error);
    return 0;
  }
  // The plan's warnings first, as one runPLI call (planning and running) reports them.
  st.warnings.insert(st.warnings.begin(), planWarnings.begin(), planWarnings.end());
  // Overlapping fibers are what a model straight from a source or a file has before it is solved:
  // simulating it is a quick look the user chose (the nearest fiber owns a shared voxel), and the
  // solver or FiberMetrics count its collisions. It matters when the input says it is
  // collision-free: then something else (layers wider than the fibers, a later edit) overlaps.
  if (image.fibersOverlap && claimsSolved)
  {
    st.warnings.push_back(
      "fibers overlap although the input is collision-free (its field data collisions is 0): "
      "the nearest fiber owns the shared voxels (Layers scaled beyond the fiber radius?)");
  }
  if (!st.warnings.empty())
  {
    std::string text = "PLISimulation:";
    for (const std::string& w : st.warnings)
    {
      text += " " + w + ";";
    }
    vtkWarningMacro(<< text);
  }
  if (st.aborted)
  {
    return 1; // partial results are never passed on
  }

  const double spacing[3] = { options.pixelSize, options.pixelSize, plan.thickness };
  ext[4] = ext[5] = 0;
  output->SetExtent(ext);
  output->SetSpacing(spacing);
  output->SetOrigin(plan.imageOrigin);
  fiberpli::WritePliStack(
    image, plan, options, { this->NumberOfTileFibers, this->NumberOfModelFibers }, output);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
int vtkPLISimulation::VoxeliseTissue(const fiberpli::FiberModel& model,
  const fiberpli::pli::PLIOptions& options, const fiberpli::pli::PLIPlan& plan,
  vtkInformation* outInfo, vtkImageData* output)
{
  if (!this->TissueError.empty())
  {
    fiberpliErrorMacro(<< this->TissueError);
    return 0;
  }
  fiberpli::pli::VoxelBox box;
  fiberpli::Status st = fiberpli::pli::tissueBox(plan, this->TissueVolume, box);
  if (!st.ok())
  {
    fiberpliErrorMacro(<< st.error);
    return 0;
  }
  // This piece: the update extent (global voxel indices) inside the box.
  int ext[6];
  outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_EXTENT(), ext);
  fiberpli::pli::VoxelBox piece;
  for (int a = 0; a < 3; ++a)
  {
    piece.lo[a] = std::max<std::int64_t>(box.lo[a], ext[2 * a]);
    piece.hi[a] = std::min<std::int64_t>(box.hi[a], static_cast<std::int64_t>(ext[2 * a + 1]) + 1);
    if (piece.hi[a] <= piece.lo[a])
    {
      return 1; // an empty piece
    }
  }
  this->SetProgressText("Voxelising the tissue");
  fiberpli::pli::TissueVolume tv;
  st = fiberpli::pli::exportTissue(model, plan, options, piece, tv, fiberpli::MakeProgress(this));
  if (!st.error.empty())
  {
    fiberpliErrorMacro(<< st.error);
    return 0;
  }
  if (st.aborted)
  {
    return 1; // aborted: the port stays empty
  }
  const double voxel = plan.lattice.voxel;
  output->SetExtent(static_cast<int>(piece.lo[0]), static_cast<int>(piece.hi[0] - 1),
    static_cast<int>(piece.lo[1]), static_cast<int>(piece.hi[1] - 1), static_cast<int>(piece.lo[2]),
    static_cast<int>(piece.hi[2] - 1));
  output->SetSpacing(voxel, voxel, voxel);
  output->SetOrigin(plan.lattice.origin[0] + 0.5 * voxel, plan.lattice.origin[1] + 0.5 * voxel,
    plan.lattice.origin[2] + 0.5 * voxel);
  fiberpli::WritePliTissue(
    tv, plan, { this->NumberOfTileFibers, this->NumberOfModelFibers }, output);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkPLISimulation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Wavelength: " << this->Wavelength << "\n";
  os << indent << "LightIntensity: " << this->LightIntensity << "\n";
  os << indent << "NumberOfRotations: " << this->NumberOfRotations << "\n";
  auto list = [&os, indent](const char* name, const std::vector<double>& values)
  {
    os << indent << name << ":";
    for (double v : values)
    {
      os << " " << v;
    }
    os << "\n";
  };
  list("RotationAngles", this->RotationAngles);
  os << indent << "TiltAngle: " << this->TiltAngle << "\n";
  list("TiltAngles", this->TiltAngles);
  list("TiltAzimuths", this->TiltAzimuths);
  os << indent << "TiltConvention: " << this->TiltConvention << "\n";
  os << indent << "ExportTissue: " << this->ExportTissue << "\n";
  const double* t = this->TissueVolume;
  os << indent << "TissueVolume: " << t[0] << " " << t[1] << " " << t[2] << " " << t[3] << " "
     << t[4] << " " << t[5] << "\n";
  os << indent << "Birefringence: " << this->Birefringence << "\n";
  os << indent << "Absorption: " << this->Absorption << "\n";
  os << indent << "Seed: " << this->Seed << "\n";
  os << indent << "Layers: " << (this->Layers ? this->Layers : "") << "\n";
  os << indent << "BackgroundAbsorption: " << this->BackgroundAbsorption << "\n";
  os << indent << "StepSize: " << this->StepSize << "\n";
  os << indent << "Interpolation: " << this->Interpolation << "\n";
  os << indent << "OpticalSigma: " << this->OpticalSigma << "\n";
  os << indent << "NoiseGain: " << this->NoiseGain << "\n";
  os << indent << "RefractiveIndex: " << this->RefractiveIndex << "\n";
  os << indent << "TiltedSensor: " << this->TiltedSensor << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
}
