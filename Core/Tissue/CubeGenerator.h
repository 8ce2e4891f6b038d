/// CubeGenerator: the paper's cube benchmark (docs/tissue-models.md §6.1). Straight fibers of 1, 2
/// or 3 mutually perpendicular populations (x; x+y; x+y+z) placed uniformly at random in a cube of
/// edge L centred at the origin, n = max(2, round(L/l) + 1) points per fiber, every point displaced
/// by U[-D, D] per axis, constant radius. bundle = population index (0, 1, 2). Periodic: the cube
/// is a periodic cell; every fiber spans exactly one period along its axis and closes through the
/// faces (last point = first point + L along the axis, points unwrapped).
#pragma once

#include "Geometry/PeriodicCell.h"
#include "Model/FiberModel.h"
#include "Tissue/FiberShape.h"
#include "Tissue/PopulationAxes.h"
#include "Tissue/RadiusDistribution.h"
#include "Tissue/ShapeOptions.h"
#include "Util/EnumCode.h"
#include "Util/Progress.h"

#include <cstdint>
#include <string>

namespace fiberpli
{

/// How the populations share the cell (docs/tissue-models.md §10.5).
enum class CubeArrangement
{
  Auto = 0,       ///< each seeding's own: Random uniform (interwoven), Lattice its lattice or, with
                  ///< varying radii, its slabs
  Interwoven = 1, ///< populations mixed everywhere (Random: uniform; Lattice, 2 populations:
                  ///< alternating layers)
  Sheets = 2      ///< 2 populations in two slabs along z, thickness by their cross-section shares
};

/// The api string of an arrangement ("Auto", "Interwoven", "Sheets").
const char* cubeArrangementName(CubeArrangement arrangement);

/// The `Arrangement` code as the enum (Util/EnumCode.h): "" or the message naming the code.
inline std::string cubeArrangementFromCode(int code, CubeArrangement& arrangement)
{
  return enumFromCode(
    code, 2, "Arrangement", "0 (Auto), 1 (Interwoven) or 2 (Sheets)", arrangement);
}

/// How the transverse positions of a cube's fibers are chosen.
enum class CubeSeeding
{
  Random = 0, ///< uniform over the cross-section
  Lattice =
    1, ///< periodic cells only: jittered sites of an ordered lattice (Tissue/LatticeSeeding.h)
};

/// The `Seeding` code as the enum (Util/EnumCode.h): "" or the message naming the code.
inline std::string cubeSeedingFromCode(int code, CubeSeeding& seeding)
{
  return enumFromCode(code, 1, "Seeding", "0 (Random) or 1 (Lattice)", seeding);
}

struct CubeOptions
{
  int populations = 1;                    ///< 1..3
  int numberOfFibers = 1000;              ///< split as evenly as possible over the populations
  double edgeLength = 51.961524227066320; ///< √3·30 µm
  double fiberRadius = 0.8;               ///< µm
  double segmentLength = 2.0;             ///< µm, point spacing before displacement
  double displacement = 0.5;              ///< µm, D of U[-D, D]³
  std::uint64_t seed = 42;
  /// The cube is a periodic cell: fibers are closed through its faces (see above).
  bool periodic = false;
  /// > 0: the fiber count is the smallest for which Σ π r² · L (L = one period, the straight
  /// length of every fiber) reaches at least this fraction of the cube volume; 0 = use
  /// numberOfFibers. Must be < 1.
  double volumeFraction = 0.0;
  /// Radius spread s >= 0 (0 = constant FiberRadius) and its distribution (RadiusDistribution.h).
  double radiusSpread = 0.0;
  RadiusDistribution radiusDistribution = RadiusDistribution::Constant;
  /// Lattice (needs periodic): the fibers of population k take sites of periodicLattice (at least
  /// as many as fibers; the empty ones chosen at random), each jittered uniformly in the disc of
  /// radius max(0, spacing/2 − fiberRadius); the drawn positions are replaced, the displacements
  /// kept.
  CubeSeeding seeding = CubeSeeding::Random;
  /// Realism knobs (Tissue/ShapeOptions.h, docs/tissue-models.md §10); the defaults are off and
  /// leave the cube bit-identical. Undulation (and dispersion) replace the straight fiber of n
  /// points by a shaped one of max(n_min, round(τ·span/l) + 1) points whose displacements come from
  /// the fiber's Jitter stream; its transverse position and radius are drawn as for the straight
  /// fiber. Beading multiplies the radii (field on the nominal arc positions i·τ·span/(n − 1)).
  ShapeOptions realism;
  /// Degrees between the axes of populations 0 and 1, in [0, 90]; 90 = today's x and y. In a
  /// periodic cell the nearest small-integer lattice direction is taken (Tissue/PopulationAxes.h).
  /// Other than 90 needs Seeding Random.
  double crossingAngle = 90.0;
  /// Relative shares of the populations (fibers with numberOfFibers, volume with volumeFraction),
  /// the first `populations` values used, each > 0. Empty or all equal: today's split (even /
  /// populations in turn). Otherwise the counts are the largest-remainder split of numberOfFibers,
  /// or fibers are added to the population furthest below its share of the volume.
  std::vector<double> populationShares;
  CubeArrangement arrangement = CubeArrangement::Auto;
  /// µm, > 0: the undulation of a population is one random field over the cell
  /// (Tissue/Undulation.h, drawUndulationField) instead of independent modes per fiber, with this
  /// transverse coherence length ξ: fibers whose axes are r apart undulate with correlation about
  /// exp(−r²/2ξ²). Needs every population along a coordinate axis. 0 = off (independent).
  double undulationCoherence = 0.0;
  /// Lattice seeding of a periodic cell with beading: each fiber's radius profile is turned (a
  /// cyclic shift by whole points, Tissue/BeadPhasing.h) so that its beads meet those of its
  /// neighbours on their sites least. false = every profile as drawn.
  bool beadPhasing = false;
};

/// The target shape of fiber j of population k (Tissue/FiberShape.h): the straight base path from
/// the drawn transverse position along the fiber's span, its calibrated undulation, the point
/// count, the displacements (drawn from the Jitter stream) and the radius drawn for it. Lattice
/// seeding and Sheets translate the finished fiber across its axis afterwards.
/// Meaningful when the fiber is reshaped (undulation, dispersion or a crossing-angle axis). With
/// undulationCoherence the population's field is sampled along the base path shifted by
/// `fieldShift` (generateCube passes the translation the seeding applies afterwards, so the field
/// is sampled where the fiber ends up).
FiberShape cubeFiberShape(const CubeOptions& options, int k, int j, const Vec3& fieldShift = {});

/// The achieved ⟨cos²⟩ of the end-to-end directions about the axis, per population (1 without
/// dispersion; every fiber of the model counted, so the same on every piece). Open cubes: the
/// sample mean of the Watson draws; periodic: of the lattice directions taken (their κ calibrated
/// so that they reach the request, Tissue/LatticeDispersion.h). About each population's own axis.
std::vector<double> cubeDispersionC2(const CubeOptions& options);

/// The axes of the cube's populations (unit vectors; periodic: the lattice directions taken).
std::vector<PopulationAxis> cubePopulationAxes(const CubeOptions& options);

/// The cell of a periodic cube: [-L/2, L/2]³.
PeriodicCell cubeCell(const CubeOptions& options);

/// Empty string when the options are usable, else a message naming the option and its value. The
/// memory guard checks one piece of `pieces` (its share of the fibers and points).
std::string validateCubeOptions(const CubeOptions& options, int pieces = 1);

/// Number of fibers of population k (0-based) when options.numberOfFibers are split (with
/// volumeFraction > 0 the counts come from the radii drawn, see generateCube).
int cubePopulationSize(const CubeOptions& options, int k);

/// Generates the cube. Fiber ids are 0..N-1 in population order. The draws of fiber j of population
/// k come from the stream (seed, k, j): transverse position (2), displacements point by point, then
/// (only with radiusSpread > 0) the radius. With volumeFraction > 0, fibers j = 0, 1, … are added
/// to the populations in turn (0, 1, 2, 0, …) until the fiber volume reaches the target (the
/// smallest such count). Pieces (docs/tissue-models.md §9): only the fibers of pieceRange(N, piece,
/// pieces) are built, with their global ids; the counts (and with volumeFraction the radii of all
/// fibers) are drawn by every piece, the points only for the piece's own fibers, so a piece holds
/// its share of the memory. Precondition: validateCubeOptions(options, pieces) is empty. warning
/// (if given): empty, or why the polydisperse Lattice seeding leaves fibers overlapping
/// (docs/periodic-cells.md, "Polydisperse seeding"); the same on every piece.
/// progress (Util/Progress.h): over that seeding's disk packing (the first 70 % when there is one)
/// and over the fibers' points (every 256 fibers); when it returns false the generator stops and
/// returns an empty model.
FiberModel generateCube(const CubeOptions& options, int piece = 0, int pieces = 1,
  std::string* warning = nullptr, const ProgressFn& progress = {});

} // namespace fiberpli
