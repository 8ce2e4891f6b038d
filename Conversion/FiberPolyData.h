/**
 * @class   FiberPolyData
 * @brief   THE conversion layer between fiber vtkPolyData (docs/data-contract.md §3) and
 * fiberpli::FiberModel
 *
 * Every FiberPLI filter, reader and writer converts fibers through this class only, so the data
 * contract is validated in one place:
 * - no `radius` point array, or one with other than 1 component → error;
 * - cells but no line cell → error (verts/polys/strips are ignored with a warning otherwise);
 * - a fiber of fewer than 2 points → dropped with a warning;
 * - NaN/Inf coordinates or radius <= 0 → error naming the fiber (cell index and fiber_id) and
 * point;
 * - an input without points and cells → an empty model, no error (empty MPI pieces).
 * `fiber_id` (any integer array) and `bundle_id` cell arrays are read when present; otherwise the
 * fiber id is the cell index and the bundle id 0. An id that is no integer of its range (NaN,
 * a fraction, beyond 64 bits; a bundle_id beyond int) → error naming the cell and the value.
 */
#ifndef FiberPolyData_h
#define FiberPolyData_h

#include "FiberPLIConversionModule.h" // for export macro
#include "Model/FiberModel.h"

#include <string>
#include <vector>

class vtkAlgorithm;
class vtkInformation;
class vtkPolyData;

namespace fiberpli
{

struct FiberConversion
{
  FiberModel model;
  std::vector<long long> sourceCell;                ///< input cell index of each fiber of the model
  std::vector<std::vector<long long>> sourcePoints; ///< input point ids of each fiber of the model
  std::string error;                                ///< empty when the input is usable
  std::string warning; ///< one line per kind of recoverable oddity, with counts
  bool ok() const { return error.empty(); }
};

class FIBERPLICONVERSION_EXPORT FiberPolyData
{
public:
  /// Converts and validates fiber polydata (see the class documentation). `who` prefixes messages.
  static FiberConversion ToModel(vtkPolyData* input, const std::string& who);

  /// Replaces `output` by the model: one polyline per fiber, point array `radius` (double), cell
  /// arrays `fiber_id` (vtkIdType) and `bundle_id` (int). Fields data of `output` is kept.
  static void FromModel(const FiberModel& model, vtkPolyData* output);

  /// Copies the input's other point and cell arrays onto `output` (made by FromModel from the
  /// converted model): cell tuples from each fiber's source cell; point tuples from the source
  /// position `sourceIndex[f][i]` (fractional input point index along fiber f; floating-point
  /// arrays are interpolated linearly, other arrays take the tuple of the point before). An empty
  /// `sourceIndex` means the points are unchanged. radius, fiber_id and bundle_id are not touched.
  static void PassArrays(vtkPolyData* input, const FiberConversion& conversion,
    const std::vector<std::vector<double>>& sourceIndex, vtkPolyData* output);

  /// Asks the upstream for all fibers (piece 0 of 1, no ghosts) whatever piece is requested
  /// downstream: filters that need every fiber on every rank call it in RequestUpdateExtent.
  static void RequestAllFibers(vtkInformation* inputInfo);

  /// Brings input port 0 of `algorithm` up to date with all fibers now (for RequestInformation of
  /// filters whose output size depends on the fibers' bounds); the later data pass asks for the
  /// same piece and does not execute upstream again.
  static void UpdateAllFibers(vtkAlgorithm* algorithm, vtkInformation* inputInfo);

  /// The piece an output request asks for (0 without one) and of how many pieces (1 without one).
  static int RequestedPiece(vtkInformation* outInfo);
  static int RequestedPieces(vtkInformation* outInfo);

  /// Field data of the fiber sources: `segment_length` (µm) and `seed`.
  static void AddSourceFieldData(vtkPolyData* output, double segmentLength, int seed);

  /// The output of a fiber source from its model: FromModel, the fibers' inner radii
  /// (AddInnerRadii, FiberInnerRadii.h) and AddSourceFieldData, which every piece carries, also an
  /// empty one.
  static void FromSourceModel(
    const FiberModel& model, vtkPolyData* output, double segmentLength, int seed);

  /// True when the polydata holds neither points nor cells (an empty piece, never an error).
  static bool IsEmpty(vtkPolyData* input);
};

/// The model of one input, converted again only when the input object or its MTime changes (the
/// PLI filters keep their fibers between requests, docs/pli-simulation.md §7.3). Keeps the model
/// with the fibers' inner radii (FiberInnerRadii.h; a bad inner_radius is the conversion's error),
/// not the source ids (those filters pass no input arrays on).
class FIBERPLICONVERSION_EXPORT FiberModelCache
{
public:
  /// The conversion of `input` (ToModel with `who`), reused while it is the same object with the
  /// same MTime.
  const FiberConversion& Get(vtkPolyData* input, const std::string& who);

private:
  bool Valid = false;
  const vtkPolyData* Input = nullptr; // compared only, never dereferenced (it may be gone)
  unsigned long long Time = 0;
  FiberConversion Value;
};

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberPolyData.h
