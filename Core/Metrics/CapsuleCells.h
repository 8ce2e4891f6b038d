/// CapsuleCells: capsules (every periodic image that reaches the region, with its lattice shift)
/// listed per cell of a uniform grid over a region, for point queries — which capsule, if any,
/// covers a point. Shared by the Monte Carlo volume fraction and the mixing figure.
#pragma once

#include "Metrics/Capsules.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace fiberpli
{

/// One capsule's entry in a voxel layer: the capsule shifted by a lattice vector (zero without a
/// cell).
struct LayerEntry
{
  std::size_t capsule;
  Vec3 shift;
};

class CapsuleCells
{
public:
  static constexpr std::size_t npos = std::numeric_limits<std::size_t>::max();

  /// Lists the capsules of `set` per cell of a grid over [lo, hi] (wrapping round `cell` when it
  /// is enabled). Checks the memory budget first: error() then says why nothing was built.
  CapsuleCells(const CapsuleSet& set, const Vec3& lo, const Vec3& hi, const PeriodicCell& cell);

  /// Empty, or why the cells were not built (over the memory budget).
  const std::string& error() const { return error_; }

  /// Index into set.capsules of the first listed capsule image containing p (distance <= r), or
  /// npos.
  std::size_t find(const Vec3& p) const;

  bool inside(const Vec3& p) const { return find(p) != npos; }

private:
  const CapsuleSet& set_;
  Vec3 lo_;
  bool periodic_;
  std::int64_t n_[3] = { 1, 1, 1 };
  Vec3 edge_;
  std::vector<std::size_t> start_;
  std::vector<LayerEntry> entries_;
  std::string error_;
};

} // namespace fiberpli
