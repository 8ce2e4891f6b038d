#include "Tissue/Dispersion.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>

namespace fiberpli
{

namespace
{
constexpr int kTable = 2048;

// The table's range of x = 1 − t: the density exp(κ(x² − 2x)) is below e^−40 beyond 20/κ.
double tableSpan(double kappa)
{
  return kappa > 20.0 ? 20.0 / kappa : 1.0;
}

double density(double kappa, double x)
{
  return std::exp(kappa * (x * x - 2.0 * x));
}
} // namespace

double watsonC2(double kappa)
{
  // Simpson's rule over x = 1 − t ∈ [0, span]: ∫ t² ρ / ∫ ρ.
  const double span = tableSpan(kappa);
  double num = 0.0, den = 0.0;
  for (int i = 0; i <= kTable; ++i)
  {
    const double x = span * i / kTable;
    const double w = (i == 0 || i == kTable) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    const double rho = density(kappa, x);
    num += w * (1.0 - x) * (1.0 - x) * rho;
    den += w * rho;
  }
  return num / den;
}

double watsonConcentration(double c2)
{
  double lo = std::log(1e-8), hi = std::log(1e9);
  for (int i = 0; i < 200 && hi - lo > 1e-13; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (watsonC2(std::exp(mid)) < c2 ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

WatsonTable::WatsonTable(double kappa)
  : kappa_(kappa)
  , span_(tableSpan(kappa))
  , cdf_(kTable + 1, 0.0)
{
  for (int i = 1; i <= kTable; ++i)
  {
    const double a = span_ * (i - 1) / kTable, b = span_ * i / kTable;
    // Simpson on each cell: the density varies by up to e^-0.02 over a cell at the largest κ.
    cdf_[i] = cdf_[i - 1] +
      (b - a) / 6.0 * (density(kappa, a) + 4.0 * density(kappa, 0.5 * (a + b)) + density(kappa, b));
  }
  for (double& c : cdf_)
    c /= cdf_.back();
}

double WatsonTable::cosine(double u) const
{
  const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
  const std::size_t i =
    std::clamp<std::size_t>(static_cast<std::size_t>(it - cdf_.begin()), 1, cdf_.size() - 1);
  const double c0 = cdf_[i - 1], c1 = cdf_[i];
  const double f = c1 > c0 ? (u - c0) / (c1 - c0) : 0.0;
  const double x = span_ * (static_cast<double>(i - 1) + std::clamp(f, 0.0, 1.0)) / kTable;
  return 1.0 - x;
}

std::shared_ptr<const WatsonTable> watsonTableForC2(double c2)
{
  static std::mutex mutex;
  static std::map<double, std::shared_ptr<const WatsonTable>> tables;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = tables.find(c2);
  if (it != tables.end())
    return it->second;
  if (tables.size() >= 16)
    tables.clear(); // the callers hold their own shared_ptr
  auto table = std::make_shared<const WatsonTable>(watsonConcentration(c2));
  tables.emplace(c2, table);
  return table;
}

std::shared_ptr<const WatsonTable> watsonTableForKappa(double kappa)
{
  static std::mutex mutex;
  static std::map<double, std::shared_ptr<const WatsonTable>> tables;
  const std::lock_guard<std::mutex> lock(mutex);
  auto it = tables.find(kappa);
  if (it != tables.end())
    return it->second;
  if (tables.size() >= 16)
    tables.clear();
  auto table = std::make_shared<const WatsonTable>(kappa);
  tables.emplace(kappa, table);
  return table;
}

double dispersionQuantile(double offset, std::uint64_t index)
{
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  const double x = offset + (static_cast<double>(index) + 0.5) * g;
  return x - std::floor(x);
}

Vec3 watsonDirection(
  const Vec3& axis, const Vec3& e1, const Vec3& e2, const WatsonTable& table, double u1, double u2)
{
  const double t = table.cosine(u1);
  const double s = std::sqrt(std::max(0.0, 1.0 - t * t));
  const double phi = 2.0 * M_PI * u2;
  return t * axis + s * (std::cos(phi) * e1 + std::sin(phi) * e2);
}

} // namespace fiberpli
