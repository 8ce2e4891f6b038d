#include "Analysis/TiltFit.h"
#include "Analysis/ForEachPixel.h"
#include "Model/DataNames.h"

#include "Analysis/Axis.h"
#include "Util/Angles.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace fiberpli
{

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// sinc(x) = sin x / x and its derivative, with series where the closed forms cancel.
void sinc(double x, double& f, double& df)
{
  if (std::abs(x) < 1e-2)
  {
    const double x2 = x * x;
    f = 1.0 - x2 / 6.0 + x2 * x2 / 120.0;
    df = x * (-1.0 / 3.0 + x2 / 30.0 - x2 * x2 / 840.0);
  }
  else
  {
    f = std::sin(x) / x;
    df = (x * std::cos(x) - std::sin(x)) / (x * x);
  }
}

// Solves the 3×3 system a·x = b by Gaussian elimination with partial pivoting; false if singular.
bool solve3(double a[3][3], double b[3], double x[3])
{
  for (int c = 0; c < 3; ++c)
  {
    int piv = c;
    for (int r = c + 1; r < 3; ++r)
    {
      if (std::abs(a[r][c]) > std::abs(a[piv][c]))
      {
        piv = r;
      }
    }
    if (!(std::abs(a[piv][c]) > 0.0))
    {
      return false;
    }
    if (piv != c)
    {
      for (int k = 0; k < 3; ++k)
      {
        std::swap(a[c][k], a[piv][k]);
      }
      std::swap(b[c], b[piv]);
    }
    for (int r = c + 1; r < 3; ++r)
    {
      const double f = a[r][c] / a[c][c];
      for (int k = c; k < 3; ++k)
      {
        a[r][k] -= f * a[c][k];
      }
      b[r] -= f * b[c];
    }
  }
  for (int r = 2; r >= 0; --r)
  {
    double s = b[r];
    for (int k = r + 1; k < 3; ++k)
    {
      s -= a[r][k] * x[k];
    }
    x[r] = s / a[r][r];
  }
  return true;
}
} // namespace

struct TiltFit::Data
{
  std::vector<double> y; // views·N normalised intensities
  std::vector<double> w; // weights 1/σ
};

std::string TiltFit::init(const std::vector<double>& rho, const TiltFitOptions& options)
{
  if (rho.size() < 4)
  {
    std::ostringstream msg;
    msg << "the tilt fit needs at least 4 polarizer angles, " << plifield::kPolarizerAngles
        << " has " << rho.size();
    return msg.str();
  }
  std::string err = epa_.init(rho);
  if (!err.empty())
  {
    return err;
  }
  if (options.views.size() < 2)
  {
    std::ostringstream msg;
    msg << "the tilt fit needs at least 2 tilted views, the input has " << options.views.size();
    return msg.str();
  }
  for (std::size_t v = 0; v < options.views.size(); ++v)
  {
    const TiltView& t = options.views[v];
    std::ostringstream msg;
    if (!std::isfinite(t.theta) || t.theta <= 0.0 || t.theta >= M_PI / 2)
      msg << plifield::kTiltAngles << "[" << v << "] is " << t.theta * 180.0 / M_PI
          << " deg, the tilt fit needs a value in (0, 90)";
    else if (!std::isfinite(t.azimuth))
      msg << "tilt_directions[" << v << "] is " << t.azimuth * 180.0 / M_PI
          << " deg, must be finite";
    for (std::size_t u = 0; u < v && msg.str().empty(); ++u)
    {
      const double dphi = std::remainder(t.azimuth - options.views[u].azimuth, 2.0 * M_PI);
      if (t.theta == options.views[u].theta && std::fabs(dphi) < 1e-12)
        msg << "tilted views " << u << " and " << v << " are the same (tilt "
            << t.theta * 180.0 / M_PI << " deg, azimuth " << t.azimuth * 180.0 / M_PI << " deg)";
    }
    if (!msg.str().empty())
      return msg.str();
  }
  if (options.maxIterations < 1)
  {
    return mustBe("maxIterations", options.maxIterations, ">= 1");
  }
  maxIterations_ = options.maxIterations;
  gain_ = options.gain > 0.0 && std::isfinite(options.gain) ? options.gain : 1.0;
  s_.resize(rho.size());
  c_.resize(rho.size());
  for (std::size_t k = 0; k < rho.size(); ++k)
  {
    s_[k] = std::sin(2.0 * rho[k]);
    c_[k] = std::cos(2.0 * rho[k]);
  }
  // View 0 is the identity; the tilted views use R(τ, ψ) of docs/pli-simulation.md §4.3.
  frames_.assign(
    1 + options.views.size(), Frame{ { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } }, M_PI / 2.0 });
  for (std::size_t j = 1; j < frames_.size(); ++j)
  {
    const TiltView& t = options.views[j - 1];
    const double c = std::cos(t.theta), s = std::sin(t.theta);
    double cp, sp;
    cosSinQuarterExact(t.azimuth, cp, sp);
    const double R[3][3] = { { c * cp * cp + sp * sp, (c - 1) * sp * cp, s * cp },
      { (c - 1) * sp * cp, c * sp * sp + cp * cp, s * sp }, { -s * cp, -s * sp, c } };
    for (int r = 0; r < 3; ++r)
    {
      for (int q = 0; q < 3; ++q)
      {
        frames_[j].m[r][q] = options.convention == TiltConvention::Physical ? R[q][r] : R[r][q];
      }
    }
    frames_[j].kappa = M_PI / (2.0 * c); // path d/cos τ: t_j = t/cos τ
  }
  return {};
}

