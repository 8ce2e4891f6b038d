#include "Tissue/LatticeDispersion.h"

#include "Tissue/ShapeOptions.h"

#include <cmath>
#include <map>
#include <mutex>
#include <tuple>
#include <vector>

namespace fiberpli
{

Vec3 latticeDispersedDirection(
  const PopulationAxis& axis, const WatsonTable& table, double u1, double u2)
{
  const Vec3 d = watsonDirection(
    axis.direction, normalized(axis.across1), normalized(axis.across2), table, u1, u2);
  return nearestLatticeDirection(axis, d);
}

double latticeDispersionKappa(
  const PopulationAxis& axis, double c2, std::uint64_t seed, std::uint64_t group)
{
  using Key = std::tuple<std::uint64_t, std::uint64_t, double, double, double, double>;
  static std::mutex mutex;
  static std::map<Key, double> kept;
  const Key key{ seed, group, c2, axis.lattice.x, axis.lattice.y, axis.lattice.z };
  {
    const std::lock_guard<std::mutex> lock(mutex);
    const auto it = kept.find(key);
    if (it != kept.end())
      return it->second;
  }
  std::vector<double> u1(kLatticeDispersionSample), u2(kLatticeDispersionSample);
  const double offset = shapeStream(seed, ShapeFeature::Dispersion, group, kGroupStream).uniform();
  for (int j = 0; j < kLatticeDispersionSample; ++j)
  {
    RandomStream rng =
      shapeStream(seed, ShapeFeature::Dispersion, group, static_cast<std::uint64_t>(j));
    u1[static_cast<std::size_t>(j)] = dispersionQuantile(offset, static_cast<std::uint64_t>(j));
    u2[static_cast<std::size_t>(j)] = rng.uniform();
  }
  const auto achieved = [&](double kappa)
  {
    const WatsonTable table(kappa);
    double sum = 0.0;
    for (std::size_t j = 0; j < u1.size(); ++j)
    {
      const Vec3 t = normalized(latticeDispersedDirection(axis, table, u1[j], u2[j]));
      const double c = dot(t, axis.direction);
      sum += c * c;
    }
    return sum / static_cast<double>(u1.size());
  };
  // From the κ of the plain Watson distribution: the snapped mean is close to it, so a bracket of
  // a few decades around it holds the answer (the ends are taken when it does not).
  const double start = std::log(watsonConcentration(c2));
  double lo = start - std::log(100.0), hi = start + std::log(1000.0);
  for (int i = 0; i < 40 && hi - lo > 1e-3; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (achieved(std::exp(mid)) < c2 ? lo : hi) = mid;
  }
  const double kappa = std::exp(0.5 * (lo + hi));
  const std::lock_guard<std::mutex> lock(mutex);
  if (kept.size() >= 64)
    kept.clear();
  kept.emplace(key, kappa);
  return kappa;
}

} // namespace fiberpli
