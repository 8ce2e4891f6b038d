/// FiberShape: the target shape of one generated fiber (docs/tissue-models.md §10.8), everything
/// a later step needs to re-apply it or to go towards it gradually: the base path the fiber
/// undulates around, its undulation (modes and calibrated amplitude), its point count, its point
/// displacements and its radius. Both generators build their undulated fibers from it
/// (cubeFiberShape, bundleFiberShape).
#pragma once

#include "Tissue/Undulation.h"

#include <cstddef>
#include <vector>

namespace fiberpli
{

struct FiberShape
{
  BasePath base;
  Undulation undulation;
  std::size_t pointCount = 0;
  /// One displacement per point (closed: the last equals the first).
  std::vector<Vec3> jitter;
  /// The radius drawn for the fiber (before beading).
  double radius = 0.0;
  /// false when the displacements alone make the fiber longer than its target (amplitude 0).
  bool reached = true;

  /// The fiber's points with the fraction `fraction` of its undulation amplitude (0: the base path
  /// resampled, 1: the target): undulatedPath(base, undulation, fraction·amplitude, pointCount) +
  /// jitter; a closed fiber's last point is its first + base.closure exactly.
  std::vector<Vec3> points(double fraction = 1.0) const;
};

/// Draws `count` displacements U[−D, D]³ (x, y, z point by point) from rng; closed: count − 1
/// drawn, the last equal to the first.
std::vector<Vec3> drawJitter(
  RandomStream& rng, std::size_t count, double displacement, bool closed);

} // namespace fiberpli