// χ² at p = (φ, α, t); fills r (views·N weighted residuals) and, if J is set, dr/dp.
double TiltFit::residuals(const Data& d, const double p[3], double* r, double (*J)[3]) const
{
  const std::size_t n = s_.size();
  const double ca = std::cos(p[1]), sa = std::sin(p[1]), cf = std::cos(p[0]), sf = std::sin(p[0]);
  const double v[3] = { ca * cf, ca * sf, sa };
  const double dvf[3] = { -ca * sf, ca * cf, 0.0 };
  const double dva[3] = { -sa * cf, -sa * sf, ca };
  const double at = std::abs(p[2]);
  const double sgn = p[2] < 0.0 ? -1.0 : 1.0;
  double chi2 = 0.0;
  for (std::size_t j = 0; j < frames_.size(); ++j)
  {
    const auto& m = frames_[j].m;
    const double vx = m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2];
    const double vy = m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2];
    const double q = vx * vx + vy * vy; // cos²α_j
    const double P = vx * vx - vy * vy; // q·cos 2φ_j
    const double Q = 2.0 * vx * vy;     // q·sin 2φ_j
    // m_jk = sin(κ|t|q)·(s_k P − c_k Q)/q = κ|t|·sinc(κ|t|q)·g_k: finite for a vertical axis.
    const double a = frames_[j].kappa * at;
    double sc, dsc;
    sinc(a * q, sc, dsc);
    const double f = a * sc;                                    // sin(aq)/q
    const double fq = a * a * dsc;                              // d f / d q
    const double ft = frames_[j].kappa * std::cos(a * q) * sgn; // d(sin(aq)/q)/dt · q / q
    double dxf = 0, dyf = 0, dxa = 0, dya = 0;
    if (J)
    {
      dxf = m[0][0] * dvf[0] + m[0][1] * dvf[1] + m[0][2] * dvf[2];
      dyf = m[1][0] * dvf[0] + m[1][1] * dvf[1] + m[1][2] * dvf[2];
      dxa = m[0][0] * dva[0] + m[0][1] * dva[1] + m[0][2] * dva[2];
      dya = m[1][0] * dva[0] + m[1][1] * dva[1] + m[1][2] * dva[2];
    }
    for (std::size_t k = 0; k < n; ++k)
    {
      const std::size_t idx = j * n + k;
      const double g = s_[k] * P - c_[k] * Q;
      const double model = f * g;
      const double w = d.w[idx];
      r[idx] = w * (d.y[idx] - model);
      chi2 += r[idx] * r[idx];
      if (J)
      {
        const double dmx = fq * 2.0 * vx * g + f * 2.0 * (s_[k] * vx - c_[k] * vy);
        const double dmy = fq * 2.0 * vy * g + f * 2.0 * (-s_[k] * vy - c_[k] * vx);
        J[idx][0] = -w * (dmx * dxf + dmy * dyf);
        J[idx][1] = -w * (dmx * dxa + dmy * dya);
        J[idx][2] = -w * ft * g;
      }
    }
  }
  return chi2;
}

