/// Random: seedable, counter-keyed random streams (docs/tissue-models.md §7). SplitMix64 derives
/// one stream per (seed, key...) so that a fiber's draws never depend on other fibers, generation
/// order or thread count; xoshiro256** is the engine. Distributions are our own code (std::
/// distributions differ between standard libraries, which would break bit-identical results).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>

namespace fiberpli
{

/// Empty when `seed` is a usable Seed property (>= 0: it becomes the unsigned stream seed), else
/// the message naming it. The one Seed rule of every source and filter with randomness.
inline std::string validateSeed(long long seed)
{
  return seed < 0 ? "Seed is " + std::to_string(seed) + ", must be >= 0" : std::string();
}

inline std::uint64_t splitMix64(std::uint64_t& state)
{
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

class RandomStream
{
public:
  /// Stream for (seed, key1, key2): e.g. (Seed, bundle index, fiber index).
  explicit RandomStream(std::uint64_t seed, std::uint64_t key1 = 0, std::uint64_t key2 = 0)
  {
    std::uint64_t sm = seed;
    sm = splitMix64(sm) ^ key1;
    sm = splitMix64(sm) ^ key2;
    for (std::uint64_t& s : state_)
    {
      s = splitMix64(sm);
    }
  }

  /// xoshiro256** next 64-bit value.
  std::uint64_t next()
  {
    const std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
    const std::uint64_t t = state_[1] << 17;
    state_[2] ^= state_[0];
    state_[3] ^= state_[1];
    state_[1] ^= state_[2];
    state_[0] ^= state_[3];
    state_[2] ^= t;
    state_[3] = rotl(state_[3], 45);
    return result;
  }

  /// Uniform in [0, 1) with 53 random bits.
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  /// Uniform in [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  /// Standard normal (Box–Muller, one value per call: simple and order-stable).
  double normal()
  {
    const double u1 = 1.0 - uniform(); // (0, 1]: log is finite
    const double u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t state_[4];
};

} // namespace fiberpli
