/// SubstrateMesher: the outer surface of every fiber (and the axon surface inside it where inner
/// radii exist) as triangle meshes for diffusion simulators (docs/diffusion-export.md §1).
///
/// Each surface is a tube of `sides`-gons: rings at the fiber's points (and, with ringSpacing > 0,
/// at points inserted so that no link is longer than ringSpacing), each ring perpendicular to the
/// bisector of its links and carried along by parallel transport (as Mesh/TubeMesher), triangles
/// wound counter-clockwise seen from outside.
/// - Open model (no periodic cell): every tube is capped at both ends (a fan around the end point),
///   so each surface is closed.
/// - Periodic cell: a fiber closed through the cell (docs/data-contract.md §9) becomes a tube loop
///   without caps (its last ring joins its first, shifted by the closure vector); fibers that are
///   not closed are capped. Every tube is then cut by the lattice planes x = xmin + i·Lx (and y, z)
///   it crosses — each triangle that straddles a plane is split there, conformingly, so both sides
///   share the cut vertices — and every piece is moved by the lattice vector that brings it into
///   the cell. Cut vertices land exactly on the cell faces (coordinates equal to the bounds), and
///   the cut vertices of the two faces of one cut differ by exactly one edge length: the surface is
///   closed once opposite faces are identified. Vertices within 1e-9 × the edge of a plane are
///   moved onto it, so no sliver triangle straddles a face.
/// Tessellation error: a ring is a polygon inscribed in the circle, so the surface lies within
/// r·(1 − cos(π/sides)) inside the true tube, and a straight tube's volume is π r² L times the
/// polygon factor sin(2π/n)/(2π/n) exactly (the cut changes no volume).
#pragma once

#include "Geometry/PeriodicCell.h"
#include "Model/FiberModel.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <array>
#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace fiberpli
{

constexpr int kMaxSubstrateSides = 256;

struct SubstrateMeshOptions
{
  int sides = 16; ///< vertices per ring, 3 to kMaxSubstrateSides
  double ringSpacing =
    0; ///< µm; > 0: extra rings so that no link is longer; 0: rings at the points
};

/// One closed (modulo the cell) surface: a fiber's outer or inner tube.
struct SubstrateSurface
{
  std::size_t fiber = 0; ///< index in the model
  bool inner = false;    ///< the axon surface inside the outer one
  std::vector<Vec3> vertices;
  std::vector<std::array<std::int64_t, 3>> triangles; ///< indices into vertices, CCW from outside
};

/// Receives every surface in model order (outer before inner); returns false to stop.
using SubstrateSink = std::function<bool(const SubstrateSurface&)>;

/// "" when valid, else a message naming the option (NumberOfSides, RingSpacing) and the value.
std::string checkSubstrateMeshOptions(const SubstrateMeshOptions& options);

/// Sides per ring so that the polygon stays within tolerance (µm, > 0) of a circle of radius r:
/// the smallest n >= 3 with r(1 − cos(π/n)) <= tolerance (capped at kMaxSubstrateSides).
int substrateSidesForTolerance(double radius, double tolerance);

/// Meshes every surface and hands it to sink, one at a time (memory: one surface). model must pass
/// validateModel; innerRadii (may be null or empty) holds one vector per fiber, one value per
/// point, each > 0 and <= the radius. cell may be disabled (open model). progress is called per
/// fiber. Errors name the option or fiber.
Status meshSubstrate(const FiberModel& model, const std::vector<std::vector<double>>* innerRadii,
  const PeriodicCell& cell, const SubstrateMeshOptions& options, const SubstrateSink& sink,
  const ProgressFn& progress = {});

/// Counts of a whole substrate mesh (from a counting pass of meshSubstrate).
struct SubstrateMeshCounts
{
  std::uint64_t vertices = 0;
  std::uint64_t triangles = 0;
  std::uint64_t surfaces = 0;
};

/// Writes the substrate as one ASCII PLY that MC/DC reads: header with `element vertex N`
/// (`property float x/y/z`) and `element face M` (`property list uchar int vertex_indices`),
/// vertex lines `x y z` (µm, shortest round-trip text of the double), face lines `3 i j k`. The
/// mesh is built three times (count, vertices, faces), never held whole in memory. counts
/// receives the numbers (also on failure after the count pass). Returns a Status (error names
/// the option or fiber; aborted when progress said stop).
Status writeSubstratePly(std::ostream& out, const FiberModel& model,
  const std::vector<std::vector<double>>* innerRadii, const PeriodicCell& cell,
  const SubstrateMeshOptions& options, SubstrateMeshCounts& counts,
  const ProgressFn& progress = {});

/// The MC/DC configuration that simulates in this substrate: `<obstacle>` with `ply <plyPath>` and
/// `ply_scale 0.001` (µm → mm), and `<voxels>` = the cell (or lo/hi for an open model) in mm.
std::string mcdcConfigSnippet(const std::string& plyPath, const Vec3& lo, const Vec3& hi);

} // namespace fiberpli
