#include "PLI/Optics.h"

#include "Util/Random.h"
#include "Util/Threads.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fiberpli
{
namespace pli
{

std::int64_t gaussianRadius(double sigma)
{
  if (!(sigma > 0.0))
    return 0;
  const double r = std::floor(4.0 * sigma + 0.5);
  return r < static_cast<double>(kMaxGaussianRadius) ? static_cast<std::int64_t>(r) : -1;
}

std::vector<double> gaussianWeights(double sigma)
{
  if (!(sigma > 0.0))
    return { 1.0 };
  const std::int64_t R = gaussianRadius(sigma);
  if (R < 0)
    return {};
  std::vector<double> w(static_cast<std::size_t>(2 * R + 1));
  double sum = 0.0;
  for (std::int64_t m = -R; m <= R; ++m)
  {
    w[static_cast<std::size_t>(m + R)] =
      std::exp(-static_cast<double>(m) * static_cast<double>(m) / (2.0 * sigma * sigma));
    sum += w[static_cast<std::size_t>(m + R)];
  }
  for (double& x : w)
    x /= sum;
  return w;
}

std::int64_t mirrorIndex(std::int64_t i, std::int64_t n)
{
  const std::int64_t period = 2 * n;
  std::int64_t r = i % period;
  if (r < 0)
    r += period;
  return r < n ? r : period - 1 - r;
}

Status blurStack(const Stack& in, std::int64_t nGX, std::int64_t nGY, double sigma,
  const GridRange& range, Stack& out)
{
  Status st;
  const std::int64_t R = gaussianRadius(sigma);
  if (R < 0 || R > 2 * std::max(nGX, nGY))
  {
    std::ostringstream m;
    m << "blur: sigma " << sigma << " voxels gives a kernel wider than twice the " << nGX << " x "
      << nGY << " voxel image";
    st.error = m.str();
    return st;
  }
  const std::vector<double> w = gaussianWeights(sigma);
  const int nr = in.nrho;
  // The kernel reads mirror(a + m) for a in [a0, a1), |m| <= R: the mirror image of the contiguous
  // range [a0 − R, a1 − 1 + R], itself contiguous, all of [0, n) once it spans a period 2n.
  auto covered =
    [&](std::int64_t a0, std::int64_t a1, std::int64_t n, std::int64_t have0, std::int64_t have1)
  {
    if (a1 <= a0)
      return true;
    std::int64_t lo = n, hi = -1;
    const std::int64_t first = a0 - R, last = std::min(a1 - 1 + R, a0 - R + 2 * n - 1);
    for (std::int64_t v = first; v <= last; ++v)
    {
      const std::int64_t s = mirrorIndex(v, n);
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
    return lo >= have0 && hi < have1;
  };
  if (!covered(range.i0, range.i1, nGX, in.x0, in.x0 + in.nx) ||
    !covered(range.j0, range.j1, nGY, in.y0, in.y0 + in.ny))
  {
    st.error = "blur: the voxel piece does not hold the kernel halo of the requested range";
    return st;
  }
  // x pass over every row of the piece, then y pass.
  Stack tmp;
  tmp.resize(GridRange{ range.i0, range.i1, in.y0, in.y0 + in.ny }, nr);
  for (std::int64_t j = in.y0; j < in.y0 + in.ny; ++j)
    for (std::int64_t i = range.i0; i < range.i1; ++i)
    {
      double* dst = &tmp.at(i, j, 0);
      for (std::int64_t m = -R; m <= R; ++m)
      {
        const double wm = w[static_cast<std::size_t>(m + R)];
        const double* src = in.ptr(mirrorIndex(i + m, nGX), j);
        for (int k = 0; k < nr; ++k)
          dst[k] += wm * src[k];
      }
    }
  out.resize(range, nr);
  for (std::int64_t j = range.j0; j < range.j1; ++j)
    for (std::int64_t i = range.i0; i < range.i1; ++i)
    {
      double* dst = &out.at(i, j, 0);
      for (std::int64_t m = -R; m <= R; ++m)
      {
        const double wm = w[static_cast<std::size_t>(m + R)];
        const double* src = tmp.ptr(i, mirrorIndex(j + m, nGY));
        for (int k = 0; k < nr; ++k)
          dst[k] += wm * src[k];
      }
    }
  return st;
}

Status binStack(const Stack& in, std::int64_t nVX, std::int64_t nVY, double scale,
  const GridRange& px, Stack& out)
{
  Status st;
  const int nr = in.nrho;
  out.resize(px, nr);
  for (std::int64_t q = px.j0; q < px.j1; ++q)
  {
    std::int64_t y0, y1;
    voxelsOfPixel(q, scale, nVY, y0, y1);
    for (std::int64_t p = px.i0; p < px.i1; ++p)
    {
      std::int64_t x0, x1;
      voxelsOfPixel(p, scale, nVX, x0, x1);
      if (x0 < in.x0 || x1 > in.x0 + in.nx || y0 < in.y0 || y1 > in.y0 + in.ny || x1 <= x0 ||
        y1 <= y0)
      {
        std::ostringstream m;
        m << "binning: pixel (" << p << "," << q << ") needs voxels outside the piece";
        st.error = m.str();
        return st;
      }
      double* dst = &out.at(p, q, 0);
      for (std::int64_t j = y0; j < y1; ++j)
        for (std::int64_t i = x0; i < x1; ++i)
        {
          const double* src = in.ptr(i, j);
          for (int k = 0; k < nr; ++k)
            dst[k] += src[k];
        }
      const double inv = 1.0 / static_cast<double>((x1 - x0) * (y1 - y0));
      for (int k = 0; k < nr; ++k)
        dst[k] *= inv;
    }
  }
  return st;
}

namespace
{
// Marsaglia–Tsang (2000); shape < 1 via the U^(1/a) boost.
double sampleGamma(RandomStream& rng, double shape)
{
  double boost = 1.0;
  if (shape < 1.0)
  {
    boost = std::pow(1.0 - rng.uniform(), 1.0 / shape);
    shape += 1.0;
  }
  const double d = shape - 1.0 / 3.0, c = 1.0 / std::sqrt(9.0 * d);
  for (;;)
  {
    double x, v;
    do
    {
      x = rng.normal();
      v = 1.0 + c * x;
    } while (v <= 0.0);
    v = v * v * v;
    const double u = 1.0 - rng.uniform();
    if (u < 1.0 - 0.0331 * x * x * x * x || std::log(u) < 0.5 * x * x + d * (1.0 - v + std::log(v)))
      return boost * d * v;
  }
}

// log(k!) without std::lgamma (which writes the global signgam: a data race under OpenMP).
double logFactorial(double k)
{
  if (k < 16.0)
  {
    double s = 0.0;
    for (int i = 2; i <= static_cast<int>(k); ++i)
      s += std::log(static_cast<double>(i));
    return s;
  }
  const double n = k + 1.0, n2 = n * n;
  return (n - 0.5) * std::log(n) - n + 0.5 * std::log(2.0 * M_PI) + 1.0 / (12.0 * n) -
    1.0 / (360.0 * n * n2) + 1.0 / (1260.0 * n * n2 * n2);
}

double samplePoisson(RandomStream& rng, double lambda)
{
  if (lambda < 10.0)
  {
    // Inversion by sequential search.
    double p = std::exp(-lambda), s = p;
    const double u = rng.uniform();
    double x = 0.0;
    while (u > s && x < 1000.0)
    {
      x += 1.0;
      p *= lambda / x;
      s += p;
    }
    return x;
  }
  // PTRS, Hörmann (1993), transformed rejection with squeeze.
  const double slam = std::sqrt(lambda), loglam = std::log(lambda);
  const double b = 0.931 + 2.53 * slam, a = -0.059 + 0.02483 * b;
  const double invalpha = 1.1239 + 1.1328 / (b - 3.4), vr = 0.9277 - 3.6224 / (b - 2.0);
  for (;;)
  {
    const double U = rng.uniform() - 0.5, V = rng.uniform();
    const double us = 0.5 - std::fabs(U);
    const double k = std::floor((2.0 * a / us + b) * U + lambda + 0.43);
    if (us >= 0.07 && V <= vr)
      return k;
    if (k < 0.0 || (us < 0.013 && V > us))
      continue;
    if (std::log(V) + std::log(invalpha) - std::log(a / (us * us) + b) <=
      -lambda + k * loglam - logFactorial(k))
      return k;
  }
}
} // namespace

double sampleCounts(
  double I, double gain, std::uint64_t seed, std::uint64_t key1, std::uint64_t key2)
{
  if (gain == 0.0 || !std::isfinite(I) || I <= 0.0)
    return I;
  RandomStream rng(seed, key1, key2);
  double lambda = I;
  if (gain > 1.0)
    lambda = sampleGamma(rng, I / (gain - 1.0)) * (gain - 1.0);
  return samplePoisson(rng, lambda);
}

void addNoise(Stack& px, double gain, std::uint64_t seed, int view, std::int64_t nPxX, int threads)
{
  if (gain == 0.0)
    return;
  const int n = resolveThreadCount(threads);
  const int nr = px.nrho;
#pragma omp parallel for schedule(static) num_threads(n)
  for (std::int64_t j = px.y0; j < px.y0 + px.ny; ++j)
    for (std::int64_t i = px.x0; i < px.x0 + px.nx; ++i)
      for (int k = 0; k < nr; ++k)
      {
        double& v = px.at(i, j, k);
        const std::uint64_t key1 = static_cast<std::uint64_t>(j * nPxX + i);
        const std::uint64_t key2 =
          (static_cast<std::uint64_t>(view) << 32) | static_cast<std::uint64_t>(k);
        v = sampleCounts(v, gain, seed, key1, key2);
      }
}

} // namespace pli
} // namespace fiberpli
