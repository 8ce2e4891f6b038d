#include "Tissue/Beading.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

namespace
{
std::size_t counted(const std::vector<double>& v, bool closed)
{
  return closed && v.size() > 1 ? v.size() - 1 : v.size();
}
} // namespace

double coefficientOfVariation(const std::vector<double>& values, bool closed)
{
  const std::size_t n = counted(values, closed);
  if (n == 0)
    return 0.0;
  double mean = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    mean += values[i];
  mean /= static_cast<double>(n);
  double var = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    var += (values[i] - mean) * (values[i] - mean);
  var /= static_cast<double>(n);
  return mean != 0.0 ? std::sqrt(var) / mean : 0.0;
}

std::vector<double> beadingFactors(const BeadingProfile& p, double sigmaScale)
{
  const double s = sigmaScale * p.sigma;
  std::vector<double> f(p.field.size(), 1.0);
  const std::size_t n = counted(p.field, p.closed);
  if (n == 0)
    return f;
  double mean = 0.0;
  for (std::size_t i = 0; i < p.field.size(); ++i)
    f[i] = std::exp(s * p.field[i]);
  for (std::size_t i = 0; i < n; ++i)
    mean += f[i];
  mean /= static_cast<double>(n);
  for (double& x : f)
    x /= mean;
  return f;
}

BeadingProfile drawBeading(
  RandomStream& rng, const std::vector<double>& arc, double ell, double cv, bool closed)
{
  BeadingProfile p;
  p.closed = closed;
  p.field.assign(arc.size(), 0.0);
  if (arc.size() < 2 || !(arc.back() > 0.0))
    return p;
  const double length = arc.back();
  const double period = closed ? length : length + 4.0 * ell;
  // Squared-exponential correlation exp(−Δ²/2ℓ²): spectral weight exp(−(ωℓ)²/2) per mode, modes up
  // to ωℓ = 5 (the rest carries < 1e-5 of the variance).
  // No more modes than points over the period: finer waves are not resolved by the points (a
  // correlation length below the point spacing gives radii uncorrelated from point to point).
  const double spacing = length / static_cast<double>(arc.size() - 1);
  const int resolved = static_cast<int>(std::ceil(period / spacing)) + 1;
  const int modes = std::clamp(static_cast<int>(std::ceil(5.0 * period / (2.0 * M_PI * ell))), 1,
    std::min(kMaxBeadingModes, resolved));
  for (int m = 1; m <= modes; ++m)
  {
    const double omega = 2.0 * M_PI * m / period;
    const double w = std::exp(-0.25 * omega * omega * ell * ell); // sqrt of the spectral weight
    const double a = w * rng.normal();
    const double b = w * rng.normal();
    for (std::size_t i = 0; i < arc.size(); ++i)
      p.field[i] += a * std::cos(omega * arc[i]) + b * std::sin(omega * arc[i]);
  }
  if (closed)
    p.field.back() = p.field.front();
  // Standardise over the counted points, so that σ alone sets the variation.
  const std::size_t n = counted(p.field, closed);
  double mean = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    mean += p.field[i];
  mean /= static_cast<double>(n);
  double var = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    var += (p.field[i] - mean) * (p.field[i] - mean);
  const double sd = std::sqrt(var / static_cast<double>(n));
  for (double& g : p.field)
    g = sd > 0.0 ? (g - mean) / sd : 0.0;
  if (!(sd > 0.0) || !(cv > 0.0))
    return p;
  // The CV of exp(σ g) grows with σ from 0: bracket, then bisect.
  const auto cvOf = [&](double s)
  {
    BeadingProfile q = p;
    q.sigma = s;
    return coefficientOfVariation(beadingFactors(q), closed);
  };
  double lo = 0.0;
  double hi = cv;
  for (int i = 0; i < 60 && cvOf(hi) < cv; ++i)
  {
    lo = hi;
    hi *= 2.0;
  }
  for (int i = 0; i < 100 && hi - lo > 1e-14 * hi; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (cvOf(mid) < cv ? lo : hi) = mid;
  }
  p.sigma = 0.5 * (lo + hi);
  return p;
}

} // namespace fiberpli
