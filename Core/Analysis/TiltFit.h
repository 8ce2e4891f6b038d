/// TiltFit: signed inclination, direction and relative thickness from one untilted and four
/// tilted views (ROFL, Schmitz et al. 2018; docs/pli-analysis.md §3.2). Per pixel: EPA of each
/// view, normalised data y_jk = I_jk/A_j − 1 with camera-noise weights, a start grid over (α, t) at
/// the EPA direction of the flat view, then Levenberg–Marquardt on (φ, α, t) with an analytic
/// Jacobian. Angles in radians.
#pragma once

#include "Analysis/Epa.h"
#include "Section/PixelGrid.h"
#include "Section/TiltConvention.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

/// One tilted view: in-tissue tilt θ_t (field data tilt_angles) and tilt azimuth φ_t (field data
/// tilt_directions, the direction the beam leans to, counter-clockwise from +x), radians.
struct TiltView
{
  double theta = 0.0;
  double azimuth = 0.0;
};

/// The classic polarimeter: one tilt θ_t at the azimuths 0°, 90°, 180°, 270°.
std::vector<TiltView> fourTiltViews(double theta);

struct TiltFitOptions
{
  std::vector<TiltView> views; ///< the tilted views, in the order of their stacks
  TiltConvention convention = TiltConvention::Physical;
  double gain = 3.0; ///< camera gain g of the weights; g <= 0 (noise-free data) means 1
  int maxIterations = 100;
};

/// Fit of one pixel; every field NaN (iterations 0) when a view has a0 <= 0 or non-finite data.
struct TiltFitResult
{
  double direction;         ///< canonical axis (docs/pli-analysis.md §3.2 step 4), [0, π)
  double inclinationSigned; ///< [−π/2, π/2]
  double inclination;       ///< |inclinationSigned|
  double relativeThickness; ///< |t| = 4·d·|Δn|/λ of the untilted section
  double chi2;              ///< weighted χ² at the optimum
  int iterations;           ///< Levenberg–Marquardt iterations used
};

/// Per-image set-up (angles, rotations, EPA weights) and the per-pixel fit.
class TiltFit
{
public:
  /// Errors: fewer than 4 polarizer angles (docs/pli-analysis.md §3.2), angles EPA refuses, fewer
  /// than 2 tilted views, a tilt not in (0, 90°), a non-finite azimuth, two equal views,
  /// maxIterations < 1.
  std::string init(const std::vector<double>& rho, const TiltFitOptions& options);

  /// views[0] = untilted, views[1..M] = the tilted views of the options; each points to the
  /// N = rho.size() intensities of this pixel.
  TiltFitResult pixel(const std::vector<const double*>& views) const;

private:
  struct Data; // normalised data and weights of one pixel
  double residuals(const Data& d, const double p[3], double* r, double (*J)[3]) const;

  EpaFit epa_;
  std::vector<double> s_, c_; // sin 2ρ_k, cos 2ρ_k
  struct Frame
  {
    double m[3][3]; // tissue → beam frame
    double kappa;   // (π/2)·(path / d)
  };
  std::vector<Frame> frames_; // untilted view first
  double gain_ = 1.0;
  int maxIterations_ = 100;
};

/// Maps of the tilt fit (all radians except chi2 and thickness); resized to nx·ny.
struct TiltMaps
{
  std::vector<double> direction;
  std::vector<double> inclination;
  std::vector<double> inclinationSigned;
  std::vector<double> relativeThickness;
  std::vector<double> chi2;
};

/// Tilt fit of the pixels in range. flat and tilts[v] are stacks of nx·ny pixels with
/// rho.size() intensities each (pixel-major, x fastest), tilts in the order of options.views.
/// OpenMP over pixels with `threads` (0 = all); bit-identical for any thread count.
/// The Status error says why it failed; aborted: progress asked to stop (maps incomplete).
Status computeTiltFit(const double* flat, const std::vector<const double*>& tilts, std::int64_t nx,
  std::int64_t ny, const std::vector<double>& rho, const TiltFitOptions& options,
  const GridRange& range, int threads, TiltMaps& maps, const ProgressFn& progress = {});

} // namespace fiberpli
