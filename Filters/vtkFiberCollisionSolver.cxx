#include "vtkFiberCollisionSolver.h"

#include "Checkpoint/SolverCheckpoint.h"
#include "FiberAdapter.h"
#include "FiberCollective.h"
#include "FiberFieldData.h"
#include "FiberGuard.h"
#include "FiberPolyData.h"
#include "FiberProgress.h"
#include "FiberSolverComm.h"
#include "Parallel/Collectives.h"
#include "Solver/CollisionSolver.h"
#include "Solver/SolverSnapshots.h"
#include "Solver/TortuosityHold.h"
#include "Util/MemoryBudget.h"
#include "Util/ValueCheck.h"

#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkMultiProcessController.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>
#include <vector>

vtkStandardNewMacro(vtkFiberCollisionSolver);

namespace
{
bool FirstPiece(vtkInformation* outInfo)
{
  return fiberpli::FiberPolyData::RequestedPiece(outInfo) == 0;
}
} // namespace

// The states of one solve (fiberpli::SolverSnapshots: the final state alone, or with
// IterationsAsTime the snapshots of evenly spaced steps too) and its result; kept while input and
// properties are unchanged.
struct vtkFiberCollisionSolver::Snapshots
{
  vtkMTimeType inputTime = 0;
  vtkMTimeType filterTime = 0;
  fiberpli::SolverSnapshots states; // the last one is the final state (result.sourceIndex)
  fiberpli::CollisionSolverResult result;
  fiberpli::FiberConversion input;
  fiberpli::PeriodicCell cell; // the input's periodic_cell (off without one)
  bool periodic = false;
  std::string error; // non-empty: this input and these properties cannot be solved
};

//------------------------------------------------------------------------------
// Construct with SegmentLength 2, MinCurvatureRadius 0 (off), MaxSteps 10000, SeparationSpeed
// 0.025, MinimumGap 0, all threads, IterationsAsTime off, TimeStepInterval 50.
vtkFiberCollisionSolver::vtkFiberCollisionSolver() = default;
vtkFiberCollisionSolver::~vtkFiberCollisionSolver() = default;

//------------------------------------------------------------------------------
int vtkFiberCollisionSolver::RequestInformation(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Any exception escaping the work becomes a VTK error (FiberGuard.h), never an abort.
  return fiberpli::GuardRequest(this, nullptr, fiberpli::ProxyName(this),
    [&]() -> int
    {
      vtkInformation* outInfo = outputVector->GetInformationObject(0);
      if (!this->IterationsAsTime) // the input's own time steps pass through
      {
        return 1;
      }
      outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_STEPS());
      outInfo->Remove(vtkStreamingDemandDrivenPipeline::TIME_RANGE());
      // The time steps are the steps the solve really took, so the solve runs here (once, cached):
      // the timeline then ends where the solve ended instead of at MaxSteps.
      vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
      fiberpli::FiberPolyData::UpdateAllFibers(this, inInfo);
      vtkPolyData* input = inInfo ? vtkPolyData::GetData(inInfo) : nullptr;
      if (fiberpli::FiberPolyData::IsEmpty(input))
      {
        return 1;
      }
      if (this->Solve(input) != 1)
      {
        return 1; // an error is reported (again by RequestData, which makes no output); or aborted
      }
      const std::vector<int>& steps = this->Cache->states.steps;
      std::vector<double> times(steps.begin(), steps.end());
      outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_STEPS(), times.data(),
        static_cast<int>(times.size()));
      const double range[2] = { times.front(), times.back() };
      outInfo->Set(vtkStreamingDemandDrivenPipeline::TIME_RANGE(), range, 2);
      return 1;
    });
}

//------------------------------------------------------------------------------
vtkMultiProcessController* vtkFiberCollisionSolver::Distributed(vtkInformation* outInfo) const
{
  return this->IterationsAsTime ? nullptr : fiberpli::FiberCollective::ControllerFor(outInfo);
}

//------------------------------------------------------------------------------
// Distributed (docs/solver.md §13): every rank asks for its own piece and solves it with the
// others. Else (one process, or IterationsAsTime, whose snapshots are not distributed) every piece
// asks for all fibers (piece 0 of 1, as the other filters that need them whole; the same request
// on every rank, so a piece-making source sees no half-collective update), piece 0 solves them,
// the other pieces are empty (docs/architecture.md §7).
int vtkFiberCollisionSolver::RequestUpdateExtent(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInformation* inInfo = inputVector[0]->GetInformationObject(0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  if (!this->Distributed(outInfo))
  {
    fiberpli::FiberPolyData::RequestAllFibers(inInfo);
    return 1;
  }
  using SDDP = vtkStreamingDemandDrivenPipeline;
  inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), outInfo->Get(SDDP::UPDATE_PIECE_NUMBER()));
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES()));
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0); // the solver exchanges its own halo
  return 1;
}