TiltFitResult TiltFit::pixel(const std::vector<const double*>& views) const
{
  TiltFitResult res{ kNaN, kNaN, kNaN, kNaN, kNaN, 0 };
  const std::size_t n = s_.size();
  const std::size_t nv = frames_.size();
  if (views.size() != nv)
  {
    return res;
  }
  const double dn = static_cast<double>(n);
  Data d;
  d.y.resize(nv * n);
  d.w.resize(nv * n);
  double phi0 = 0.0;
  for (std::size_t j = 0; j < nv; ++j)
  {
    const double* I = views[j];
    const Harmonic h = epa_.harmonic(I);
    const double A = h.a0;
    if (!std::isfinite(A) || A <= 0.0)
    {
      return res;
    }
    if (j == 0)
    {
      phi0 = epaFromHarmonic(h).direction;
    }
    for (std::size_t k = 0; k < n; ++k)
    {
      if (!std::isfinite(I[k]))
      {
        return res;
      }
      const double var = gain_ * (I[k] / (A * A) + I[k] * I[k] / (A * A * A * dn));
      const double sigma = var > 0.0 ? std::sqrt(var) : 0.0;
      d.y[j * n + k] = I[k] / A - 1.0;
      d.w[j * n + k] = 1.0 / (sigma > 1e-12 ? sigma : 1e-12);
    }
  }

  std::vector<double> r(nv * n), rTry(nv * n);
  std::vector<double> Jstore(3 * nv * n);
  auto* J = reinterpret_cast<double(*)[3]>(Jstore.data());

  // Start grid of fastPLI's ROFL: interior of linspace(−90°, 90°, 8) × interior of linspace(0, 0.9,
  // 8).
  double p[3] = { phi0, 0.0, 0.0 };
  double best = std::numeric_limits<double>::infinity();
  for (int ia = 1; ia <= 6; ++ia)
  {
    for (int it = 1; it <= 6; ++it)
    {
      const double trial[3] = { phi0, (-90.0 + ia * 180.0 / 7.0) * M_PI / 180.0, it * 0.9 / 7.0 };
      const double c2 = residuals(d, trial, r.data(), nullptr);
      if (c2 < best)
      {
        best = c2;
        p[1] = trial[1];
        p[2] = trial[2];
      }
    }
  }

  // Levenberg–Marquardt with Marquardt's diagonal scaling.
  double chi2 = residuals(d, p, r.data(), J);
  double lambda = 1e-3;
  int iter = 0;
  while (iter < maxIterations_ && chi2 > 0.0)
  {
    ++iter;
    double A[3][3] = {}, g[3] = {};
    for (std::size_t i = 0; i < nv * n; ++i)
    {
      for (int a = 0; a < 3; ++a)
      {
        g[a] += J[i][a] * r[i];
        for (int b = 0; b < 3; ++b)
        {
          A[a][b] += J[i][a] * J[i][b];
        }
      }
    }
    const double maxDiag = std::max(A[0][0], std::max(A[1][1], A[2][2]));
    double M[3][3], rhs[3] = { -g[0], -g[1], -g[2] }, step[3];
    for (int a = 0; a < 3; ++a)
    {
      for (int b = 0; b < 3; ++b)
      {
        M[a][b] = A[a][b];
      }
      M[a][a] += lambda * std::max(A[a][a], 1e-15 * maxDiag);
    }
    if (!solve3(M, rhs, step))
    {
      lambda *= 10.0;
      if (lambda > 1e20)
      {
        break;
      }
      continue;
    }
    const double trial[3] = { p[0] + step[0], p[1] + step[1], p[2] + step[2] };
    const double c2 = residuals(d, trial, rTry.data(), nullptr);
    const double stepNorm = std::sqrt(step[0] * step[0] + step[1] * step[1] + step[2] * step[2]);
    if (c2 < chi2)
    {
      const double rel = (chi2 - c2) / chi2;
      p[0] = trial[0];
      p[1] = trial[1];
      p[2] = trial[2];
      chi2 = residuals(d, p, r.data(), J);
      lambda = std::max(lambda * 0.1, 1e-12);
      if (rel < 1e-12 || stepNorm < 1e-10)
      {
        break;
      }
    }
    else
    {
      lambda *= 10.0;
      if (stepNorm < 1e-10 || lambda > 1e20)
      {
        break; // no downhill step is left at this precision
      }
    }
  }

  axisAngles(axisFromAngles(p[0], p[1]), res.direction, res.inclinationSigned);
  res.inclination = std::abs(res.inclinationSigned);
  res.relativeThickness = std::abs(p[2]);
  res.chi2 = chi2;
  res.iterations = iter;
  return res;
}

