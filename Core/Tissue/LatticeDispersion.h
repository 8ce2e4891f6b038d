/// LatticeDispersion: dispersion in a periodic cell (docs/tissue-models.md §10.2). A closed fiber's
/// end-to-end vector is a lattice vector, so a Watson-drawn direction is replaced by a nearby
/// short lattice direction (PopulationAxes.h, nearestLatticeDirection). Those directions are coarse
/// near the axis and the snapping prefers short vectors, so with the κ of the requested ⟨cos²⟩ the
/// population would come out less aligned than asked; here κ is instead calibrated so that the
/// snapped directions themselves reach the request.
#pragma once

#include "Tissue/Dispersion.h"
#include "Tissue/PopulationAxes.h"

#include <cstdint>

namespace fiberpli
{

/// Fibers whose draws calibrate a population's κ (the first of the population, whatever its count,
/// so that κ does not depend on the count, which with a volume fraction depends on κ).
constexpr int kLatticeDispersionSample = 1000;

/// The concentration κ for which the mean cos² about axis.direction of the lattice directions
/// (nearestLatticeDirection of watsonDirection(axis, …, u1, u2)) of fibers j <
/// kLatticeDispersionSample is c2, u1 = dispersionQuantile(offset, j) (offset the first number of
/// the group's stream shapeStream(seed, Dispersion, group, kGroupStream)) and u2 the first number
/// of the fiber's stream shapeStream(seed, Dispersion, group, j); bisection on log κ (the mean
/// grows with κ for fixed draws, in steps). Computed once per (seed, group, c2, axis) and kept.
double latticeDispersionKappa(
  const PopulationAxis& axis, double c2, std::uint64_t seed, std::uint64_t group);

/// The lattice direction (in periods) of the draws (u1, u2) with the table of κ.
Vec3 latticeDispersedDirection(
  const PopulationAxis& axis, const WatsonTable& table, double u1, double u2);

} // namespace fiberpli
