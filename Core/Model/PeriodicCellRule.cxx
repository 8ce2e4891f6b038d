#include "Model/PeriodicCellRule.h"

#include "Util/NumberFormat.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

std::string validatePeriodicCell(const PeriodicCell& cell)
{
  static const char* const kAxis[3] = { "x", "y", "z" };
  for (int a = 0; a < 3; ++a)
  {
    const double lo = cell.lo[a];
    const double hi = cell.hi[a];
    const std::string where = std::string("periodic_cell axis ") + kAxis[a] + " is [" + formatNumber(lo) + ", " +
      formatNumber(hi) + "]";
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo))
    {
      return where + ", must be finite with max > min";
    }
    const double edge = hi - lo; // inf when the bounds are finite but far apart
    if (!(edge <= kMaxPeriodicEdge))
    {
      return where + ": its edge " + formatNumber(edge) + " um must be at most " + formatNumber(kMaxPeriodicEdge) +
        " um (a metre)";
    }
    const double magnitude = std::max(std::fabs(lo), std::fabs(hi));
    if (edge < kMinPeriodicEdgeRatio * magnitude)
    {
      return where + ": its edge " + formatNumber(edge) + " um is below " + formatNumber(kMinPeriodicEdgeRatio) +
        " x its bounds' magnitude, too fine for double precision (move the cell towards the origin)";
    }
  }
  return {};
}

std::string periodicCellFromBounds(const double* b, std::size_t count, PeriodicCell& cell)
{
  if (count != 6)
  {
    return "periodic_cell has " + formatNumber(count) + " values, must have 6 (xmin xmax ymin ymax zmin zmax)";
  }
  PeriodicCell c;
  for (int a = 0; a < 3; ++a)
  {
    c.lo[a] = b[2 * a];
    c.hi[a] = b[2 * a + 1];
  }
  const std::string error = validatePeriodicCell(c);
  if (error.empty())
  {
    cell = c;
  }
  return error;
}

} // namespace fiberpli
