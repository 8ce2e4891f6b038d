#include "Metrics/Histogram.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

Histogram makeHistogram(double lo, double hi, std::size_t bins)
{
  Histogram h;
  if (!(hi > lo))
  {
    const double pad = std::max(std::abs(lo) * 1e-3, 1e-9);
    hi = lo + pad;
    lo -= pad;
  }
  h.lo = lo;
  h.hi = hi;
  h.count.assign(std::max<std::size_t>(bins, 1), 0);
  h.weight.assign(h.count.size(), 0.0);
  return h;
}

void addToHistogram(Histogram& h, double value, double weight)
{
  if (!std::isfinite(value) || value < h.lo || value > h.hi || h.count.empty())
  {
    return;
  }
  const auto bins = static_cast<double>(h.count.size());
  const auto k = static_cast<std::size_t>(
    std::min(bins - 1.0, std::floor((value - h.lo) / (h.hi - h.lo) * bins)));
  ++h.count[k];
  h.weight[k] += weight;
}

bool finiteRange(const std::vector<double>& values, double& lo, double& hi)
{
  bool any = false;
  for (double v : values)
  {
    if (!std::isfinite(v))
    {
      continue;
    }
    lo = any ? std::min(lo, v) : v;
    hi = any ? std::max(hi, v) : v;
    any = true;
  }
  return any;
}

} // namespace fiberpli
