/**
 * @file PLIImage.h
 * @brief the one conversion between PLI images (vtkImageData) and the Core's structs
 *
 * The counterpart of FiberPolyData for the PLI half of the pipeline (docs/pli-simulation.md §7,
 * docs/pli-analysis.md §1, §5): WritePliStack and WritePliTissue write what PLISimulation computed,
 * ReadPliStack reads such a stack for PLIAnalysis (the rules of Core/Analysis/PliStackRules.h), and
 * the map writers turn the Core's whole-image maps into the point arrays of the requested pixels,
 * all through one cropping rule (AddCroppedMap). The names come from Core/Model/DataNames.h.
 * Geometry (extent, origin, spacing) stays with the filters, which know the pipeline's request.
 */
#ifndef PLIImage_h
#define PLIImage_h

#include "Analysis/GroundTruth.h"
#include "Analysis/PliAnalysis.h"
#include "FiberPLIConversionModule.h" // for export macro
#include "PLI/PLIPipeline.h"
#include "PLI/TissueExport.h"

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

class vtkImageData;

namespace fiberpli
{

/// Fibers a PLI piece was computed from and fibers of the whole model (docs/pli-simulation.md
/// §6.3).
struct PieceFibers
{
  double tile = 0.0;
  double model = 0.0;
};

/// Port 0 of PLISimulation: one point array per view (`intensity`, then `intensity_tilt_<v>`; one
/// component per polarizer angle, in the Core's order x fastest, rotations innermost, which is
/// VTK's point order) and the image's field data, onto `output` whose extent holds `image.range`.
FIBERPLICONVERSION_EXPORT void WritePliStack(const pli::PLIImage& image, const pli::PLIPlan& plan,
  const pli::PLIOptions& options, const PieceFibers& fibers, vtkImageData* output);

/// Port 1 of PLISimulation: the tissue's `label` and `optic_axis` and their field data.
FIBERPLICONVERSION_EXPORT void WritePliTissue(const pli::TissueVolume& tissue,
  const pli::PLIPlan& plan, const PieceFibers& fibers, vtkImageData* output);

/// A PLI stack read from an image: the Core's PliStack, whose pointers refer to the image's double
/// arrays or to the copies held here (a deque never moves its elements). Valid while both live.
struct PliStackInput
{
  PliStack stack;
  std::deque<std::vector<double>> copies;
};

/// Reads the stack of `image` (a one-slice PLISimulation image, or any image carrying its arrays
/// and field data) for the InclinationMethod `method`: "" and `input`, or the error naming the
/// array or field data (decodePliStack).
FIBERPLICONVERSION_EXPORT std::string ReadPliStack(
  vtkImageData* image, InclinationMethod method, PliStackInput& input);

/// Adds the point array `name` (double): the pixels of `range` of the Core map `map` (the whole
/// image, nx pixels wide, x fastest), each multiplied by `scale`. An empty map adds nothing.
FIBERPLICONVERSION_EXPORT void AddCroppedMap(vtkImageData* output, const char* name,
  const std::vector<double>& map, std::int64_t nx, const GridRange& range, double scale);

/// PLIAnalysis's maps of `range` (angles in degrees, direction in [0, 180)) with `direction` as
/// the active scalars, and its field data reference_retardation and inclination_method.
FIBERPLICONVERSION_EXPORT void WriteAnalysisMaps(
  const PliAnalysisMaps& maps, std::int64_t nx, const GridRange& range, vtkImageData* output);

/// FiberOrientationGroundTruth's maps of `range` (angles in degrees) with `direction` as the
/// active scalars, and the piece's fiber counts.
FIBERPLICONVERSION_EXPORT void WriteGroundTruthMaps(const GroundTruthMaps& maps, std::int64_t nx,
  const GridRange& range, const PieceFibers& fibers, vtkImageData* output);

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: PLIImage.h
