#include "Tissue/Stratification.h"

#include "Util/Random.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace fiberpli
{

namespace
{
// 0 .. n−1 in the order of a Fisher–Yates shuffle drawn from rng.
std::vector<int> shuffled(int n, RandomStream rng)
{
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  for (std::size_t i = order.size(); i > 1; --i)
  {
    const auto pick = static_cast<std::size_t>(rng.uniform() * static_cast<double>(i));
    std::swap(order[i - 1], order[std::min(pick, i - 1)]);
  }
  return order;
}
} // namespace

int strataPerSide(std::size_t fibers)
{
  const double blocks = std::floor(std::sqrt(static_cast<double>(fibers) / 9.0));
  return 3 * std::max(1, static_cast<int>(blocks));
}

std::vector<int> assignStrata(
  const std::vector<double>& weights, int perSide, std::uint64_t seed, std::uint64_t key)
{
  if (perSide < 3 || perSide % 3 != 0)
    return {};
  const std::size_t n = weights.size();
  std::vector<std::size_t> heaviest(n);
  std::iota(heaviest.begin(), heaviest.end(), std::size_t{ 0 });
  std::stable_sort(heaviest.begin(), heaviest.end(),
    [&](std::size_t a, std::size_t b) { return weights[a] > weights[b]; });
  const int side = perSide / 3; // strata per block side
  const int perBlock = side * side;
  std::vector<int> filled(9, 0); // fibers each block has taken
  std::vector<int> strata(n, 0);
  std::uint64_t stream = 0;
  std::vector<int> blockOrder;
  std::vector<std::vector<int>> roundOrder(9);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (i % 9 == 0)
      blockOrder = shuffled(9, RandomStream(seed, key, stream++));
    const int block = blockOrder[i % 9];
    int& c = filled[static_cast<std::size_t>(block)];
    if (c % perBlock == 0)
      roundOrder[static_cast<std::size_t>(block)] =
        shuffled(perBlock, RandomStream(seed, key, stream++));
    const int inBlock =
      roundOrder[static_cast<std::size_t>(block)][static_cast<std::size_t>(c % perBlock)];
    ++c;
    const int column = (block % 3) * side + inBlock % side;
    const int row = (block / 3) * side + inBlock / side;
    strata[heaviest[i]] = row * perSide + column;
  }
  return strata;
}

double intoStratum(double coordinate, int cell, int perSide, double edgeLength)
{
  const double u = std::min(std::max((coordinate + 0.5 * edgeLength) / edgeLength, 0.0), 1.0);
  return -0.5 * edgeLength + (cell + u) * edgeLength / perSide;
}

} // namespace fiberpli
