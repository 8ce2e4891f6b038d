/// RetardationInclination: unsigned inclination from the retardation of one untilted view
/// (docs/pli-analysis.md §3.1). For a homogeneous column r = |sin((π/2)·t_rel·cos²α)|; with the
/// reference r_ref = retardation of an in-plane fiber, α = arccos(√(asin(min(r,
/// r_ref))/asin(r_ref))). Only valid while t_rel <= 1 (sin still monotonic), e.g. Δn −0.001 at 60
/// µm and 525 nm (t_rel 0.457); at Δn −0.004 (t_rel 1.83) the inversion is ambiguous. The sign of α
/// is unknown.
#pragma once

#include "Section/PixelGrid.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

/// α in radians, [0, π/2]: r <= 0 → π/2, r >= rRef → 0, NaN r → NaN. Precondition 0 < rRef <= 1.
double inclinationFromRetardation(double r, double rRef);

/// Largest finite retardation of the pixels in range (the automatic r_ref of §3.1: the most
/// in-plane region of the section); 0 when there is none. Under MPI the caller takes the global
/// maximum of the pieces' values.
double maxRetardation(const double* retardation, std::int64_t nx, const GridRange& range);

/// Inclination map (radians) of the pixels in range; `inclination` is resized to nx·ny (NaN
/// outside the range when freshly allocated). referenceRetardation > 0 is r_ref, 0 = automatic
/// (maxRetardation over the range; all-zero retardation then gives 90° everywhere).
/// Errors: referenceRetardation < 0, > 1 or non-finite (named ReferenceRetardation), bad range.
std::string inclinationMapFromRetardation(const double* retardation, std::int64_t nx,
  std::int64_t ny, const GridRange& range, double referenceRetardation, int threads,
  std::vector<double>& inclination);

} // namespace fiberpli
