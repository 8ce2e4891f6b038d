/**
 * @class   FiberTileExchange
 * @brief   the fibers of one MPI tile: each rank's piece of the model goes to the ranks whose tile
 * it reaches
 *
 * PLISimulation and FiberOrientationGroundTruth compute their image (and tissue) piece by piece,
 * one piece per rank (docs/pli-simulation.md §6.3). Instead of asking every rank for the whole
 * model — which made every rank execute the whole upstream again — they ask the upstream for the
 * rank's own piece of fibers (RequestPiece). In RequestData every rank says which box its piece
 * reads (a Core TileReach) and each fiber is sent, through the global vtkMultiProcessController,
 * to the ranks whose box it reaches: the exchange of Core/Parallel/TileExchange.h (where it is
 * unit-tested), here over FiberSolverComm and with FiberCollective's error agreement. A rank then
 * holds only the fibers of its tile, in the order of the whole model, so the pieces are bit for bit
 * the crop of the serial result.
 *
 * Input that sits on one rank only (a reader that cannot make pieces gives piece 0 the whole
 * model and empty pieces elsewhere) is spread the same way. Errors on any rank (a bad input
 * piece, a plan error, the memory budget of the received fibers) are agreed on before anything is
 * sent, so every rank fails together (FiberCollective.h). Outside a parallel update
 * (FiberCollective::ControllerFor) the upstream is asked for all fibers and nothing is exchanged.
 */
#ifndef FiberTileExchange_h
#define FiberTileExchange_h

#include "FiberPLIConversionModule.h" // for export macro
#include "Parallel/TileExchange.h"

#include <functional>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkInformation;
class vtkInformationVector;
class vtkPolyData;

namespace fiberpli
{
class FiberModelCache;

class FIBERPLICONVERSION_EXPORT FiberTileExchange
{
public:
  /// What this rank's piece reads (Parallel/TileExchange.h).
  using ReachFunction = fiberpli::ReachFunction;

  /// RequestUpdateExtent: the input is asked for this rank's piece (the piece of the requesting
  /// output port, no ghost levels) in a parallel update, for all fibers (piece 0 of 1) otherwise.
  static void RequestPiece(
    vtkInformation* request, vtkInformationVector* outputVector, vtkInformation* inInfo);

  /// RequestInformation of a filter whose image size depends on the fibers' bounds: updates input
  /// port 0 with the piece RequestPiece will ask for (so the data pass does not execute upstream
  /// again) and gives the bounds, radii included, of the whole model (min > max when it has no
  /// point); collective over every rank when the global controller has more than one. Returns
  /// this rank's conversion error ("" when its piece is usable).
  /// With a `cache` (FiberPolyData.h) the piece is converted only when its MTime changed.
  static std::string UpdateBounds(vtkAlgorithm* algorithm, vtkInformation* inInfo,
    const std::string& who, double bounds[6], FiberModelCache* cache = nullptr);

  /// RequestData: converts this rank's input piece and, in a parallel update, exchanges the fibers
  /// so that this rank receives those reaching reachOf's box. `localError` (this rank's error so
  /// far, "" when none) takes part in the agreement. Every rank of a parallel update must call it
  /// once per RequestData, whatever its own state.
  /// With a `cache` the piece is converted only when its MTime changed (the result's model is
  /// then a copy of the cached one).
  static TileFibers Receive(vtkInformation* outInfo, vtkPolyData* input, const std::string& who,
    const std::string& localError, const ReachFunction& reachOf, FiberModelCache* cache = nullptr);
};

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberTileExchange.h
