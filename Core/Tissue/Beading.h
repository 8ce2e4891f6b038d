/// Beading: the radius of a fiber varying along it (docs/tissue-models.md §10.3). A smooth
/// Gaussian random field g(s) along the fiber (squared-exponential correlation of length ℓ,
/// synthesised from Fourier modes, periodic over a closed fiber) makes the log-normal profile
/// r(s) = r·exp(σ·g(s)) / mean(exp(σ·g)), so the fiber's mean radius over its points is exactly the
/// radius drawn for it. σ is found per fiber (bisection) so that the coefficient of variation of
/// the radius over the fiber's points is exactly the requested one.
///
/// A fiber keeps its BeadingProfile (field and σ): beadingFactors with a fraction of σ gives the
/// same fiber less beaded, for a later step that goes from uniform radii to the target.
#pragma once

#include "Util/Random.h"

#include <vector>

namespace fiberpli
{

/// The profile of one fiber: the standardised field at its points (mean 0, standard deviation 1
/// over the counted points) and the σ reaching its target coefficient of variation.
struct BeadingProfile
{
  std::vector<double> field;
  double sigma = 0.0;
  bool closed = false; ///< the last point repeats the first (not counted, same factor)
};

/// Draws the field at arc-length positions `arc` (increasing, arc[0] = 0) of a fiber of length
/// arc.back(), correlation length ℓ > 0, and calibrates σ to the coefficient of variation cv ∈
/// (0, 1]. Closed: the field is periodic over the fiber's length and the last point (the first
/// shifted by the lattice vector) gets the first point's value. Open: synthesised over
/// length + 4ℓ, so the ends are not tied together. Draws 2 normals per Fourier mode from rng
/// (modes up to 5/(2πℓ) cycles per µm, at most one per point spacing over the period and at most
/// kMaxBeadingModes).
BeadingProfile drawBeading(RandomStream& rng, const std::vector<double>& arc,
  double correlationLength, double cv, bool closed);

/// The most Fourier modes of one field (bounds the work for a tiny BeadingLength).
constexpr int kMaxBeadingModes = 20000;

/// The radius factors exp(σ'·g) / mean(exp(σ'·g)), σ' = sigmaScale·σ: mean 1 over the counted
/// points.
std::vector<double> beadingFactors(const BeadingProfile& profile, double sigmaScale = 1.0);

/// Coefficient of variation (population standard deviation / mean) of the values, the last one
/// left out when closed.
double coefficientOfVariation(const std::vector<double>& values, bool closed);

} // namespace fiberpli
