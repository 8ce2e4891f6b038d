/// Epa: transmittance, direction and retardation of a polarizer-angle stack by a least-squares
/// fit of the first harmonic I(ρ) ≈ a0 + a1·sin 2ρ + b1·cos 2ρ (docs/pli-analysis.md §2). Works for
/// any set of N >= 3 polarizer angles that determine the harmonic; equidistant angles take the
/// closed-form fast path of §2.2. Angles in radians.
#pragma once

#include "Section/PixelGrid.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

/// Coefficients of the first harmonic of one pixel (§2).
struct Harmonic
{
  double a0 = 0.0;
  double a1 = 0.0;
  double b1 = 0.0;
};

/// Result of one pixel (§2.3). All NaN for an invalid pixel (a0 <= 0 or non-finite data, §1).
struct EpaPixel
{
  double transmittance = 0.0; ///< 2·a0, same unit as the intensities
  double direction = 0.0; ///< radians in [0, π): ½·atan2(−b1, a1); 0 when the amplitude vanishes
  double retardation = 0.0; ///< √(a1² + b1²)/a0 clamped to [0, 1]
};

/// The per-image part of the fit: a0, a1, b1 are dot products of the N intensities with these
/// weight vectors (rows of (XᵀX)⁻¹Xᵀ, §2.1; or the closed form of §2.2).
class EpaFit
{
public:
  /// Prepares the weights for the polarizer angles rho (radians). Returns an empty string on
  /// success, else a message: fewer than 3 angles, a non-finite angle, or angles that do not
  /// determine the harmonic (reciprocal condition number < 1e-10, e.g. {0°, 90°}).
  std::string init(const std::vector<double>& rho);

  std::size_t size() const { return w0_.size(); }
  /// True when the §2.2 fast path (equidistant to 1e-9 rad) is in use.
  bool equidistant() const { return equidistant_; }

  /// Harmonic of the N = size() intensities at I (stride 1).
  Harmonic harmonic(const double* I) const;
  /// EPA of the N intensities at I (§2.3), NaN everywhere for an invalid pixel.
  EpaPixel pixel(const double* I) const;

private:
  std::vector<double> w0_, w1_, wb_;
  bool equidistant_ = false;
};

/// §2.3 from the harmonic: the maps of one pixel; NaN everywhere when a0 <= 0 or non-finite.
EpaPixel epaFromHarmonic(const Harmonic& h);

/// Per-pixel maps of an nx × ny image; outputs are resized to nx·ny and pixels outside the range
/// are left untouched (NaN when freshly allocated).
struct EpaMaps
{
  std::vector<double> transmittance;
  std::vector<double> direction; ///< radians in [0, π)
  std::vector<double> retardation;
};

/// EPA of a stack: `stack` holds nx·ny pixels (x fastest) of nrho = rho.size() intensities each,
/// pixel-major (the layout of a VTK point array with nrho components). Computes the pixels in
/// `range` with `threads` OpenMP threads (0 = all), bit-identical for any thread count.
/// The Status error says why it failed (bad angles, bad range, null stack); aborted: progress
/// asked to stop (the maps are then incomplete).
Status computeEpa(const double* stack, std::int64_t nx, std::int64_t ny,
  const std::vector<double>& rho, const GridRange& range, int threads, EpaMaps& maps,
  const ProgressFn& progress = {});

} // namespace fiberpli
