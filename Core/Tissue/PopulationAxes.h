/// PopulationAxes: the axes of a cube's populations (docs/tissue-models.md §10.5). Population 0
/// runs along x, population 1 at CrossingAngle ω from it in the x–y plane, population 2 along z.
/// In a periodic cell a closed fiber's end-to-end vector is a lattice vector, so population 1's
/// axis is the nearest small-integer lattice direction (p, q, 0) to (cos ω, sin ω, 0): the
/// shortest one within 1° of ω, else the nearest of all with |p|, |q| <= kMaxAxisPeriods. ω = 90°
/// gives exactly today's y axis.
#pragma once

#include "Geometry/Vec3.h"

#include <vector>

namespace fiberpli
{

/// The largest |p|, |q| of a periodic population axis (p, q, 0): a fiber along it spans
/// √(p² + q²) cell edges before it closes.
constexpr int kMaxAxisPeriods = 6;

struct PopulationAxis
{
  /// The unit axis.
  Vec3 direction;
  /// Periodic: the axis as a lattice vector in periods (integers); open: the unit axis.
  Vec3 lattice;
  /// Two directions across the axis: periodic, lattice vectors (integers) that with `lattice`
  /// span the directions a dispersed fiber may take; open, unit vectors.
  Vec3 across1;
  Vec3 across2;
  /// The axis is coordinate axis k of population k (today's cube: x, y, z).
  bool standard = true;
};

/// The axes of populations 0 … populations − 1 (1..3) for crossing angle ω (degrees, in [0, 90]).
std::vector<PopulationAxis> populationAxes(int populations, double crossingAngle, bool periodic);

/// The angle (degrees) between the axes of populations 0 and 1.
double axesAngle(const std::vector<PopulationAxis>& axes);

/// Of the lattice vectors m·lattice + a·across1 + b·across2 (1 <= m <= kMaxDispersionPeriods,
/// |a|, |b| <= kMaxDispersionPeriods), the shortest of those within 1° of the smallest angle to
/// `direction` (ties: the first in m, a, b order), in periods.
Vec3 nearestLatticeDirection(const PopulationAxis& axis, const Vec3& direction);

} // namespace fiberpli