//------------------------------------------------------------------------------
int vtkFiberCollisionSolver::Solve(vtkPolyData* input, fiberpli::Comm* comm)
{
  bool stale = !this->Cache || this->Cache->inputTime != input->GetMTime() ||
    this->Cache->filterTime != this->GetMTime();
  if (comm)
  {
    stale = fiberpli::anyRank(*comm, stale); // a distributed solve is redone by all ranks or none
  }
  if (stale)
  {
    auto cache = std::make_unique<Snapshots>();
    cache->inputTime = input->GetMTime();
    cache->filterTime = this->GetMTime();
    cache->error = this->SolveInto(input, *cache, comm);
    this->Cache.reset();
    if (cache->result.aborted)
    {
      return -1; // partial results are never passed on, nor kept
    }
    this->Cache = std::move(cache);
  }
  if (!this->Cache->error.empty())
  {
    vtkErrorMacro(<< this->Cache->error);
    return 0;
  }
  return 1;
}

//------------------------------------------------------------------------------
std::string vtkFiberCollisionSolver::SolveInto(
  vtkPolyData* input, Snapshots& cache, fiberpli::Comm* comm)
{
  fiberpli::CollisionSolverOptions options;
  std::string error = this->CheckInput(input, cache, options);
  if (comm)
  {
    // Every rank solves with the same options: a piece without fibers may lack periodic_cell.
    std::vector<double> c(7, -HUGE_VAL);
    c[0] = cache.periodic ? 1.0 : 0.0;
    for (int d = 0; cache.periodic && d < 3; ++d)
    {
      c[static_cast<std::size_t>(1 + d)] = -cache.cell.lo[d];
      c[static_cast<std::size_t>(4 + d)] = cache.cell.hi[d];
    }
    comm->max(c);
    fiberpli::PeriodicCell agreed;
    for (int d = 0; d < 3; ++d)
    {
      agreed.lo[d] = -c[static_cast<std::size_t>(1 + d)];
      agreed.hi[d] = c[static_cast<std::size_t>(4 + d)];
    }
    if (error.empty() && c[0] > 0.0 && cache.periodic &&
      !(agreed.lo == cache.cell.lo && agreed.hi == cache.cell.hi))
    {
      error =
        fiberpli::ProxyMessage(this, "the input pieces have different periodic_cell field data");
    }
    if (c[0] > 0.0)
    {
      cache.periodic = true;
      cache.cell = agreed;
      options.periodicCell = agreed;
    }
    error = fiberpli::agreeOnError(*comm, error);
  }
  if (!error.empty())
  {
    return error;
  }
  return this->RunSolve(cache, options, comm);
}

//------------------------------------------------------------------------------
std::string vtkFiberCollisionSolver::CheckInput(
  vtkPolyData* input, Snapshots& cache, fiberpli::CollisionSolverOptions& options)
{
  const std::string threads = fiberpli::validateThreadCount(this->NumberOfThreads);
  if (!threads.empty())
  {
    return fiberpli::ProxyMessage(this, threads);
  }
  const std::string threadWarning = fiberpli::threadCountWarning(this->NumberOfThreads);
  if (!threadWarning.empty())
  {
    fiberpliWarningMacro(<< threadWarning);
  }
  if (this->HoldTortuosity &&
    (this->IterationsAsTime || this->CheckpointInterval > 0 || this->ResumeFromCheckpoint))
  {
    return fiberpli::ProxyMessage(this,
      "HoldTortuosity solves again from the input until the tortuosity is held, so it cannot be "
      "combined with IterationsAsTime, CheckpointInterval " +
        std::to_string(this->CheckpointInterval) + " or ResumeFromCheckpoint; turn those off");
  }
  if (this->IterationsAsTime)
  {
    const std::string badSnapshots = fiberpli::ValueChecks()
                                       .atLeast("TimeStepInterval", this->TimeStepInterval, 1)
                                       .atLeast("MaximumSnapshots", this->MaximumSnapshots, 2)
                                       .error();
    if (!badSnapshots.empty())
    {
      return fiberpli::ProxyMessage(this, badSnapshots);
    }
  }
  cache.input = fiberpli::FiberPolyData::ToModel(input, fiberpli::ProxyName(this));
  if (!cache.input.ok())
  {
    return cache.input.error;
  }
  if (!cache.input.warning.empty())
  {
    vtkWarningMacro(<< cache.input.warning);
  }

  std::string cellError;
  cache.periodic = fiberpli::ReadPeriodicCell(input, cache.cell, cellError);
  if (!cache.periodic && !cellError.empty())
  {
    return fiberpli::ProxyMessage(this, "input field data " + cellError);
  }
  options.periodicCell = cache.cell;
  options.initialRadiusScale = this->InitialRadiusScale;
  options.pushBoost = this->PushBoost;
  options.drag = this->Drag;
  options.dragSteps = this->DragSteps;
  options.maxDisplacement = this->MaxDisplacement;
  options.tortuosity = this->Tortuosity;
  options.tortuosityWavelength = this->TortuosityWavelength;
  options.holdTortuosity = this->HoldTortuosity;
  options.keepBeads = this->KeepBeads;
  options.segmentLength = this->SegmentLength;
  options.minCurvatureRadius = this->MinCurvatureRadius;
  options.maxSteps = this->MaxSteps;
  options.separationSpeed = this->SeparationSpeed;
  options.minimumGap = this->MinimumGap;
  options.numberOfThreads = this->NumberOfThreads;
  if (this->IterationsAsTime)
  {
    // Snapshots of twice the input's points each (splitting) must fit the memory budget.
    const double points = static_cast<double>(cache.input.model.numberOfPoints());
    const double bytes = 2.0 * static_cast<double>(this->MaximumSnapshots) * points *
      (sizeof(fiberpli::Vec3) + sizeof(double));
    const std::string problem = fiberpli::checkMemoryBudget(bytes,
      "MaximumSnapshots " + std::to_string(this->MaximumSnapshots) + " of " +
        std::to_string(cache.input.model.numberOfPoints()) + " points");
    if (!problem.empty())
    {
      return fiberpli::ProxyMessage(this, problem + "; lower MaximumSnapshots");
    }
  }
  return {};
}

