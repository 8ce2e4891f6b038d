// Monte Carlo volume fraction for the benchmark drivers: capsules in a coarse cell list of the cube
// [-half, half]³, uniform points tested against the capsules of their cell. Independent of the
// solver's code (own point-segment distance), shared by solver_bench and periodic_bench.
#pragma once

#include "Geometry/Vec3.h"
#include "Util/Random.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace fiberpli::bench
{

struct BenchCapsule
{
  Vec3 a, b;
  double r;
};

/// Squared distance of point x to segment [a, b].
inline double pointSegment2(const Vec3& x, const Vec3& a, const Vec3& b)
{
  const Vec3 ab = b - a;
  const double l2 = dot(ab, ab);
  double t = l2 > 0.0 ? dot(x - a, ab) / l2 : 0.0;
  t = std::min(1.0, std::max(0.0, t));
  return norm2(x - (a + t * ab));
}

class CapsuleCells
{
public:
  /// nc³ cells of edge `cell` starting at -half (nc · cell may exceed 2 · half).
  CapsuleCells(double half, int nc, double cell)
    : half_(half)
    , nc_(nc)
    , cell_(cell)
    , cells_(static_cast<std::size_t>(nc) * nc * nc)
  {
  }

  /// Lists the capsule in every cell its bounding box touches; capsules outside the cube are
  /// dropped.
  void add(const BenchCapsule& s)
  {
    int lo[3], hi[3];
    for (int d = 0; d < 3; ++d)
    {
      const double mn = std::min(s.a[d], s.b[d]) - s.r;
      const double mx = std::max(s.a[d], s.b[d]) + s.r;
      lo[d] = std::max(0, static_cast<int>(std::floor((mn + half_) / cell_)));
      hi[d] = std::min(nc_ - 1, static_cast<int>(std::floor((mx + half_) / cell_)));
      if (lo[d] > hi[d] || mx <= -half_ || mn >= half_)
      {
        return;
      }
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
      for (int y = lo[1]; y <= hi[1]; ++y)
        for (int x = lo[0]; x <= hi[0]; ++x)
          cells_[static_cast<std::size_t>(x + nc_ * (y + nc_ * z))].push_back(s);
  }

  /// Fraction of `samples` uniform points of the cube (seed 12345) inside a listed capsule.
  double hitFraction(long samples) const
  {
    RandomStream rng(12345);
    long hits = 0;
    for (long i = 0; i < samples; ++i)
    {
      const Vec3 p{ rng.uniform(-half_, half_), rng.uniform(-half_, half_),
        rng.uniform(-half_, half_) };
      const int x = std::min(nc_ - 1, static_cast<int>((p.x + half_) / cell_));
      const int y = std::min(nc_ - 1, static_cast<int>((p.y + half_) / cell_));
      const int z = std::min(nc_ - 1, static_cast<int>((p.z + half_) / cell_));
      for (const BenchCapsule& s : cells_[static_cast<std::size_t>(x + nc_ * (y + nc_ * z))])
      {
        if (pointSegment2(p, s.a, s.b) <= s.r * s.r)
        {
          ++hits;
          break;
        }
      }
    }
    return static_cast<double>(hits) / static_cast<double>(samples);
  }

private:
  double half_;
  int nc_;
  double cell_;
  std::vector<std::vector<BenchCapsule>> cells_;
};

} // namespace fiberpli::bench
