/// CaterpillarFormat: the sphere-list substrate file `voxel.csv` of the CATERPillar generator
/// (docs/diffusion-export.md §2). One header line
///   cell_type cell_id component component_id X Y Z inner_radius outer_radius
/// then one sphere a line, the nine fields separated by blanks (CATERPillar writes single spaces):
/// cell type (`axon`, `glial_cell`, `blood_vessel`, `neuron`), cell id (integer), component name,
/// component id (integer), centre (µm), inner and outer radius (µm; equal when the cell has no
/// myelin). Consecutive lines of one (cell_type, cell_id, component, component_id) form a sphere
/// chain.
///
/// Sphere chains ⇄ polylines:
/// - reading: the chains of `axon` cells become fibers, the sphere centres in file order its points
///   and the sphere radii its radii (outer → radius, inner → inner_radius), fiber id = cell id,
///   bundle id = component id (0 in CATERPillar's own files; FiberPLI writes the bundle there).
///   The capsules of the polyline contain every sphere, and exceed the union of the spheres only
///   by the grooves between neighbours: at most r − √(r² − (s/2)²) for spacing s and radius r.
///   Cells of other types (glial somata and branches, vessels) are not fibers: they are skipped
///   and counted in one warning. A chain of one sphere is dropped (droppedFibers).
/// - writing: every fiber becomes one `axon` cell; each link is filled with spheres at a spacing
///   s ≤ 2√(2 r t − t²) (r the smallest radius, inner or outer, at the link; t the tolerance), so
///   that the sphere-chain surface lies within t of the tapered capsule surface everywhere; the
///   fiber's own points are always among the centres, the others lie on the links with linearly
///   interpolated radii. Numbers are written in the shortest form that reads back bit-exactly.
#pragma once

#include "IO/FiberReadResult.h"
#include "Model/FiberModel.h"

#include <istream>
#include <ostream>
#include <string>
#include <vector>

namespace fiberpli
{

/// The header CATERPillar writes (tokens separated by single spaces).
extern const char* const kCaterpillarHeader;

/// Default sphere-chain tolerance of the writer (µm).
constexpr double kCaterpillarDefaultTolerance = 0.05;

/// Reads a voxel.csv stream; fileName is only used in messages. Errors name the file and line: a
/// missing header, a line without 9 fields, a non-integer id, a non-finite number, a radius <= 0,
/// an inner radius above the outer one, a line longer than 4096 characters, two chains of one
/// axon id. Every fiber's innerRadii is filled when any inner radius of the file differs from its
/// outer one (else no fiber has them).
FiberReadResult readCaterpillarCsv(std::istream& in, const std::string& fileName);

/// Largest centre spacing (µm) whose sphere chain of radius r stays within tolerance t of the
/// capsule surface: 2√(2 r t − t²), or 2 r when t >= r.
double caterpillarSphereSpacing(double radius, double tolerance);

/// Writes the model as CATERPillar axons (see above); a fiber's inner radius is its innerRadii
/// (checked by validateInnerRadii, Model/InnerRadii.h) or, without them, its radius. tolerance (µm)
/// must be finite and > 0. Returns "" on success, else the reason (invalid model, bad tolerance or
/// inner radii, more than 10^9 spheres, stream failure); use AtomicFile to protect the target file.
std::string writeCaterpillarCsv(
  std::ostream& out, const FiberModel& model, double tolerance = kCaterpillarDefaultTolerance);

/// Content check for CanReadFile: true when the first non-blank line is the CATERPillar header
/// (so ordinary CSV files stay with ParaView's own CSV reader). Restores the stream position.
bool looksLikeCaterpillarCsv(std::istream& in);

} // namespace fiberpli