//------------------------------------------------------------------------------
std::string vtkFiberCollisionSolver::RunSolve(
  Snapshots& cache, const fiberpli::CollisionSolverOptions& options, fiberpli::Comm* comm)
{
  fiberpli::FiberModel model = cache.input.model;
  fiberpli::StepObserver observer;
  if (this->IterationsAsTime)
  {
    cache.states.start(
      model, this->TimeStepInterval, static_cast<std::size_t>(this->MaximumSnapshots));
    observer = [&cache](int step, const fiberpli::FiberModel& current)
    { cache.states.observe(step, current); };
  }
  this->SetProgressText("Solving collisions");
  // Progress: the larger of the steps' share of MaxSteps and the collisions resolved (solver).
  const fiberpli::CheckpointOptions checkpoint{ this->CheckpointFile, this->CheckpointInterval,
    this->ResumeFromCheckpoint };
  // A hold solves again from the input (Solver/TortuosityHold.h): no checkpoints or snapshots.
  cache.result = options.holdTortuosity
    ? fiberpli::solveHoldingTortuosity(model, options, fiberpli::MakeProgress(this), comm)
    : fiberpli::solveWithCheckpoints(
        model, options, checkpoint, fiberpli::MakeProgress(this), observer, comm);
  if (!cache.result.error.empty())
  {
    return fiberpli::ProxyMessage(this, cache.result.error);
  }
  if (cache.result.aborted)
  {
    return {};
  }
  // One warning per kind; an unsolved model is among them, naming the collisions left.
  for (const std::string& w : cache.result.warnings)
  {
    fiberpliWarningMacro(<< w);
  }
  cache.states.finish(std::move(model), cache.result.steps);
  return {};
}

