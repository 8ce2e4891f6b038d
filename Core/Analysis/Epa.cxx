#include "Analysis/Epa.h"
#include "Analysis/ForEachPixel.h"
#include "Model/DataNames.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace fiberpli
{

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// §2.2: ρ_k = ρ_0 + kπ/N within 1e-9 rad, in the order given.
bool isEquidistant(const std::vector<double>& rho)
{
  const double n = static_cast<double>(rho.size());
  for (std::size_t k = 0; k < rho.size(); ++k)
  {
    if (std::abs(rho[k] - (rho[0] + static_cast<double>(k) * M_PI / n)) > 1e-9)
    {
      return false;
    }
  }
  return true;
}

double norm1(const double m[3][3])
{
  double best = 0.0;
  for (int c = 0; c < 3; ++c)
  {
    const double s = std::abs(m[0][c]) + std::abs(m[1][c]) + std::abs(m[2][c]);
    best = s > best ? s : best;
  }
  return best;
}

// Inverse by the adjugate; returns the determinant (the caller judges singularity by rcond).
double invert3(const double a[3][3], double inv[3][3])
{
  inv[0][0] = a[1][1] * a[2][2] - a[1][2] * a[2][1];
  inv[0][1] = a[0][2] * a[2][1] - a[0][1] * a[2][2];
  inv[0][2] = a[0][1] * a[1][2] - a[0][2] * a[1][1];
  inv[1][0] = a[1][2] * a[2][0] - a[1][0] * a[2][2];
  inv[1][1] = a[0][0] * a[2][2] - a[0][2] * a[2][0];
  inv[1][2] = a[0][2] * a[1][0] - a[0][0] * a[1][2];
  inv[2][0] = a[1][0] * a[2][1] - a[1][1] * a[2][0];
  inv[2][1] = a[0][1] * a[2][0] - a[0][0] * a[2][1];
  inv[2][2] = a[0][0] * a[1][1] - a[0][1] * a[1][0];
  const double det = a[0][0] * inv[0][0] + a[0][1] * inv[1][0] + a[0][2] * inv[2][0];
  if (det != 0.0)
  {
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        inv[r][c] /= det;
      }
    }
  }
  return det;
}
} // namespace

std::string EpaFit::init(const std::vector<double>& rho)
{
  w0_.clear();
  w1_.clear();
  wb_.clear();
  equidistant_ = false;
  const std::size_t n = rho.size();
  if (n < 3)
  {
    std::ostringstream msg;
    msg << plifield::kPolarizerAngles << " has " << n << " angle(s), the analysis needs at least 3";
    return msg.str();
  }
  for (std::size_t k = 0; k < n; ++k)
  {
    if (!std::isfinite(rho[k]))
    {
      std::ostringstream msg;
      msg << "polarizer angle " << k << " is not finite";
      return msg.str();
    }
  }
  std::vector<double> s(n), c(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    s[k] = std::sin(2.0 * rho[k]);
    c[k] = std::cos(2.0 * rho[k]);
  }
  w0_.resize(n);
  w1_.resize(n);
  wb_.resize(n);
  if (isEquidistant(rho))
  {
    equidistant_ = true;
    const double dn = static_cast<double>(n);
    for (std::size_t k = 0; k < n; ++k)
    {
      w0_[k] = 1.0 / dn;
      w1_[k] = 2.0 * s[k] / dn;
      wb_[k] = 2.0 * c[k] / dn;
    }
    return {};
  }
  double a[3][3] = { { 0, 0, 0 }, { 0, 0, 0 }, { 0, 0, 0 } };
  for (std::size_t k = 0; k < n; ++k)
  {
    const double x[3] = { 1.0, s[k], c[k] };
    for (int r = 0; r < 3; ++r)
    {
      for (int q = 0; q < 3; ++q)
      {
        a[r][q] += x[r] * x[q];
      }
    }
  }
  double inv[3][3];
  const double det = invert3(a, inv);
  const double rcond = det == 0.0 ? 0.0 : 1.0 / (norm1(a) * norm1(inv));
  if (!(rcond >= 1e-10))
  {
    w0_.clear();
    w1_.clear();
    wb_.clear();
    std::ostringstream msg;
    msg << plifield::kPolarizerAngles
        << " do not determine the first harmonic (fewer than 3 distinct values of "
           "2*rho mod 360 deg; reciprocal condition number "
        << rcond << " < 1e-10)";
    return msg.str();
  }
  for (std::size_t k = 0; k < n; ++k)
  {
    const double x[3] = { 1.0, s[k], c[k] };
    w0_[k] = inv[0][0] * x[0] + inv[0][1] * x[1] + inv[0][2] * x[2];
    w1_[k] = inv[1][0] * x[0] + inv[1][1] * x[1] + inv[1][2] * x[2];
    wb_[k] = inv[2][0] * x[0] + inv[2][1] * x[1] + inv[2][2] * x[2];
  }
  return {};
}

