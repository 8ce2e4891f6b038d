// Small models and the bit-for-bit comparison shared by the solver tests (TestCollisionSolver,
// TestDistributedSolver, TestSolverCheckpoint): one definition, so "bit identical" means the
// same thing in every test that claims it.
#pragma once

#include "Tissue/CubeGenerator.h"

#include <cmath>
#include <cstdint>
#include <cstring>

namespace fiberpli_test
{
// A straight fiber of n points from a in steps of `step`, constant radius r.
inline fiberpli::Fiber line(fiberpli::Vec3 a, fiberpli::Vec3 step, int n, double r, std::int64_t id)
{
  fiberpli::Fiber f;
  for (int i = 0; i < n; ++i)
    f.points.push_back(a + double(i) * step);
  f.radii.assign(f.points.size(), r);
  f.id = id;
  return f;
}

// An open cube of n fibers at the density of the fastPLI paper's cubes (1000 fibers in a cube of
// edge sqrt(3)*30 µm), so a larger n keeps the density and grows the cube.
inline fiberpli::FiberModel paperCube(int pops, int n, std::uint64_t seed)
{
  fiberpli::CubeOptions o;
  o.populations = pops;
  o.numberOfFibers = n;
  o.edgeLength = std::sqrt(3.0) * 30.0 * std::sqrt(n / 1000.0);
  o.seed = seed;
  return fiberpli::generateCube(o);
}

// True when both models hold the same fibers in the same order with the same ids, bundles,
// points and radii to the bit.
inline bool bitwiseEqual(const fiberpli::FiberModel& a, const fiberpli::FiberModel& b)
{
  if (a.fibers.size() != b.fibers.size())
    return false;
  for (std::size_t f = 0; f < a.fibers.size(); ++f)
  {
    const fiberpli::Fiber& x = a.fibers[f];
    const fiberpli::Fiber& y = b.fibers[f];
    if (x.id != y.id || x.bundle != y.bundle || x.points.size() != y.points.size() ||
      x.radii.size() != y.radii.size() ||
      std::memcmp(x.points.data(), y.points.data(), x.points.size() * sizeof(fiberpli::Vec3)) !=
        0 ||
      std::memcmp(x.radii.data(), y.radii.data(), x.radii.size() * sizeof(double)) != 0)
      return false;
  }
  return true;
}
} // namespace fiberpli_test