//------------------------------------------------------------------------------
int vtkFiberCollisionSolver::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  // Any exception escaping the work becomes a VTK error (FiberGuard.h), never an abort.
  return fiberpli::GuardRequest(this, outputVector, fiberpli::ProxyName(this),
    [&]() -> int
    {
      const fiberpli::AbortScope abortScope(this); // an abort applies to this execution only
      vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
      vtkPolyData* output = vtkPolyData::GetData(outputVector);
      vtkInformation* outInfo = outputVector->GetInformationObject(0);
      output->Initialize();
      vtkMultiProcessController* controller = this->Distributed(outInfo);
      std::unique_ptr<fiberpli::FiberSolverComm> comm;
      if (controller)
      {
        comm = std::make_unique<fiberpli::FiberSolverComm>(controller);
        if (!fiberpli::anyRank(*comm, !fiberpli::FiberPolyData::IsEmpty(input)))
        {
          return 1; // no rank has fibers
        }
      }
      else if (fiberpli::FiberPolyData::IsEmpty(input) || !FirstPiece(outInfo))
      {
        return 1;
      }

      const int solved = this->Solve(input, comm.get());
      if (solved != 1)
      {
        return solved < 0 ? 1 : 0; // aborted: no output and no error; an error is reported
      }

      // Which state to show: the last one, or the last snapshot at or before the requested time.
      const fiberpli::SolverSnapshots& states = this->Cache->states;
      std::size_t shown = states.models.size() - 1;
      if (this->IterationsAsTime &&
        outInfo->Has(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP()))
      {
        const double t = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_TIME_STEP());
        shown = states.atTime(t);
        output->GetInformation()->Set(vtkDataObject::DATA_TIME_STEP(), t);
      }
      const int shownStep =
        this->IterationsAsTime ? states.steps[shown] : this->Cache->result.steps;

      const fiberpli::FiberModel& model = states.models[shown];
      const fiberpli::CollisionSolverResult& r = this->Cache->result;
      const bool final = shown + 1 == states.models.size();
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
        fiberpli::FiberPolyData::PassArrays(
          input, this->Cache->input, final ? r.sourceIndex : unchanged, output);
      }

      const fiberpli::PeriodicCell& cell = this->Cache->cell;
      const std::size_t collisions = final
        ? r.collisions
        : fiberpli::countCollisions(model, this->MinimumGap, this->NumberOfThreads, cell);
      fiberpli::AddFieldInt(output, fiberpli::fiberfield::kSteps, shownStep);
      fiberpli::AddFieldInt(
        output, fiberpli::fiberfield::kCollisions, static_cast<int>(collisions));
      fiberpli::AddFieldInt(output, fiberpli::fiberfield::kSolved, collisions == 0 ? 1 : 0);
      if (final) // only known for the solver's last state
      {
        fiberpli::AddFieldDoubles(output, fiberpli::fiberfield::kMaxOverlap, { r.maxOverlap });
        fiberpli::AddFieldInt(output, fiberpli::fiberfield::kShapeOk, r.shapeOk ? 1 : 0);
      }
      fiberpli::AddFieldDoubles(output, fiberpli::fiberfield::kSegmentLength, { r.segmentLength });
      if (this->Cache->periodic)
      {
        fiberpli::AddPeriodicCell(output, cell);
      }
      // Of the periodic cell, else of the model's bounding box.
      fiberpli::AddFieldDoubles(output, fiberpli::fiberfield::kVolumeFraction,
        { fiberpli::cellVolumeFraction(model, cell, comm.get()) });
      if (final)
      {
        fiberpli::AddFieldDoubles(output, fiberpli::fiberfield::kMinGap, { r.minGap });
        fiberpli::AddFieldDoubles(output, fiberpli::fiberfield::kRadiusScale, { r.radiusScale });
        if (r.tortuositySolves > 0)
        {
          fiberpli::AddFieldInt(
            output, fiberpli::fiberfield::kTortuositySolves, r.tortuositySolves);
        }
      }
      if (comm) // this rank's share of the distributed solve (docs/solver.md §13)
      {
        fiberpli::AddFieldDoubles(
          output, fiberpli::fiberfield::kRankPoints, { static_cast<double>(r.peakRankPoints) });
        fiberpli::AddFieldDoubles(
          output, fiberpli::fiberfield::kHaloLinks, { static_cast<double>(r.peakHaloLinks) });
        fiberpli::AddFieldDoubles(
          output, fiberpli::fiberfield::kHeldLinks, { static_cast<double>(r.peakHeldLinks) });
        fiberpli::AddFieldDoubles(
          output, fiberpli::fiberfield::kHaloBytesPerStep, { r.haloBytesPerStep });
        fiberpli::AddFieldDoubles(
          output, fiberpli::fiberfield::kMigrations, { static_cast<double>(r.migrations) });
        fiberpli::AddFieldDoubles(
          output, fiberpli::fiberfield::kTesterRecuts, { static_cast<double>(r.testerRecuts) });
        fiberpli::AddFieldDoubles(
          output, fiberpli::fiberfield::kTesterCutMove, { r.testerCutMove });
      }
      this->UpdateProgress(1.0);
      return 1;
    });
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
  os << indent << "PushBoost: " << this->PushBoost << "\n";
  os << indent << "Drag: " << this->Drag << "\n";
  os << indent << "DragSteps: " << this->DragSteps << "\n";
  os << indent << "MaxDisplacement: " << this->MaxDisplacement << "\n";
  os << indent << "Tortuosity: " << this->Tortuosity << "\n";
  os << indent << "TortuosityWavelength: " << this->TortuosityWavelength << "\n";
  os << indent << "HoldTortuosity: " << this->HoldTortuosity << "\n";
  os << indent << "KeepBeads: " << this->KeepBeads << "\n";
  os << indent << "IterationsAsTime: " << this->IterationsAsTime << "\n";
  os << indent << "TimeStepInterval: " << this->TimeStepInterval << "\n";
  os << indent << "MaximumSnapshots: " << this->MaximumSnapshots << "\n";
  os << indent << "CheckpointFile: " << this->CheckpointFile << "\n";
  os << indent << "CheckpointInterval: " << this->CheckpointInterval << "\n";
  os << indent << "ResumeFromCheckpoint: " << this->ResumeFromCheckpoint << "\n";
}
