/// PLIFields: the names of the arrays and field data of a PLISimulation image (docs/pli-simulation.md
/// §7), written by PLISimulation and read by PLIAnalysis (and named in the Core's messages), and
/// of the field data the analysis filters add: one place for every writer and reader, so that a
/// name cannot drift between them.
#pragma once

#include <cstddef>
#include <string>

namespace fiberpli
{
namespace plifield
{

// Point arrays of the image: one component per polarizer angle.
constexpr const char* kIntensity = "intensity";                ///< untilted view
constexpr const char* kIntensityTiltPrefix = "intensity_tilt_"; ///< + index of the tilted view

/// Name of the stack of tilted view v (0-based): intensity_tilt_<v>.
inline std::string intensityTilt(std::size_t v) { return kIntensityTiltPrefix + std::to_string(v); }

// Field data of the image.
constexpr const char* kPolarizerAngles = "polarizer_angles";  ///< degrees
constexpr const char* kTiltAngle = "tilt_angle";              ///< largest in-tissue tilt, degrees
constexpr const char* kTiltAngles = "tilt_angles";            ///< in-tissue tilt per tilted view, degrees
constexpr const char* kTiltDirections = "tilt_directions";    ///< tilt azimuth per tilted view, degrees
constexpr const char* kSectionThickness = "section_thickness"; ///< µm
constexpr const char* kWavelength = "wavelength";             ///< nm
constexpr const char* kTiltConvention = "tilt_convention";    ///< int, Section/TiltConvention.h code
constexpr const char* kTiltedSensor = "tilted_sensor";        ///< int 0/1
constexpr const char* kNoiseGain = "noise_gain";
constexpr const char* kEmptySection = "empty_section";        ///< int 0/1
constexpr const char* kVoxelSize = "voxel_size";              ///< µm (image and tissue port)
constexpr const char* kPixelSize = "pixel_size";              ///< µm
constexpr const char* kLightIntensity = "light_intensity";
constexpr const char* kTileFibers = "tile_fibers";            ///< fibers this piece was computed from
constexpr const char* kModelFibers = "model_fibers";          ///< fibers of the whole model

// The tissue port (ExportTissue).
constexpr const char* kLabel = "label";                       ///< point array, int
constexpr const char* kOpticAxis = "optic_axis";              ///< point array, 3 floats
constexpr const char* kLabelBundleIds = "label_bundle_ids";   ///< field data
constexpr const char* kLayersPerBundle = "layers_per_bundle"; ///< field data, int

// Field data PLIAnalysis adds to its maps.
constexpr const char* kReferenceRetardation = "reference_retardation";
constexpr const char* kInclinationMethod = "inclination_method"; ///< int

// Field data FiberOrientationMap adds to its image.
constexpr const char* kMaskThreshold = "mask_threshold"; ///< absolute threshold of the mask

} // namespace plifield
} // namespace fiberpli
