/// Histogram: equal-width bins of a set of values, for the metrics' bar-chart tables.
#pragma once

#include <cstddef>
#include <vector>

namespace fiberpli
{

/// Bins [lo + k·w, lo + (k+1)·w), w = (hi − lo)/bins; the last bin also takes hi. Values outside
/// [lo, hi] and non-finite values are not counted. weight[k] is the sum of the values' weights.
struct Histogram
{
  double lo = 0.0, hi = 0.0;
  std::vector<std::size_t> count;
  std::vector<double> weight;

  double width() const
  {
    return count.empty() ? 0.0 : (hi - lo) / static_cast<double>(count.size());
  }
  double centre(std::size_t k) const { return lo + (static_cast<double>(k) + 0.5) * width(); }
};

/// A histogram of `bins` (>= 1) bins over [lo, hi]; lo == hi (one repeated value) is widened to
/// lo ∓ max(|lo|·1e-3, 1e-9) so that the value sits in a bin of non-zero width.
Histogram makeHistogram(double lo, double hi, std::size_t bins);

/// Adds a value with its weight (1 for a plain count).
void addToHistogram(Histogram& h, double value, double weight = 1.0);

/// [min, max] of the finite values; false when there is none.
bool finiteRange(const std::vector<double>& values, double& lo, double& hi);

} // namespace fiberpli
