#include "vtkFiberCollisionSolver.h"

#include "FiberFieldData.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
#include "Solver/CollisionSolver.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkFiberCollisionSolver);

// The states of one solve at steps 0, Δ, 2Δ, …, kept while input and properties are unchanged.
struct vtkFiberCollisionSolver::Snapshots
{
  vtkMTimeType inputTime = 0;
  vtkMTimeType filterTime = 0;
  std::vector<fiberpli::FiberModel> models; // snapshots, then the final state (result.sourceIndex)
  fiberpli::CollisionSolverResult result;
  fiberpli::FiberConversion input;
};


//------------------------------------------------------------------------------
// Construct with SegmentLength 2, MinCurvatureRadius 0 (off), MaxSteps 10000, SeparationSpeed
// 0.025, MinimumGap 0, all threads, IterationsAsTime off, TimeStepInterval 50.
vtkFiberCollisionSolver::vtkFiberCollisionSolver() = default;
vtkFiberCollisionSolver::~vtkFiberCollisionSolver() = default;

//------------------------------------------------------------------------------
int vtkFiberCollisionSolver::RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (this->IterationsAsTime) // otherwise the input's own time steps pass through
  {
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
    outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
    std::vector<double> times;
    for (int step = 0; step < this->MaxSteps; step += this->TimeStepInterval)
    {
      times.push_back(step);
    }
    times.push_back(this->MaxSteps);
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(), static_cast<int>(times.size()));
    const double range[2] = { 0.0, static_cast<double>(this->MaxSteps) };
    outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
  }
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberCollisionSolver::RequestData(vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
  if (!fiberpli::CheckThreads(this, "FiberCollisionSolver", this->NumberOfThreads))
  {
    return 0;
  }
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  output->Initialize();
  if (fiberpli::FiberPolyData::IsEmpty(input))
  {
    return 1;
  }

  const bool cached = this->Cache && this->Cache->inputTime == input->GetMTime() &&
    this->Cache->filterTime == this->GetMTime();
  if (!cached)
  {
    auto cache = std::make_unique<Snapshots>();
    cache->inputTime = input->GetMTime();
    cache->filterTime = this->GetMTime();
    cache->input = fiberpli::FiberPolyData::ToModel(input, "FiberCollisionSolver");
    if (!cache->input.ok())
    {
      vtkErrorMacro(<< cache->input.error);
      this->Cache.reset();
      return 0;
    }
    if (!cache->input.warning.empty())
    {
      vtkWarningMacro(<< cache->input.warning);
    }

    fiberpli::CollisionSolverOptions options;
    std::string cellError;
    if (!fiberpli::ReadPeriodicCell(input, options.periodicCell, cellError) && !cellError.empty())
    {
      vtkErrorMacro(<< "FiberCollisionSolver: input field data " << cellError);
      this->Cache.reset();
      return 0;
    }
    options.initialRadiusScale = this->InitialRadiusScale;
    options.segmentLength = this->SegmentLength;
    options.minCurvatureRadius = this->MinCurvatureRadius;
    options.maxSteps = this->MaxSteps;
    options.separationSpeed = this->SeparationSpeed;
    options.minimumGap = this->MinimumGap;
    options.numberOfThreads = this->NumberOfThreads;

    fiberpli::FiberModel model = cache->input.model;
    fiberpli::StepObserver observer;
    if (this->IterationsAsTime)
    {
      cache->models.push_back(model);
      const int interval = this->TimeStepInterval;
      observer = [&cache, interval](int step, const fiberpli::FiberModel& current) {
        if (step % interval == 0)
        {
          cache->models.push_back(current);
        }
      };
    }
    this->SetProgressText("Solving collisions");
    // Progress: the solver reports the fraction of MaxSteps; it usually ends much earlier.
    cache->result = fiberpli::solveCollisions(model, options, fiberpli::MakeProgress(this), observer);
    if (!cache->result.error.empty())
    {
      vtkErrorMacro(<< "FiberCollisionSolver: " << cache->result.error);
      this->Cache.reset();
      return 0;
    }
    if (cache->result.aborted)
    {
      this->Cache.reset();
      return 1; // partial results are never passed on
    }
    // One warning per kind; an unsolved model is among them, naming the collisions left.
    for (const std::string& w : cache->result.warnings)
    {
      vtkWarningMacro(<< "FiberCollisionSolver: " << w);
    }
    cache->models.push_back(std::move(model));
    this->Cache = std::move(cache);
  }

  // Which state to show: the last one, or the snapshot of the requested time step.
  std::size_t shown = this->Cache->models.size() - 1;
  int shownStep = this->Cache->result.steps;
  if (this->IterationsAsTime && outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
  {
    const double t = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
    const auto k = static_cast<std::size_t>(std::max(0.0, std::floor(t / this->TimeStepInterval + 1e-9)));
    // A snapshot strictly before the solver's last step; from there on, the final state.
    if (k < shown && static_cast<int>(k) * this->TimeStepInterval < this->Cache->result.steps)
    {
      shown = k;
      shownStep = static_cast<int>(k) * this->TimeStepInterval;
    }
    output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
  }

  const fiberpli::FiberModel& model = this->Cache->models[shown];
  const fiberpli::CollisionSolverResult& r = this->Cache->result;
  const bool final = shown + 1 == this->Cache->models.size();
  fiberpli::FiberPolyData::FromModel(model, output);
  // The final state knows where each point came from. Snapshots do not: their point arrays are
  // passed (unchanged points) only while no fiber has been split or merged yet.
  bool sameCounts = true;
  for (std::size_t f = 0; f < model.fibers.size() && sameCounts; ++f)
  {
    sameCounts = model.fibers[f].points.size() == this->Cache->input.sourcePoints[f].size();
  }
  if (final || sameCounts)
  {
    static const std::vector<std::vector<double>> unchanged;
    fiberpli::FiberPolyData::PassArrays(input, this->Cache->input, final ? r.sourceIndex : unchanged, output);
  }

  fiberpli::PeriodicCell cell;
  std::string cellError;
  const bool periodic = fiberpli::ReadPeriodicCell(input, cell, cellError);
  const std::size_t collisions = final ? r.collisions
                                       : fiberpli::countCollisions(model, this->MinimumGap, this->NumberOfThreads, cell);
  fiberpli::AddFieldInt(output, "steps", shownStep);
  fiberpli::AddFieldInt(output, "collisions", static_cast<int>(collisions));
  fiberpli::AddFieldInt(output, "solved", collisions == 0 ? 1 : 0);
  if (final) // only known for the solver's last state
  {
    fiberpli::AddFieldDoubles(output, "max_overlap", { r.maxOverlap });
    fiberpli::AddFieldInt(output, "shape_ok", r.shapeOk ? 1 : 0);
  }
  fiberpli::AddFieldDoubles(output, "segment_length", { r.segmentLength });
  if (periodic)
  {
    fiberpli::AddPeriodicCell(output, cell);
  }
  // Of the periodic cell, else of the model's bounding box.
  fiberpli::AddFieldDoubles(output, "volume_fraction", { fiberpli::cellVolumeFraction(model, cell) });
  if (final)
  {
    fiberpli::AddFieldDoubles(output, "min_gap", { r.minGap });
    fiberpli::AddFieldDoubles(output, "radius_scale", { r.radiusScale });
  }
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkFiberCollisionSolver::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "SegmentLength: " << this->SegmentLength << "\n";
  os << indent << "MinCurvatureRadius: " << this->MinCurvatureRadius << "\n";
  os << indent << "MaxSteps: " << this->MaxSteps << "\n";
  os << indent << "SeparationSpeed: " << this->SeparationSpeed << "\n";
  os << indent << "MinimumGap: " << this->MinimumGap << "\n";
  os << indent << "NumberOfThreads: " << this->NumberOfThreads << "\n";
  os << indent << "InitialRadiusScale: " << this->InitialRadiusScale << "\n";
  os << indent << "IterationsAsTime: " << this->IterationsAsTime << "\n";
  os << indent << "TimeStepInterval: " << this->TimeStepInterval << "\n";
}
