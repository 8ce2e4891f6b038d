#include "Tissue/Undulation.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

namespace
{
// Cumulative arc length of a polyline (cum[0] = 0).
std::vector<double> arcLengths(const std::vector<Vec3>& p)
{
  std::vector<double> cum(p.size(), 0.0);
  for (std::size_t k = 1; k < p.size(); ++k)
    cum[k] = cum[k - 1] + distance(p[k - 1], p[k]);
  return cum;
}

// Index k of the piece [cum[k], cum[k+1]] holding s, searched forward from `from` (s never
// decreases in the callers) and the fraction within it.
std::size_t locate(const std::vector<double>& cum, double s, std::size_t from, double& f)
{
  std::size_t k = from;
  while (k + 2 < cum.size() && cum[k + 1] < s)
    ++k;
  const double len = cum[k + 1] - cum[k];
  f = len > 0.0 ? std::clamp((s - cum[k]) / len, 0.0, 1.0) : 0.0;
  return k;
}

Vec3 lerp(const Vec3& a, const Vec3& b, double f)
{
  return a + f * (b - a);
}

// Dense samples per output link: enough that equal-arc-length resampling follows the sine waves
// (a wave is at least several links long when the wavelength is above a few SegmentLengths).
constexpr std::size_t kDensity = 8;
} // namespace

BasePath straightBasePath(const Vec3& start, const Vec3& span, bool closed)
{
  const Vec3 t = normalized(span);
  int least = 0;
  for (int a = 1; a < 3; ++a)
    if (std::fabs(t[a]) < std::fabs(t[least]))
      least = a;
  Vec3 e;
  e[least] = 1.0;
  const Vec3 u = normalized(e - dot(e, t) * t);
  const Vec3 v = cross(t, u);
  BasePath b;
  b.points = { start, start + span };
  b.u = { u, u };
  b.v = { v, v };
  b.closed = closed;
  b.closure = closed ? span : Vec3{};
  return b;
}

Undulation drawUndulation(RandomStream& rng, double baseLength, double wavelength, bool closed)
{
  Undulation und;
  double sum = 0.0;
  for (int i = 0; i < kUndulationModes; ++i)
  {
    UndulationMode m;
    const double lambda = wavelength * std::exp(0.25 * rng.normal());
    m.cycles = baseLength / lambda;
    if (closed)
      m.cycles = std::max(1.0, std::round(m.cycles));
    m.weight = rng.uniform(0.5, 1.0);
    m.phaseU = rng.uniform(0.0, 2.0 * M_PI);
    m.phaseV = rng.uniform(0.0, 2.0 * M_PI);
    rng.next(); // spare: a fixed count of draws per mode
    sum += m.weight * m.weight;
    und.modes.push_back(m);
  }
  for (UndulationMode& m : und.modes)
    m.weight /= std::sqrt(sum);
  return und;
}

UndulationField drawUndulationField(RandomStream& rng, const Vec3& axis, const Vec3& across1,
  const Vec3& across2, double wavelength, double coherence, double period)
{
  UndulationField field;
  double sum = 0.0;
  for (int i = 0; i < kUndulationFieldWaves; ++i)
  {
    const double along = 2.0 * M_PI / (wavelength * std::exp(0.25 * rng.normal()));
    double q1 = rng.normal() / coherence;
    double q2 = rng.normal() / coherence;
    double ka = along;
    if (period > 0.0)
    {
      const double unit = 2.0 * M_PI / period;
      ka = unit * std::max(1.0, std::round(along / unit));
      q1 = unit * std::round(q1 / unit);
      q2 = unit * std::round(q2 / unit);
    }
    UndulationWave w;
    w.k = ka * axis + q1 * across1 + q2 * across2;
    w.weight = rng.uniform(0.5, 1.0);
    w.phaseU = rng.uniform(0.0, 2.0 * M_PI);
    w.phaseV = rng.uniform(0.0, 2.0 * M_PI);
    sum += w.weight * w.weight;
    field.waves.push_back(w);
  }
  for (UndulationWave& w : field.waves)
    w.weight /= std::sqrt(sum);
  return field;
}

Undulation sampleUndulationField(const UndulationField& field, const Vec3& start, const Vec3& span)
{
  Undulation und;
  for (const UndulationWave& w : field.waves)
  {
    UndulationMode m;
    m.cycles = dot(w.k, span) / (2.0 * M_PI);
    m.weight = w.weight;
    const double at = dot(w.k, start);
    m.phaseU = at + w.phaseU;
    m.phaseV = at + w.phaseV;
    und.modes.push_back(m);
  }
  return und;
}

void undulationDeviation(const Undulation& und, double t, bool closed, double& du, double& dv)
{
  const auto raw = [&](double x, double& a, double& b)
  {
    a = 0.0;
    b = 0.0;
    for (const UndulationMode& m : und.modes)
    {
      a += m.weight * std::sin(2.0 * M_PI * m.cycles * x + m.phaseU);
      b += m.weight * std::sin(2.0 * M_PI * m.cycles * x + m.phaseV);
    }
  };
  raw(t, du, dv);
  if (closed)
    return;
  // Open fibers: remove the straight trend so that both ends stay on the base path (the fiber's
  // end-to-end vector is the base's, which dispersion chose).
  double u0, v0, u1, v1;
  raw(0.0, u0, v0);
  raw(1.0, u1, v1);
  du -= (1.0 - t) * u0 + t * u1;
  dv -= (1.0 - t) * v0 + t * v1;
}

