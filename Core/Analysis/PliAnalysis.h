/// PliAnalysis: the whole `PLIAnalysis` computation of docs/pli-analysis.md §1 on plain arrays —
/// EPA of the untilted stack (§2), then the inclination by the chosen method (§3.1 retardation
/// or §3.2 tilt fit). Angles in radians (the VTK side converts to degrees).
#pragma once

#include "Analysis/Epa.h"
#include "Analysis/TiltFit.h"
#include "Section/PixelGrid.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace fiberpli
{

/// InclinationMethod of docs/pli-analysis.md §1.
enum class InclinationMethod
{
  Auto = 0,        ///< Tilt when at least 2 tilted views exist, else Retardation
  Retardation = 1, ///< §3.1, unsigned
  Tilt = 2         ///< §3.2, signed, with relative thickness and χ²
};

/// The simulation output (docs/pli-simulation.md §7) as plain arrays.
struct PliStack
{
  const double* intensity = nullptr; ///< nx·ny pixels × rho.size(), pixel-major, x fastest
  std::vector<const double*> tilts;  ///< intensity_tilt_0..M−1 (null = missing)
  std::vector<TiltView> tiltViews;   ///< set-up of the tilted stacks, same order
  std::int64_t nx = 0, ny = 0;
  std::vector<double> rho; ///< polarizer angles, radians
  TiltConvention convention = TiltConvention::Physical;
  double noiseGain = -1.0; ///< field data noise_gain; < 0 = absent
};

struct PliAnalysisOptions
{
  InclinationMethod method = InclinationMethod::Auto;
  double referenceRetardation =
    0.0; ///< docs/pli-analysis.md §3.1 r_ref in [0, 1]; 0 = largest retardation (automatic)
  double noiseGain = -1.0; ///< −1 = stack.noiseGain if present, else 3; g <= 0 → 1 in the fit
  int threads = 0;         ///< OpenMP threads, 0 = all
  /// Automatic r_ref across MPI pieces: receives the local maximum, returns the global one (the
  /// VTK side passes an AllReduce(MAX)); called exactly once, from the calling thread, whenever the
  /// Retardation method runs with referenceRetardation = 0, even for an empty range.
  std::function<double(double)> globalMaxRetardation;
};

/// Largest NoiseGain the analysis accepts (the tilt-fit weights 1/(g·I)); real cameras have g of
/// about 1 to 10. Plugin/PLIAnalysis.xml repeats this range.
constexpr double kMaxAnalysisNoiseGain = 1e6;

/// InclinationMethod from its property code (0 Auto, 1 Retardation, 2 Tilt): "" or an error naming
/// the property and the value; any other code is refused, never cast into the enum.
std::string inclinationMethodFromCode(int code, InclinationMethod& method);

/// "" when ReferenceRetardation is in [0, 1] and NoiseGain is −1 or in [0, kMaxAnalysisNoiseGain];
/// else the message naming the property and the value. analysePli checks it first.
std::string checkPliAnalysisOptions(const PliAnalysisOptions& options);

/// Maps on the nx·ny grid (pixels outside the range stay NaN when freshly allocated).
struct PliAnalysisMaps
{
  InclinationMethod method = InclinationMethod::Retardation; ///< the method actually used
  double referenceRetardation = 0.0;                         ///< r_ref used (Retardation method)
  std::vector<double> transmittance, direction, retardation,
    inclination;                                                  ///< outputs of docs/api.md §3
  std::vector<double> inclinationSigned, relativeThickness, chi2; ///< Tilt method only, else empty
};

/// Runs docs/pli-analysis.md §2 + §3 on the pixels of range. In the Tilt method `direction` is the
/// fitted axis direction (consistent with inclinationSigned) and a pixel whose fit has invalid data
/// is NaN in every output. Errors name the fix: missing tilt stacks or tilt views for Tilt, too few
/// or degenerate polarizer_angles, ReferenceRetardation outside [0, 1], a bad range; aborted when
/// progress asked to stop.
Status analysePli(const PliStack& stack, const PliAnalysisOptions& options, const GridRange& range,
  PliAnalysisMaps& maps, const ProgressFn& progress = {});

} // namespace fiberpli
