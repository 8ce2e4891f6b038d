/// [ours] Push boost for heavily overlapping input (docs/solver.md §4.1): the push multiplier b the
/// solver fixes at its first detection from how crowded the input is, and the push of one
/// colliding pair under it. Pure functions, no solver state.
#pragma once

#include <cstddef>

namespace fiberpli
{

/// b = 1 + (pushBoost − 1)·clamp((q − 6)/3, 0, 1) with q = pairs / links, the colliding pairs per
/// link at the first detection: 1 (bit for bit the unboosted solve) up to q = 6, input that
/// nominally fills its whole volume; the full pushBoost from q = 9. 1 without links.
double pushScaleFor(std::size_t pairs, std::size_t links, double pushBoost);

/// The push σ of one pair (each of its links receives σ in total) from the unboosted push σ₀ and
/// the pair's overlap ρa + ρb + g − δ: b·σ₀, but never more than half the overlap (the two links
/// together never get more than the overlap, so a deep pair is separated fast and a shallow one
/// is not pushed far past contact, which would leave a gap), and never less than σ₀. Exactly σ₀
/// for b = 1.
double boostedPush(double sigma0, double scale, double overlap);

} // namespace fiberpli
