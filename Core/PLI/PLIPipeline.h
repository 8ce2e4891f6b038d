/// PLIPipeline: the whole `PLISimulation` filter in Core form (docs/pli-simulation.md §2.1, §6.2,
/// §7): options → lattice, layers and views → simulate the voxel columns a pixel range needs (with
/// the blur halo) → blur → bin → noise. Any pixel sub-rectangle gives exactly the crop of the
/// whole image, so the VTK filter can split the plane over MPI ranks without communication.
#pragma once

#include "Model/FiberModel.h"
#include "PLI/PLITypes.h"
#include "Section/SectionPlan.h"
#include "Util/Progress.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{
namespace pli
{

/// The filter properties of §2.1 (angles in degrees, as at the ParaView boundary).
struct PLIOptions
{
  double volumeOfInterest[6] = { 1, -1, 1, -1, 1,
    -1 };                    ///< µm; min > max on every axis = model bounds
  double voxelSize = 0.5;    ///< µm, > 0
  double pixelSize = 2.0;    ///< µm, >= voxelSize
  double wavelength = 525.0; ///< nm
  double lightIntensity = 26000.0;
  int numberOfRotations = 18; ///< >= 3; ρ_k = k·180°/N (when rotationAngles is empty)
  std::vector<double>
    rotationAngles;       ///< deg, each in [0, 180), distinct, >= 3; empty = numberOfRotations
  double tiltAngle = 0.0; ///< deg, [0, 45); 0 = no tilted views (when tiltAngles is empty)
  std::vector<double> tiltAngles;   ///< deg, each in (0, 45), distinct; empty = {tiltAngle} if > 0
  std::vector<double> tiltAzimuths; ///< deg, each in [0, 360), distinct; empty = 0, 90, 180, 270
  double birefringence = -0.001;
  double absorption = 0.0; ///< 1/mm
  std::uint64_t seed = 0;
  std::string layers; ///< §3.2 grammar; overrides birefringence/absorption
  double backgroundAbsorption = 0.0;
  double stepSize = 1.0; ///< voxels
  Interp interpolation = Interp::Slerp;
  double opticalSigma = 0.71; ///< output pixels, 0 = off
  double noiseGain = 3.0;     ///< 0 = off, else >= 1
  double refractiveIndex = 1.0;
  bool tiltedSensor = false; ///< tilted views on the tilted sensor's grid (§4.6), not registered
  int numberOfThreads = 0;
  /// The bundle ids of the whole model when `model` holds only the fibers of one MPI tile (§6.3),
  /// so that every tile has the same layer table and labels; empty = those of the model.
  std::vector<int> bundleIds;
  /// The whole model carries inner_radius (set by the caller for an MPI tile, like bundleIds;
  /// a model with Fiber::innerRadii counts by itself): myelinated tissue when `layers` is empty
  /// (§3.2).
  bool myelin = false;
  // Core-only switches (§2.1).
  TiltConvention tiltConvention = TiltConvention::Physical;
  StepRule stepRule = StepRule::ExactLength;
  LateralOutside lateralOutside = LateralOutside::SampleFibers;
  RadiusModel radiusModel = RadiusModel::Linear;
  int tileSize = 64;
};

/// The integer code of the Interpolation property (Plugin/PLISimulation.xml) → the Core enum:
/// "" or an error naming the property and the value; other codes are refused, never cast. (The
/// TiltConvention code: Section/TiltConvention.h.)
std::string interpolationFromCode(
  int code, Interp& interpolation); ///< 0 nearest, 1 linear, 2 Slerp

/// What RequestInformation needs, computed without voxelising: the section (lattice, pixel grid,
/// image geometry: §3.1, §5.2, planned by Section/SectionPlan.h), the tissue and the views.
struct PLIPlan : SectionPlan
{
  TissueSpec tissue;
  std::vector<View> views; ///< untilted, then every tilt angle × every azimuth (angle-major)
  std::vector<double> tiltDeg, azimuthDeg; ///< per tilted view: in-tissue θ_t and φ_t, degrees
  std::vector<double> rho;                 ///< radians
  std::vector<double> rhoDeg;              ///< the same in degrees, exactly as given (field data)
  double tiltInTissue = 0.0;               ///< largest θ_t, radians (0 = untilted only)
  double sigmaVox = 0.0;                   ///< blur σ in voxels
  std::size_t bytesPerVoxel = 0;           ///< tile buffer bytes per voxel (§3.4)
  double estimatedBytes = 0.0;             ///< whole-image run in one process (estimatePieceBytes)
};

/// Validates options (before any allocation) and derives the plan. Errors name the property. The
/// memory budget is not checked here but by runPLI for the piece it computes (estimatePieceBytes):
/// the whole image may exceed one process's budget when it is split over MPI ranks.
/// planPLI = planPLIImage, then planPLITissue (warnings of both).
Status planPLI(const FiberModel& model, const PLIOptions& options, PLIPlan& plan);

/// The part of the plan the image geometry needs (RequestInformation): the options, the section
/// (planSection; the model is used only for its bounds when VolumeOfInterest is the sentinel), the
/// views and polarizer angles, the blur and the memory estimate. Resets the plan.
Status planPLIImage(const FiberModel& model, const PLIOptions& options, PLIPlan& plan);

/// The part that needs the fibers: the layers of the bundles (options.bundleIds, else the model's;
/// plan.tissue, §3.2) and the warning when VoxelSize does not resolve the smallest radius. Call
/// after planPLIImage.
Status planPLITissue(const FiberModel& model, const PLIOptions& options, PLIPlan& plan);

/// The warning of planPLITissue when VoxelSize > half the model's smallest radius, else "".
std::string resolutionWarning(const FiberModel& model, const PLIOptions& options);

struct PLIImage
{
  PLIPlan plan;
  GridRange range;           ///< pixels computed (global pixel indices)
  std::vector<Stack> views;  ///< one pixel stack per view, covering range
  bool emptySection = false; ///< background only (warning in status)
  /// Some voxel was reachable by two fibers and the nearest won (§3.3). Expected for a model that
  /// was never solved; the caller decides whether it deserves a warning (it knows the model's
  /// origin).
  bool fibersOverlap = false;
  double voxeliseCpuSeconds = 0.0, propagateCpuSeconds = 0.0, opticsSeconds = 0.0;
  std::int64_t raySteps = 0;
  std::size_t peakTissueBytes = 0; ///< estimate of the tile buffers + voxel stacks
};

/// Voxel columns (global, clipped to the voxel image) whose rays a pixel range needs: the voxels
/// that bin into it, grown by the blur radius (§6.2 step 3).
GridRange voxelColumnsFor(const PLIPlan& plan, const PLIOptions& options, const GridRange& pixels);

/// Bytes runPLI plans for the pixel range `pixels`: tile buffers and voxel stacks of its columns
/// (with the blur halo), the blur buffers, and its pixel stacks twice (Core and VTK arrays).
double estimatePieceBytes(const PLIPlan& plan, const PLIOptions& options, const GridRange& pixels);

/// The propagation settings of the options (what runPLI hands to simulate).
SimParams simParams(const PLIPlan& plan, const PLIOptions& options);

/// Runs the simulation for `pixels` (an empty range = the whole image). status.error set on
/// invalid options or when the piece exceeds the memory budget; the model must be valid
/// (validateModel). status.aborted when progress asked to stop (the image is then incomplete).
Status runPLI(const FiberModel& model, const PLIOptions& options, GridRange pixels, PLIImage& image,
  const ProgressFn& progress = {});

/// The same with the plan planPLI made for this model and these options (the VTK filter plans once
/// per change of its input or properties and runs every piece and request on that plan).
Status runPLI(const FiberModel& model, const PLIOptions& options, const PLIPlan& plan,
  GridRange pixels, PLIImage& image, const ProgressFn& progress = {});

} // namespace pli
} // namespace fiberpli
