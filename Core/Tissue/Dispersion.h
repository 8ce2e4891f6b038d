/// Dispersion: fibers' end-to-end directions spread about their population's axis
/// (docs/tissue-models.md §10.2). Open models draw each fiber's axis from a Watson distribution
/// (density ∝ exp(κ·(μ·x)²) on the sphere) whose concentration κ gives the requested ⟨cos²⟩; in a
/// periodic cell a fiber's end-to-end vector must be a lattice vector, so the drawn direction is
/// replaced by the nearest direction of a short lattice vector (m periods along the axis, a and b
/// across, 1 <= m <= kMaxDispersionPeriods, |a|, |b| <= kMaxDispersionPeriods;
/// PopulationAxes.h, nearestLatticeDirection), and the achieved ⟨cos²⟩ is reported.
#pragma once

#include "Geometry/Vec3.h"
#include "Util/Random.h"

#include <cstdint>
#include <memory>
#include <vector>

namespace fiberpli
{

/// ⟨cos²θ⟩ of the Watson distribution of concentration κ >= 0 (κ = 0: isotropic, 1/3; large κ:
/// about 1 − 1/κ), by quadrature.
double watsonC2(double kappa);

/// The κ whose watsonC2 is c2 ∈ (1/3, 1) (bisection on log κ; 1e-10 relative in c2).
double watsonConcentration(double c2);

/// The distribution of t = |cos θ| of a Watson distribution, tabulated for sampling by inversion.
class WatsonTable
{
public:
  explicit WatsonTable(double kappa);
  /// t = F⁻¹(u) for u ∈ [0, 1): the |cos θ| of quantile u (increasing in κ for a fixed u).
  double cosine(double u) const;
  double kappa() const { return kappa_; }

private:
  double kappa_ = 0.0;
  double span_ = 1.0;       // the table covers x = 1 − t ∈ [0, span_]
  std::vector<double> cdf_; // mass of x ∈ [0, x_i], normalised
};

/// The table of the κ reaching c2 (watsonConcentration), shared by all fibers of a model: computed
/// once per c2 and kept (a few models' worth; safe to call from several threads).
std::shared_ptr<const WatsonTable> watsonTableForC2(double c2);

/// The table of concentration κ, kept like watsonTableForC2's.
std::shared_ptr<const WatsonTable> watsonTableForKappa(double kappa);

/// The quantile of |cos θ| of fiber `index` of a population: frac(offset + (index + ½)·g), g the
/// golden ratio's fraction (√5 − 1)/2, offset ∈ [0, 1) drawn once per population. The first N
/// fibers of any population then sample the distribution evenly (a low-discrepancy sequence), so
/// the population's ⟨cos²⟩ meets the target to O(log N / N) instead of the O(1/√N) of independent
/// draws, for every count; the azimuth stays an independent draw per fiber.
double dispersionQuantile(double offset, std::uint64_t index);

/// A direction about `axis` (unit) with |cos θ| = table.cosine(u1) and azimuth 2π·u2 around it,
/// (e1, e2) being the directions across the axis; always in the axis's hemisphere.
Vec3 watsonDirection(
  const Vec3& axis, const Vec3& e1, const Vec3& e2, const WatsonTable& table, double u1, double u2);

/// The most periods a dispersed periodic fiber spans along or across its axis.
constexpr int kMaxDispersionPeriods = 4;

} // namespace fiberpli
