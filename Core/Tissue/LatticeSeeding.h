/// LatticeSeeding: ordered transverse positions for the fibers of a periodic cube
/// (docs/periodic-cells.md, "Lattice seeding"). Random seeds braid closed fibers and the solver
/// jams below the dense targets; sites on a lattice commensurate with the cell start the solve near
/// an ordered packing:
/// - 1 population: a (slightly anisotropic) triangular lattice in the cross-section;
/// - 2 populations: alternating layers along z, x-fibers in even layers, y-fibers in odd ones
///   (straight-fiber limit π/4 for touching layers);
/// - 3 populations: the cubic three-direction rod packing (x, y and z rods a/2 apart in the
///   third coordinate, straight-fiber limit 3π/16 at a = 4r), or three bundled blocks (one per
///   population, filled with hexagonal rows, no two crossing; limit 3/4 × π/(2√3)), whichever
///   has the larger spacing.
#pragma once

#include <vector>

namespace fiberpli
{

/// One site: the two transverse coordinates of a fiber of population k, along the axes
/// (k + 1) mod 3 and (k + 2) mod 3, in [-L/2, L/2).
struct LatticeSite
{
  double t1 = 0.0;
  double t2 = 0.0;
};

/// The sites of every population (index = population, 0..2) of a periodic cube of edge L and the
/// smallest distance between two fiber axes (parallel sites, or the lines of two perpendicular
/// populations), over all periodic images. A fiber of radius r fits on the straight lattice when
/// spacing >= 2r.
struct PeriodicLattice
{
  std::vector<std::vector<LatticeSite>> sites;
  double spacing = 0.0;
};

/// The lattice with at least counts[k] sites for population k (counts.size() = 1, 2 or 3): of all
/// commensurate lattices of its kind with that many sites (up to 2 % more for one population), the
/// one with the largest spacing. Empty for 0 or more than 3 populations, or L <= 0.
PeriodicLattice periodicLattice(double edgeLength, const std::vector<int>& counts);

} // namespace fiberpli