Harmonic EpaFit::harmonic(const double* I) const
{
  Harmonic h;
  for (std::size_t k = 0; k < w0_.size(); ++k)
  {
    h.a0 += w0_[k] * I[k];
    h.a1 += w1_[k] * I[k];
    h.b1 += wb_[k] * I[k];
  }
  return h;
}

EpaPixel EpaFit::pixel(const double* I) const
{
  return epaFromHarmonic(harmonic(I));
}

EpaPixel epaFromHarmonic(const Harmonic& h)
{
  EpaPixel p;
  if (!(std::isfinite(h.a0) && std::isfinite(h.a1) && std::isfinite(h.b1)) || h.a0 <= 0.0)
  {
    p.transmittance = p.direction = p.retardation = kNaN;
    return p;
  }
  const double amp = std::hypot(h.a1, h.b1);
  p.transmittance = 2.0 * h.a0;
  // a1 = a0·r·cos 2φ and b1 = −a0·r·sin 2φ (§2.3): the sign makes φ the fiber axis.
  double phi = amp <= 1e-12 * std::abs(h.a0) ? 0.0 : 0.5 * std::atan2(-h.b1, h.a1);
  phi = std::fmod(phi, M_PI);
  if (phi < 0.0)
  {
    phi += M_PI;
  }
  if (phi >= M_PI)
  {
    phi = 0.0; // −ε + π rounds to π: keep the documented half-open range [0, π)
  }
  p.direction = phi;
  const double r = amp / h.a0;
  p.retardation = r > 1.0 ? 1.0 : r; // noise can push it past 1 (§1 decision)
  return p;
}

Status computeEpa(const double* stack, std::int64_t nx, std::int64_t ny,
  const std::vector<double>& rho, const GridRange& range, int threads, EpaMaps& maps,
  const ProgressFn& progress)
{
  EpaFit fit;
  std::string err = fit.init(rho);
  if (!err.empty())
  {
    return err;
  }
  err = validatePixelRange(nx, ny, range);
  if (!err.empty())
  {
    return err;
  }
  if (!stack && range.count() > 0)
  {
    return "intensity stack is null";
  }
  const std::size_t npx = static_cast<std::size_t>(nx * ny);
  maps.transmittance.resize(npx, kNaN);
  maps.direction.resize(npx, kNaN);
  maps.retardation.resize(npx, kNaN);
  const std::size_t nrho = rho.size();
  const bool done = forEachPixel(nx, range, threads, progress,
    [&](std::int64_t p)
    {
      const EpaPixel e = fit.pixel(stack + static_cast<std::size_t>(p) * nrho);
      maps.transmittance[p] = e.transmittance;
      maps.direction[p] = e.direction;
      maps.retardation[p] = e.retardation;
    });
  return done ? Status() : Status::stopped();
}

} // namespace fiberpli
