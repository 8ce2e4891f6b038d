/// TiltConvention: how a tissue vector is seen by the tilted beam (docs/pli-simulation.md §4.3),
/// the one enumeration of the simulation that writes it and the analysis that fits tilted views.
/// Its integer code is the PLISimulation property TiltConvention and the field data
/// tilt_convention.
#pragma once

#include <cstdint>
#include <string>

namespace fiberpli
{

enum class TiltConvention : std::uint8_t
{
  Physical = 0, ///< v_b = Rᵀ·v
  FastPLI = 1   ///< v_b = R·v (fastPLI's simulator and ROFL)
};

/// Code 0 (physical) or 1 (fastPLI) → the enumeration: "" or an error naming TiltConvention and the
/// value; other codes are refused, never cast.
std::string tiltConventionFromCode(int code, TiltConvention& convention);

/// The integer code of a convention (property value and field data).
inline int tiltConventionCode(TiltConvention c)
{
  return static_cast<int>(c);
}

} // namespace fiberpli
