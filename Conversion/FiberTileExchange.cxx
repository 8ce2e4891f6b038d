#include "FiberTileExchange.h"

#include "FiberCollective.h"
#include "FiberFieldData.h"
#include "FiberPolyData.h"
#include "FiberSolverComm.h"
#include "Model/FiberModel.h"

#include <vtkAlgorithm.h>
#include <vtkAlgorithmOutput.h>
#include <vtkExecutive.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkMultiProcessController.h>
#include <vtkPolyData.h>
#include <vtkStreamingDemandDrivenPipeline.h>

#include <algorithm>
#include <cmath>

namespace fiberpli
{

namespace
{
vtkMultiProcessController* ParallelController()
{
  vtkMultiProcessController* c = vtkMultiProcessController::GetGlobalController();
  return c && c->GetNumberOfProcesses() > 1 ? c : nullptr;
}
} // namespace

void FiberTileExchange::RequestPiece(
  vtkInformation* request, vtkInformationVector* outputVector, vtkInformation* inInfo)
{
  int port = request && request->Has(vtkExecutive::FROM_OUTPUT_PORT())
    ? request->Get(vtkExecutive::FROM_OUTPUT_PORT())
    : 0;
  port = port >= 0 && port < outputVector->GetNumberOfInformationObjects() ? port : 0;
  vtkInformation* outInfo = outputVector->GetInformationObject(port);
  if (!FiberCollective::ControllerFor(outInfo))
  {
    FiberPolyData::RequestAllFibers(inInfo);
    return;
  }
  using SDDP = vtkStreamingDemandDrivenPipeline;
  inInfo->Set(SDDP::UPDATE_PIECE_NUMBER(), outInfo->Get(SDDP::UPDATE_PIECE_NUMBER()));
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_PIECES(), outInfo->Get(SDDP::UPDATE_NUMBER_OF_PIECES()));
  inInfo->Set(SDDP::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
}

std::string FiberTileExchange::UpdateBounds(vtkAlgorithm* algorithm, vtkInformation* inInfo,
  const std::string& who, double bounds[6], FiberModelCache* cache)
{
  vtkMultiProcessController* c = ParallelController();
  auto* exec = vtkStreamingDemandDrivenPipeline::SafeDownCast(algorithm->GetInputExecutive(0, 0));
  if (inInfo && exec && algorithm->GetNumberOfInputConnections(0) > 0)
  {
    if (c)
    {
      // The piece a parallel update asks for (ParaView: piece = rank of every rank).
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), c->GetLocalProcessId());
      inInfo->Set(
        vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), c->GetNumberOfProcesses());
      inInfo->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    }
    else
    {
      FiberPolyData::RequestAllFibers(inInfo);
    }
    exec->Update(algorithm->GetInputConnection(0, 0)->GetIndex());
  }
  vtkPolyData* input =
    inInfo ? vtkPolyData::SafeDownCast(inInfo->Get(vtkDataObject::DATA_OBJECT())) : nullptr;
  std::string error;
  // The largest (−lo, hi) over the ranks: one reduction gives both corners.
  std::vector<double> corners(6, -HUGE_VAL); // -inf: no fibers
  if (!FiberPolyData::IsEmpty(input))
  {
    FiberConversion uncached;
    const FiberConversion& in =
      cache ? cache->Get(input, who) : (uncached = FiberPolyData::ToModel(input, who));
    Vec3 lo, hi;
    error = in.error;
    if (in.ok() && modelBounds(in.model, true, lo, hi))
    {
      corners = { -lo.x, -lo.y, -lo.z, hi.x, hi.y, hi.z };
    }
  }
  if (c)
  {
    FiberSolverComm comm(c);
    comm.max(corners);
  }
  for (std::size_t d = 0; d < 3; ++d)
  {
    const bool none = corners[d] == -HUGE_VAL;
    bounds[2 * d] = none ? 1.0 : -corners[d];
    bounds[2 * d + 1] = none ? -1.0 : corners[3 + d];
  }
  return error;
}

TileFibers FiberTileExchange::Receive(vtkInformation* outInfo, vtkPolyData* input,
  const std::string& who, const std::string& localError, const ReachFunction& reachOf,
  FiberModelCache* cache)
{
  std::string error = localError;
  FiberConversion local; // this rank's piece when there is no cache
  const FiberConversion* conversion = &local;
  if (error.empty() && !FiberPolyData::IsEmpty(input))
  {
    conversion = cache ? &cache->Get(input, who) : &(local = FiberPolyData::ToModel(input, who));
    error = conversion->error;
  }
  TilePiece piece;
  piece.model = &conversion->model;
  piece.empty = FiberPolyData::IsEmpty(input);
  piece.hasCell = PeriodicCellValues(input, piece.cell);
  TileFibers result;
  vtkMultiProcessController* c = FiberCollective::ControllerFor(outInfo);
  if (!c)
  {
    result = wholeModelTile(piece, error);
  }
  else
  {
    piece.piece = outInfo->Get(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER());
    FiberSolverComm comm(c);
    result = exchangeTileFibers(
      piece, error, who, reachOf,
      [outInfo, &who](const std::string& e)
      { return FiberCollective::AgreeOnError(outInfo, who, e); },
      comm);
  }
  result.warning = conversion->warning;
  return result;
}

} // namespace fiberpli
