#include "Analysis/FiberOrientationMap.h"

#include "Util/Threads.h"
#include "Util/ValueCheck.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace fiberpli
{

namespace
{
// §4 quantisation: the 1e-6 keeps exact values such as 1.0 or 2/3 from dropping a level.
std::uint8_t q(double x)
{
  const double v = std::floor(255.0 * x + 1e-6);
  return static_cast<std::uint8_t>(v < 0.0 ? 0.0 : (v > 255.0 ? 255.0 : v));
}

Rgb8 hsvBlack(double d, double i)
{
  double h = std::fmod(2.0 * d, 360.0);
  if (h < 0.0)
  {
    h += 360.0;
  }
  const double v = 1.0 - i / 90.0;
  const double h6f = std::floor(h / 60.0);
  const double f = h / 60.0 - h6f;
  const double qq = v * (1.0 - f);
  const double t = v * f;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h6f) % 6)
  {
    case 0:
      r = v;
      g = t;
      b = 0;
      break;
    case 1:
      r = qq;
      g = v;
      b = 0;
      break;
    case 2:
      r = 0;
      g = v;
      b = t;
      break;
    case 3:
      r = 0;
      g = qq;
      b = v;
      break;
    case 4:
      r = t;
      g = 0;
      b = v;
      break;
    default:
      r = v;
      g = 0;
      b = qq;
      break;
  }
  return { q(r), q(g), q(b) };
}

Rgb8 rgbScheme(double d, double i)
{
  const double dr = d * M_PI / 180.0;
  const double ir = i * M_PI / 180.0;
  return { q(std::abs(std::cos(ir) * std::cos(dr))), q(std::abs(std::cos(ir) * std::sin(dr))),
    q(std::abs(std::sin(ir))) };
}
} // namespace

bool parseFomScheme(const std::string& name, FomScheme& scheme)
{
  if (name == "HSV-black")
  {
    scheme = FomScheme::HsvBlack;
    return true;
  }
  if (name == "RGB")
  {
    scheme = FomScheme::Rgb;
    return true;
  }
  return false;
}

const char* fomSchemeName(FomScheme scheme)
{
  return scheme == FomScheme::Rgb ? "RGB" : "HSV-black";
}

Rgb8 fomColor(double directionDeg, double inclinationDeg, FomScheme scheme)
{
  if (!std::isfinite(directionDeg) || !std::isfinite(inclinationDeg))
  {
    return {};
  }
  double i = std::abs(inclinationDeg);
  i = i > 90.0 ? 90.0 : i;
  return scheme == FomScheme::Rgb ? rgbScheme(directionDeg, i) : hsvBlack(directionDeg, i);
}

std::string fomMap(const double* directionDeg, const double* inclinationDeg, std::size_t n,
  FomScheme scheme, int threads, std::uint8_t* rgb)
{
  if (n > 0 && (!directionDeg || !inclinationDeg || !rgb))
  {
    return "fomMap: direction, inclination or output array is null";
  }
  const int nThreads = resolveThreadCount(threads);
  const std::int64_t count = static_cast<std::int64_t>(n);
#pragma omp parallel for num_threads(nThreads) schedule(static)
  for (std::int64_t p = 0; p < count; ++p)
  {
    const Rgb8 c = fomColor(directionDeg[p], inclinationDeg[p], scheme);
    rgb[3 * p] = c.r;
    rgb[3 * p + 1] = c.g;
    rgb[3 * p + 2] = c.b;
  }
  return {};
}

std::string fomApplyMask(const double* values, std::size_t n, FomMask mask, double threshold,
  std::uint8_t* rgb, std::uint8_t* tissue)
{
  if (mask != FomMask::None && n > 0 && (!values || !rgb))
  {
    return "fomApplyMask: mask image or FOM is null";
  }
  if (mask != FomMask::None && !std::isfinite(threshold))
  {
    return "fomApplyMask: the threshold is not a finite number";
  }
  for (std::size_t p = 0; p < n; ++p)
  {
    bool keep = true;
    if (mask == FomMask::Retardation)
    {
      keep = values[p] >= threshold; // false for NaN too
    }
    else if (mask == FomMask::Transmittance)
    {
      keep = values[p] <= threshold;
    }
    if (!keep)
    {
      rgb[3 * p] = rgb[3 * p + 1] = rgb[3 * p + 2] = 0;
    }
    if (tissue)
    {
      tissue[p] = keep ? 1 : 0;
    }
  }
  return {};
}

double fomMaskReference(const double* values, std::size_t n)
{
  double largest = -std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < n; ++p)
  {
    if (std::isfinite(values[p]) && values[p] > largest)
    {
      largest = values[p];
    }
  }
  return largest;
}

std::string fomMaskThreshold(FomMask mask, double fraction, double largest, double& threshold)
{
  if (!(fraction >= 0.0 && fraction <= 1.0)) // also refuses NaN
  {
    return "the fraction must be in [0, 1] (of the image's largest " +
      std::string(mask == FomMask::Transmittance ? "transmittance" : "retardation") + ")";
  }
  if (!std::isfinite(largest))
  {
    threshold = 0.0; // no finite value anywhere: every pixel is background whatever the threshold
    return {};
  }
  threshold = mask == FomMask::Transmittance ? (1.0 - fraction) * largest : fraction * largest;
  return {};
}

std::string fomLegend(int size, FomScheme scheme, std::vector<std::uint8_t>& rgb, Rgb8 background)
{
  const std::string sizeError = ValueChecks().within("legend size", size, 1, 16384).error();
  if (!sizeError.empty())
  {
    return sizeError;
  }
  rgb.assign(3 * static_cast<std::size_t>(size) * static_cast<std::size_t>(size), 0);
  for (int row = 0; row < size; ++row)
  {
    for (int col = 0; col < size; ++col)
    {
      const double x = 2.0 * (col + 0.5) / size - 1.0;
      const double y = 2.0 * (row + 0.5) / size - 1.0;
      const double rho2 = x * x + y * y;
      Rgb8 c = background;
      if (rho2 <= 1.0)
      {
        double d = std::atan2(y, x) * 180.0 / M_PI;
        d = d < 0.0 ? d + 180.0 : d;
        d = d >= 180.0 ? d - 180.0 : d;
        const double i = std::asin(std::sqrt(1.0 - rho2)) * 180.0 / M_PI;
        c = fomColor(d, i, scheme);
      }
      const std::size_t p = 3 * (static_cast<std::size_t>(row) * size + col);
      rgb[p] = c.r;
      rgb[p + 1] = c.g;
      rgb[p + 2] = c.b;
    }
  }
  return {};
}

} // namespace fiberpli