namespace
{
// The dense samples of the curve base(s) + amplitude·(du(s)·u(s) + dv(s)·v(s)) that do not depend
// on the amplitude: the base point and the deviation direction du·u + dv·v of each (left empty for
// amplitude 0). The sines are nearly all of an undulated fiber's cost, and the calibration
// evaluates the curve at some fifty amplitudes: it samples once.
struct DenseUndulation
{
  std::vector<Vec3> base;
  std::vector<Vec3> deviation;
};

DenseUndulation sampleDense(
  const BasePath& base, const Undulation& und, std::size_t points, bool withDeviation)
{
  const std::vector<double> baseCum = arcLengths(base.points);
  const double baseLength = baseCum.back();
  const std::size_t dense = kDensity * std::max(points, base.points.size());
  DenseUndulation d;
  d.base.resize(dense + 1);
  d.deviation.resize(withDeviation ? dense + 1 : 0);
  std::size_t k = 0;
  for (std::size_t j = 0; j <= dense; ++j)
  {
    const double t = static_cast<double>(j) / static_cast<double>(dense);
    double f = 0.0;
    k = locate(baseCum, t * baseLength, k, f);
    d.base[j] = lerp(base.points[k], base.points[k + 1], f);
    if (!withDeviation)
      continue;
    const Vec3 u = normalized(lerp(base.u[k], base.u[k + 1], f));
    const Vec3 v = normalized(lerp(base.v[k], base.v[k + 1], f));
    double du = 0.0, dv = 0.0;
    undulationDeviation(und, t, base.closed, du, dv);
    d.deviation[j] = du * u + dv * v;
  }
  return d;
}

// The curve at this amplitude resampled to `points` points equally spaced in arc length.
std::vector<Vec3> resampleDense(
  const DenseUndulation& d, const BasePath& base, double amplitude, std::size_t points)
{
  const std::size_t n = d.base.size();
  std::vector<Vec3> curve(n);
  for (std::size_t j = 0; j < n; ++j)
  {
    Vec3 c = d.base[j];
    if (amplitude != 0.0)
      c += amplitude * d.deviation[j];
    curve[j] = c;
  }
  // Equal arc length along the dense curve.
  const std::vector<double> cum = arcLengths(curve);
  std::vector<Vec3> out(points);
  std::size_t j = 0;
  for (std::size_t i = 0; i < points; ++i)
  {
    const double s = cum.back() * static_cast<double>(i) / static_cast<double>(points - 1);
    double f = 0.0;
    j = locate(cum, s, j, f);
    out[i] = lerp(curve[j], curve[j + 1], f);
  }
  out.front() = curve.front();
  out.back() = base.closed ? curve.front() + base.closure : curve.back();
  return out;
}
} // namespace

std::vector<Vec3> undulatedPath(
  const BasePath& base, const Undulation& und, double amplitude, std::size_t points)
{
  points = std::max<std::size_t>(points, 2);
  return resampleDense(sampleDense(base, und, points, amplitude != 0.0), base, amplitude, points);
}

double jitteredLength(const std::vector<Vec3>& p, const std::vector<Vec3>* jitter)
{
  double len = 0.0;
  for (std::size_t i = 1; i < p.size(); ++i)
  {
    Vec3 d = p[i] - p[i - 1];
    if (jitter)
      d += (*jitter)[i] - (*jitter)[i - 1];
    len += norm(d);
  }
  return len;
}

bool calibrateUndulation(const BasePath& base, Undulation& und, double tortuosity,
  std::size_t points, const std::vector<Vec3>* jitter)
{
  double baseLength = arcLengths(base.points).back();
  // Jittered ends move the end-to-end distance of an open fiber; the target is relative to it
  // (for a straight base exactly the end-to-end distance, for a curved one scaled alike).
  if (jitter && !base.closed && !jitter->empty())
  {
    const Vec3 ends = base.points.back() - base.points.front();
    const double moved = norm(ends + jitter->back() - jitter->front());
    if (norm(ends) > 0.0)
      baseLength *= moved / norm(ends);
  }
  points = std::max<std::size_t>(points, 2);
  const DenseUndulation dense = sampleDense(base, und, points, true);
  const auto ratio = [&](double a)
  { return jitteredLength(resampleDense(dense, base, a, points), jitter) / baseLength; };
  und.amplitude = 0.0;
  if (!(baseLength > 0.0) || ratio(0.0) >= tortuosity)
    return false;
  // Bracket: the deviation's amplitude grows until the fiber is long enough.
  double lo = 0.0;
  double hi = 1e-3 * baseLength;
  for (int i = 0; i < 80 && ratio(hi) < tortuosity; ++i)
  {
    lo = hi;
    hi *= 2.0;
  }
  const double excess = tortuosity - 1.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    const double r = ratio(mid);
    if (std::fabs(r - tortuosity) <= 1e-6 * excess)
    {
      lo = hi = mid;
      break;
    }
    (r < tortuosity ? lo : hi) = mid;
  }
  und.amplitude = 0.5 * (lo + hi);
  return true;
}

std::size_t undulatedPointCount(
  double baseLength, double tortuosity, double segmentLength, std::size_t minimum)
{
  const double n = std::round(tortuosity * baseLength / segmentLength) + 1.0;
  return std::max<std::size_t>(minimum, static_cast<std::size_t>(std::max(2.0, n)));
}

} // namespace fiberpli
