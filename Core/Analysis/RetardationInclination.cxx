#include "Analysis/RetardationInclination.h"
#include "Analysis/ForEachPixel.h"
#include "Util/ValueCheck.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace fiberpli
{

double inclinationFromRetardation(double r, double rRef)
{
  if (std::isnan(r))
  {
    return r;
  }
  if (r <= 0.0)
  {
    return M_PI / 2.0;
  }
  if (r >= rRef)
  {
    return 0.0;
  }
  const double c2 = std::asin(r) / std::asin(rRef); // cos²α, in (0, 1)
  return std::acos(std::sqrt(c2));
}

double maxRetardation(const double* retardation, std::int64_t nx, const GridRange& range)
{
  double best = 0.0;
  for (std::int64_t j = range.j0; j < range.j1; ++j)
  {
    for (std::int64_t i = range.i0; i < range.i1; ++i)
    {
      const double r = retardation[i + nx * j];
      if (std::isfinite(r) && r > best)
      {
        best = r;
      }
    }
  }
  return best;
}

std::string inclinationMapFromRetardation(const double* retardation, std::int64_t nx,
  std::int64_t ny, const GridRange& range, double referenceRetardation, int threads,
  std::vector<double>& inclination)
{
  std::string err = validatePixelRange(nx, ny, range);
  if (!err.empty())
  {
    return err;
  }
  err = ValueChecks()
          .within("ReferenceRetardation", referenceRetardation, 0.0, 1.0, " (0 = automatic)")
          .error();
  if (!err.empty())
  {
    return err;
  }
  if (!retardation && range.count() > 0)
  {
    return "retardation map is null";
  }
  inclination.resize(static_cast<std::size_t>(nx * ny), std::numeric_limits<double>::quiet_NaN());
  double rRef = referenceRetardation;
  if (rRef == 0.0)
  {
    rRef = maxRetardation(retardation, nx, range);
  }
  forEachPixel(nx, range, threads, {},
    [&](std::int64_t p)
    {
      // rRef = 0 only when every r is 0 (or NaN): the r <= 0 rule gives 90° before dividing.
      inclination[p] = inclinationFromRetardation(retardation[p], rRef > 0.0 ? rRef : 1.0);
    });
  return {};
}

} // namespace fiberpli
