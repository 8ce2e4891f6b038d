/// TileExchange: under MPI every rank computes one tile of an image from the fibers that reach it
/// (docs/pli-simulation.md §6.3). Each rank holds one piece of the model; every rank says which box
/// its tile reads (a TileReach) and each fiber is sent to the ranks whose box it reaches, so a rank
/// ends up with only the fibers of its tile, in the order of the whole model (global index = the
/// fibers of the lower pieces + the local index). The one ownership rule of the voxels, which
/// depends on that order, then gives every voxel the owner it has in one process: the tiles are
/// bit for bit the crop of the serial result. Errors on any rank (a bad piece, a plan error, the
/// memory budget of the received fibers) are agreed on before anything is sent, so every rank
/// fails together. Pure C++ over a Comm; the VTK side is Conversion/FiberTileExchange.
#pragma once

#include "Geometry/PeriodicCell.h"
#include "Model/FiberModel.h"
#include "Model/TileReach.h"
#include "Parallel/Comm.h"

#include <functional>
#include <string>
#include <vector>

namespace fiberpli
{

/// The fibers one rank's tile reads and what every rank knows of the whole model.
struct TileFibers
{
  FiberModel
    model; ///< the fibers reaching this rank's tile (all of them when serial), in model order
  std::vector<int> bundleIds; ///< distinct bundle ids of the whole model, sorted
  bool myelinated = false;    ///< some fiber of the whole model carries inner radii
  bool periodic =
    false;           ///< some piece carries field data periodic_cell (the lowest rank's is used)
  PeriodicCell cell; ///< that cell, when cellError is empty
  std::string cellError;     ///< why periodic_cell is unusable ("" when fine or absent)
  long long modelFibers = 0; ///< fibers of the whole model
  long long pieceFibers = 0; ///< fibers of this rank's input piece
  bool distributed = false;  ///< the fibers were exchanged between ranks
  bool emptyInput = false; ///< no rank's input piece holds points or cells (empty output, no error)
  std::string error;       ///< the agreed error: "" on every rank or an error on every rank
  std::string warning;     ///< this rank's conversion warning
  bool ok() const { return error.empty(); }
};

/// This rank's input piece as the exchange sees it.
struct TilePiece
{
  const FiberModel* model = nullptr; ///< its fibers (null: none)
  int piece = 0;            ///< its piece number: the global order runs over the pieces by number
  bool empty = true;        ///< the input piece has neither points nor cells
  bool hasCell = false;     ///< it carries field data periodic_cell …
  std::vector<double> cell; ///< … with these values, as they are
};

/// What this rank's tile reads, from what every rank knows of the model (`whole`: bundle ids,
/// periodic cell; its model is not yet filled). Returns "" or an error.
using ReachFunction = std::function<std::string(const TileFibers& whole, TileReach& reach)>;

/// The rank error agreement of the caller: every rank passes its error ("" = none) and gets ""
/// on every rank or an error on every rank. Collective.
using AgreeFunction = std::function<std::string(const std::string& localError)>;

/// One process: the piece is the whole model, kept as it is; `localError` is the result's error.
TileFibers wholeModelTile(const TilePiece& piece, const std::string& localError);

/// Every rank of `comm` calls it once, whatever its own state (`localError`, "" when none, takes
/// part in the agreement). `who` starts the memory budget's message. Collective.
TileFibers exchangeTileFibers(const TilePiece& piece, const std::string& localError,
  const std::string& who, const ReachFunction& reachOf, const AgreeFunction& agree, Comm& comm);

} // namespace fiberpli
