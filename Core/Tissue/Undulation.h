/// Undulation: a smooth random path around a fiber's base path, calibrated to a target tortuosity
/// (docs/tissue-models.md §10.1). The transverse deviation is a sum of a few sine modes in the two
/// directions across the path, with wavelengths around the requested one and random phases; its
/// amplitude is found per fiber by bisection on the length of the actual polyline, so every fiber
/// reaches the requested tortuosity. On a closed fiber (a periodic cell) every mode has a whole
/// number of waves over the fiber's period, so the deviation is periodic with zero mean and the
/// fiber still closes on its first point shifted by its lattice vector. On an open fiber the
/// deviation's straight trend is removed, so the end points stay on the base path.
///
/// A fiber keeps its Undulation (modes and calibrated amplitude): undulatedPath with a fraction of
/// the amplitude gives the same fiber less undulated, so a later step can go from straight to the
/// target shape, or re-apply it.
#pragma once

#include "Geometry/Vec3.h"
#include "Util/Random.h"

#include <cstddef>
#include <vector>

namespace fiberpli
{

/// Where a fiber runs without undulation: a polyline of >= 2 points (no two consecutive equal) and
/// at every point two unit directions u, v across it. closed: the fiber is closed through a
/// periodic cell, points.back() − points.front() being its lattice vector.
struct BasePath
{
  std::vector<Vec3> points;
  std::vector<Vec3> u;
  std::vector<Vec3> v;
  bool closed = false;
  /// closed: the fiber's lattice vector, exactly (points.back() − points.front() up to rounding).
  Vec3 closure;
};

/// The straight base path from `start` to `start + span` (2 points) with a fixed pair of directions
/// across it (u: the unit vector of the coordinate axis least aligned with span, made
/// perpendicular; v = span̂ × u).
BasePath straightBasePath(const Vec3& start, const Vec3& span, bool closed);

/// One sine mode of the deviation: `cycles` waves over the base length (a whole number on a closed
/// fiber), its weight and a phase for each of the two transverse directions.
struct UndulationMode
{
  double cycles = 1.0;
  double weight = 1.0;
  double phaseU = 0.0; ///< radians
  double phaseV = 0.0; ///< radians
};

/// A fiber's undulation: its modes (weights with Σ weight² = 1) and the amplitude (µm) that
/// reaches its target tortuosity (0 = straight).
struct Undulation
{
  std::vector<UndulationMode> modes;
  double amplitude = 0.0;
};

/// The number of modes drawUndulation draws.
constexpr int kUndulationModes = 3;

/// Draws the modes of one fiber (amplitude 0): kUndulationModes modes of wavelength
/// λ·exp(0.25·z) (z standard normal, so most wavelengths lie within ±30 % of λ), on a closed fiber
/// rounded to a whole number >= 1 of waves over baseLength; weights U[0.5, 1] normalised, phases
/// U[0, 2π). Draws 5 numbers per mode from rng, in this order: z, weight, phaseU, phaseV, and one
/// spare (so the draw count per mode is fixed). Precondition: baseLength, wavelength > 0.
Undulation drawUndulation(RandomStream& rng, double baseLength, double wavelength, bool closed);

/// One plane wave of a population's shared undulation field: its wave vector (rad/µm), weight and
/// a phase for each of the two transverse directions.
struct UndulationWave
{
  Vec3 k;
  double weight = 1.0;
  double phaseU = 0.0; ///< radians
  double phaseV = 0.0; ///< radians
};

/// A population's undulation field (docs/tissue-models.md §10.1, `UndulationCoherence`): the
/// deviation at a point x of the cell is Σ weight·sin(k·x + phase) along each of the two
/// directions across the population's axis, so fibers whose axes are r apart undulate with
/// correlation about exp(−r²/2ξ²) (ξ the coherence length) instead of independently.
struct UndulationField
{
  std::vector<UndulationWave> waves;
};

/// The number of waves drawUndulationField draws.
constexpr int kUndulationFieldWaves = 32;

/// Draws a population's field (axis and the two directions across it unit and orthogonal):
/// kUndulationFieldWaves waves of wavelength λ·exp(0.25·z) along the axis (z standard normal) and
/// transverse wave numbers q₁, q₂ standard normal / ξ, so that the deviations of two fibers r apart
/// across the axis correlate as exp(−r²/2ξ²). period > 0 (a periodic cell of that edge, the axis
/// and directions along coordinate axes): every wave vector is a whole multiple of 2π/period per
/// axis (at least one wave along the axis), so the field is periodic over the cell and closed
/// fibers stay closed. Weights U[0.5, 1] normalised to Σ weight² = 1, phases U[0, 2π). Draws 6
/// numbers per wave from rng: z, q₁, q₂, weight, phaseU, phaseV. Precondition: wavelength,
/// coherence > 0.
UndulationField drawUndulationField(RandomStream& rng, const Vec3& axis, const Vec3& across1,
  const Vec3& across2, double wavelength, double coherence, double period);

/// The field sampled along the straight fiber start + t·span, t ∈ [0, 1], as the fiber's modes
/// (amplitude 0): wave w gives cycles k·span / 2π and phases k·start + phase.
Undulation sampleUndulationField(const UndulationField& field, const Vec3& start, const Vec3& span);

/// The transverse deviation (along u, along v) of the modes at the fraction t ∈ [0, 1] of the base
/// length, for amplitude 1 (open fibers: minus the straight trend, so 0 at both ends).
void undulationDeviation(
  const Undulation& undulation, double t, bool closed, double& du, double& dv);

/// The undulated fiber with `points` points (>= 2) spaced equally in arc length along the curve
/// base(s) + amplitude·(du(s)·u(s) + dv(s)·v(s)); the first and last points lie on the base
/// path's ends (closed: last = first + base.closure, exactly). amplitude 0 gives the base
/// path resampled.
std::vector<Vec3> undulatedPath(
  const BasePath& base, const Undulation& undulation, double amplitude, std::size_t points);

/// Polyline length of `points` (+ jitter[i] per point when jitter is given, same size).
double jitteredLength(const std::vector<Vec3>& points, const std::vector<Vec3>* jitter);

/// Sets undulation.amplitude so that the fiber undulatedPath(base, undulation, amplitude, points)
/// (+ jitter, when given) is `tortuosity` times as long as the base path (an open fiber's base
/// length scaled by how much the jitter of its two ends changes its end-to-end distance) (bisection
/// on the polyline's own length, to 1e-6 of the excess). Returns false, with amplitude 0, when the
/// jittered straight fiber is already at least that long (the jitter alone exceeds the target).
bool calibrateUndulation(const BasePath& base, Undulation& undulation, double tortuosity,
  std::size_t points, const std::vector<Vec3>* jitter = nullptr);

/// The point count of a fiber of base length L at tortuosity τ and spacing l along its path:
/// max(minimum, round(τ·L/l) + 1).
std::size_t undulatedPointCount(
  double baseLength, double tortuosity, double segmentLength, std::size_t minimum);

} // namespace fiberpli