std::vector<TiltView> fourTiltViews(double theta)
{
  return { { theta, 0.0 }, { theta, M_PI / 2 }, { theta, M_PI }, { theta, 3 * M_PI / 2 } };
}

Status computeTiltFit(const double* flat, const std::vector<const double*>& tilts, std::int64_t nx,
  std::int64_t ny, const std::vector<double>& rho, const TiltFitOptions& options,
  const GridRange& range, int threads, TiltMaps& maps, const ProgressFn& progress)
{
  TiltFit fit;
  std::string err = fit.init(rho, options);
  if (!err.empty())
  {
    return err;
  }
  err = validatePixelRange(nx, ny, range);
  if (!err.empty())
  {
    return err;
  }
  if (range.count() > 0)
  {
    if (!flat)
    {
      return "intensity stack is null";
    }
    if (tilts.size() != options.views.size())
    {
      std::ostringstream msg;
      msg << tilts.size() << " tilted stacks for " << options.views.size() << " tilted views";
      return msg.str();
    }
    for (std::size_t t = 0; t < tilts.size(); ++t)
    {
      if (!tilts[t])
      {
        std::ostringstream msg;
        msg << plifield::intensityTilt(t) << " is missing";
        return msg.str();
      }
    }
  }
  const std::size_t npx = static_cast<std::size_t>(nx * ny);
  for (auto* v : { &maps.direction, &maps.inclination, &maps.inclinationSigned,
         &maps.relativeThickness, &maps.chi2 })
  {
    v->resize(npx, kNaN);
  }
  const std::size_t n = rho.size();
  const bool done = forEachPixel(nx, range, threads, progress,
    [&](std::int64_t p)
    {
      const std::size_t off = static_cast<std::size_t>(p) * n;
      std::vector<const double*> views{ flat + off };
      for (const double* t : tilts)
        views.push_back(t + off);
      const TiltFitResult f = fit.pixel(views);
      maps.direction[p] = f.direction;
      maps.inclination[p] = f.inclination;
      maps.inclinationSigned[p] = f.inclinationSigned;
      maps.relativeThickness[p] = f.relativeThickness;
      maps.chi2[p] = f.chi2;
    });
  return done ? Status() : Status::stopped();
}

} // namespace fiberpli
