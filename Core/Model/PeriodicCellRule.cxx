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
    const std::string where = std::string("periodic_cell axis ") + kAxis[a] + " is [" +
      formatNumber(lo) + ", " + formatNumber(hi) + "]";
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(hi > lo))
    {
      return where + ", must be finite with max > min";
    }
    const double edge = hi - lo; // inf when the bounds are finite but far apart
    if (!(edge <= kMaxPeriodicEdge))
    {
      return where + ": its edge " + formatNumber(edge) + " um must be at most " +
        formatNumber(kMaxPeriodicEdge) + " um (a metre)";
    }
    const double magnitude = std::max(std::fabs(lo), std::fabs(hi));
    if (edge < kMinPeriodicEdgeRatio * magnitude)
    {
      return where + ": its edge " + formatNumber(edge) + " um is below " +
        formatNumber(kMinPeriodicEdgeRatio) +
        " x its bounds' magnitude, too fine for double precision (move the cell towards the "
        "origin)";
    }
  }
  return {};
}

std::string periodicCellFromBounds(const double* b, std::size_t count, PeriodicCell& cell)
{
  if (count != 6)
  {
    return "periodic_cell has " + formatNumber(count) +
      " values, must have 6 (xmin xmax ymin ymax zmin zmax)";
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

std::string compareRankCells(const std::vector<RankCell>& ranks)
{
  const RankCell* first = nullptr;
  std::size_t firstRank = 0;
  for (std::size_t r = 0; r < ranks.size(); ++r)
  {
    const RankCell& c = ranks[r];
    if (!c.present)
    {
      continue;
    }
    PeriodicCell cell;
    const std::string error = periodicCellFromBounds(c.values.data(), c.count, cell);
    if (!error.empty())
    {
      return (ranks.size() > 1 ? "rank " + std::to_string(r) + "'s " : std::string()) +
        "input field data " + error;
    }
    if (!first)
    {
      first = &c;
      firstRank = r;
    }
    else if (c.values != first->values)
    {
      const auto text = [](const std::vector<double>& v)
      {
        std::string t;
        for (double x : v)
        {
          t += (t.empty() ? "" : " ") + formatNumber(x);
        }
        return t;
      };
      return "the input pieces have different periodic_cell field data: rank " +
        std::to_string(firstRank) + " has " + text(first->values) + ", rank " + std::to_string(r) +
        " has " + text(c.values);
    }
  }
  return {};
}

} // namespace fiberpli
