/// PliStackRules: how the analysis reads a PLISimulation image (docs/pli-simulation.md §7,
/// docs/pli-analysis.md §1): which polarizer angles and tilted views it holds, from its arrays'
/// component counts and its field data, and the tilted-sensor rule. The VTK side only gathers the
/// raw values (Conversion/PLIImage.h); every decision is made here, so it is unit-tested without
/// VTK and any reader of such images (a script, another front end) follows the same rules.
#pragma once

#include "Analysis/PliAnalysis.h"
#include "Analysis/TiltFit.h"
#include "Section/TiltConvention.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

/// The raw values of an image that describe its stack, as they are (nothing checked yet).
struct PliStackFields
{
  std::int64_t slices = 1;   ///< points along z
  bool hasIntensity = false; ///< the point array intensity is present
  int components = 0;        ///< its components (one per polarizer angle)
  std::vector<int>
    tiltComponents; ///< components of intensity_tilt_0, 1, … up to the first missing one
  bool hasPolarizerAngles = false;     ///< field data polarizer_angles is present
  std::vector<double> polarizerAngles; ///< its values, degrees
  bool hasTiltAngles = false;          ///< field data tilt_angles is present
  std::vector<double> tiltAngles;      ///< its values, degrees
  std::vector<double> tiltDirections;  ///< field data tilt_directions, degrees (empty when absent)
  double tiltAngle = 0.0;      ///< the older one-angle form tilt_angle, degrees (0 when absent)
  double tiltConvention = 0.0; ///< field data tilt_convention (0 when absent)
  double tiltedSensor = 0.0;   ///< field data tilted_sensor (0 when absent)
  double noiseGain = -1.0;     ///< field data noise_gain (−1 when absent)
};

/// What the analysis reads of the stack.
struct PliStackLayout
{
  std::vector<double> rho;         ///< polarizer angles, radians
  std::size_t tiltStacks = 0;      ///< tilted stacks used: intensity_tilt_0 … tiltStacks − 1
  std::vector<TiltView> tiltViews; ///< their set-up (radians), same order
  TiltConvention convention = TiltConvention::Physical;
  double noiseGain = -1.0; ///< < 0: absent
};

/// The polarizer angles in radians: polarizer_angles when present, else N equidistant angles
/// k·180°/N for the N components of intensity.
std::vector<double> polarizerAnglesOf(const PliStackFields& fields);

/// The set-up of `stacks` tilted views: tilt_angles and tilt_directions (one value per view), or
/// the older one-angle form (tilt_angle for every view, azimuths 0°, 90°, 180°, 270° for four
/// views). "" and `views` (radians), or an error naming the field data whose count does not match.
std::string tiltViewsOf(
  const PliStackFields& fields, std::size_t stacks, std::vector<TiltView>& views);

/// Decodes the stack for InclinationMethod `method`: one slice, an intensity array, at least 3
/// polarizer angles matching its components, tilted stacks with the same components and their
/// set-up. The tilted-sensor rule: views on the tilted sensor's grid (tilted_sensor = 1) are not
/// pixel-aligned with the untilted view, so Tilt is refused and Auto and Retardation read the
/// untilted view alone. "" and `layout`, or the error naming the array or field data.
std::string decodePliStack(
  const PliStackFields& fields, InclinationMethod method, PliStackLayout& layout);

} // namespace fiberpli
