/**
 * @class   FiberCollective
 * @brief   the MPI error state shared by the FiberPLI algorithms of one parallel update
 *
 * When an algorithm fails on one rank only, VTK does not execute what is downstream of it on that
 * rank, while the other ranks go on: a later collective (PLIAnalysis's reduction, the gather of
 * SaveData's parallel writer) then waits forever for the failed rank, or a writer writes only the
 * pieces of the healthy ranks. So every FiberPLI filter that executes on every rank ends
 * RequestData with AgreeOnError (or runs it through RunCollectively): all ranks learn whether any
 * rank failed, and then all fail together (empty output, an error on every rank naming the rank and
 * its message) or all succeed.
 *
 * A request is treated as collective only when it is one piece of an update of every rank of the
 * global controller (UPDATE_NUMBER_OF_PIECES equal to its number of processes, > 1): that is how
 * ParaView updates in parallel, while a serial run, or one rank updating alone, never waits. Not
 * for sources and readers: VTK executes them for piece 0 only unless they can handle pieces.
 */
#ifndef FiberCollective_h
#define FiberCollective_h

#include "FiberPLIConversionModule.h" // for export macro

#include <functional>
#include <string>

class vtkAlgorithm;
class vtkDataObject;
class vtkInformation;
class vtkInformationVector;
class vtkMultiProcessController;

namespace fiberpli
{

class FIBERPLICONVERSION_EXPORT FiberCollective
{
public:
  /// The global controller when `info` (an output, or for a writer the input, information) belongs
  /// to a request that every rank executes; else nullptr.
  static vtkMultiProcessController* ControllerFor(vtkInformation* info);

  /// Collective over ControllerFor(info) (local only without it): every rank passes its own error
  /// ("" = success) and gets "" when all ranks succeeded, else — the same decision on every rank —
  /// its own error on a failing rank and "<who>: rank R failed, so no rank gives output: <error of
  /// R>" (R = the lowest failing rank) on the others.
  /// Who failed and whose message wins follow the Core's one rule (agreeOnFailure,
  /// Parallel/Collectives.h, docs/data-contract.md §5).
  static std::string AgreeOnError(
    vtkInformation* info, const std::string& who, const std::string& localError);

  /// The largest `local` over the ranks of ControllerFor(info) (`local` itself without one).
  /// Collective: every rank calls it equally often per execution, whatever path it takes.
  static double GlobalMax(vtkInformation* info, double local);

  /// Collective over ControllerFor(info) (local only without it): FiberFieldData.h's
  /// compareRankCells (Model/PeriodicCellRule.h) over every rank's `periodic_cell` of `piece`; ""
  /// or, on every rank, "<who>: " and the message naming the rank whose cell is malformed or
  /// differs. Without a controller the one piece's cell is checked alone.
  static std::string AgreeOnPeriodicCell(
    vtkInformation* info, const std::string& who, vtkDataObject* piece);

  /// Runs `piece` (this rank's RequestData, reporting errors with vtkErrorMacro and returning 0)
  /// and ends it with AgreeOnError over the information of the requesting output port. When any
  /// rank failed, the ranks whose piece succeeded empty every output, report the failed rank's
  /// message on `self` and return 0; otherwise piece's result is returned as it is.
  static int RunCollectively(vtkAlgorithm* self, vtkInformation* request,
    vtkInformationVector* outputVector, const std::string& who, const std::function<int()>& piece);
};

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberCollective.h
