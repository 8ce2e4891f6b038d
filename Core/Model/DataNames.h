/// DataNames: the names of every array and field-data value that FiberPLI's stages write for one
/// another (docs/data-contract.md §2, §6; docs/pli-simulation.md §7). Each name is written once,
/// here, and every writer and reader (and every Core message that names one) takes it from here,
/// so that a name cannot drift between the stage that writes it and the one that reads it.
#pragma once

#include <cstddef>
#include <string>

namespace fiberpli
{

/// Fiber polydata (docs/data-contract.md §2, §6, §9).
namespace fiberfield
{

// Point and cell arrays of the fibers.
constexpr const char* kRadius = "radius";            ///< point array, µm
constexpr const char* kInnerRadius = "inner_radius"; ///< point array, µm (myelinated fibers)
constexpr const char* kFiberId = "fiber_id";         ///< cell array
constexpr const char* kBundleId = "bundle_id";       ///< cell array
constexpr const char* kTrajectoryScale = "scale";    ///< point array of a bundle's trajectory

// Field data of the sources.
constexpr const char* kSegmentLength = "segment_length";   ///< µm (the sources and the solver)
constexpr const char* kSeed = "seed";                      ///< int
constexpr const char* kPeriodicCell = "periodic_cell";     ///< xmin xmax ymin ymax zmin zmax
constexpr const char* kPopulationAxes = "population_axes"; ///< 3 values per population
constexpr const char* kDispersionC2 = "dispersion_c2";     ///< achieved ⟨cos²⟩ per population
constexpr const char* kBoxSize =
  "box_size"; ///< µm, a CACTUS strand list's box (FiberReader, FiberWriter)
/// FiberFieldSource: Σ π r² · length of the traced fibers over the field's non-empty volume.
constexpr const char* kTracedVolumeFraction = "traced_volume_fraction";

// Field data of FiberCollisionSolver (docs/solver.md §9, §13).
constexpr const char* kSteps = "steps";            ///< int, moves run
constexpr const char* kCollisions = "collisions";  ///< int, capsule pairs still overlapping
constexpr const char* kSolved = "solved";          ///< int, 1 when collisions is 0
constexpr const char* kMaxOverlap = "max_overlap"; ///< µm
constexpr const char* kShapeOk = "shape_ok";       ///< int 0/1
constexpr const char* kVolumeFraction = "volume_fraction";
constexpr const char* kMinGap = "min_gap"; ///< µm
constexpr const char* kRadiusScale = "radius_scale";
constexpr const char* kTortuositySolves = "tortuosity_solves"; ///< int, with HoldTortuosity
constexpr const char* kRankPoints = "rank_points"; ///< this rank's share of a distributed solve …
constexpr const char* kHaloLinks = "halo_links";
constexpr const char* kHeldLinks = "held_links";
constexpr const char* kHaloBytesPerStep = "halo_bytes_per_step";
constexpr const char* kMigrations = "migrations";
constexpr const char* kTesterRecuts = "tester_recuts";
constexpr const char* kTesterCutMove = "tester_cut_move"; ///< … (docs/solver.md §13)

} // namespace fiberfield

/// The PLISimulation image (docs/pli-simulation.md §7), written by PLISimulation and read by
/// PLIAnalysis, and the maps and field data the analysis filters add.
namespace plifield
{

// Point arrays of the image: one component per polarizer angle.
constexpr const char* kIntensity = "intensity";                 ///< untilted view
constexpr const char* kIntensityTiltPrefix = "intensity_tilt_"; ///< + index of the tilted view

/// Name of the stack of tilted view v (0-based): intensity_tilt_<v>.
inline std::string intensityTilt(std::size_t v)
{
  return kIntensityTiltPrefix + std::to_string(v);
}

// Field data of the image.
constexpr const char* kPolarizerAngles = "polarizer_angles"; ///< degrees
constexpr const char* kTiltAngle = "tilt_angle";             ///< largest in-tissue tilt, degrees
constexpr const char* kTiltAngles = "tilt_angles"; ///< in-tissue tilt per tilted view, degrees
constexpr const char* kTiltDirections =
  "tilt_directions"; ///< tilt azimuth per tilted view, degrees
constexpr const char* kSectionThickness = "section_thickness"; ///< µm
constexpr const char* kWavelength = "wavelength";              ///< nm
constexpr const char* kTiltConvention = "tilt_convention"; ///< int, Section/TiltConvention.h code
constexpr const char* kTiltedSensor = "tilted_sensor";     ///< int 0/1
constexpr const char* kNoiseGain = "noise_gain";
constexpr const char* kEmptySection = "empty_section"; ///< int 0/1
constexpr const char* kVoxelSize = "voxel_size";       ///< µm (image and tissue port)
constexpr const char* kPixelSize = "pixel_size";       ///< µm
constexpr const char* kLightIntensity = "light_intensity";
constexpr const char* kTileFibers = "tile_fibers";   ///< fibers this piece was computed from
constexpr const char* kModelFibers = "model_fibers"; ///< fibers of the whole model

// The tissue port (ExportTissue).
constexpr const char* kLabel = "label";                       ///< point array, int
constexpr const char* kOpticAxis = "optic_axis";              ///< point array, 3 floats
constexpr const char* kLabelBundleIds = "label_bundle_ids";   ///< field data
constexpr const char* kLayersPerBundle = "layers_per_bundle"; ///< field data, int

// Point arrays (maps) of PLIAnalysis and FiberOrientationGroundTruth, one value per pixel.
constexpr const char* kTransmittance = "transmittance";
constexpr const char* kDirection = "direction"; ///< degrees in [0, 180)
constexpr const char* kRetardation = "retardation";
constexpr const char* kInclination = "inclination";              ///< degrees in [0, 90]
constexpr const char* kInclinationSigned = "inclination_signed"; ///< degrees in [−90, 90]
constexpr const char* kRelativeThickness = "relative_thickness";
constexpr const char* kFitChi2 = "fit_chi2";
constexpr const char* kFraction = "fraction";     ///< ground truth: tissue share
constexpr const char* kAnisotropy = "anisotropy"; ///< ground truth: λ1 − λ2

// Field data PLIAnalysis adds to its maps.
constexpr const char* kReferenceRetardation = "reference_retardation";
constexpr const char* kInclinationMethod = "inclination_method"; ///< int

// FiberOrientationMap's image.
constexpr const char* kFom = "fom";   ///< point array, RGB
constexpr const char* kMask = "mask"; ///< point array, 0/1
constexpr const char* kMaskThreshold =
  "mask_threshold"; ///< field data, absolute threshold of the mask

} // namespace plifield
} // namespace fiberpli
