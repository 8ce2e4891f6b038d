/// OptionLimits: the largest values PLISimulation accepts where a larger one would not fail by
/// itself but silently turn the images into inf, NaN or zeros: such values are refused, never
/// clamped. The XML ranges of Plugin/PLISimulation.xml repeat these numbers; planPLI and
/// makeTissueSpec check them.
#pragma once

namespace fiberpli
{
namespace pli
{

/// LightIntensity: camera counts stay exact integers in a double (< 2^53) and the Poisson and
/// Gamma samplers stay finite.
constexpr double kMaxLightIntensity = 1e15;

/// NoiseGain: variance g·I; real cameras have g of about 1 to 10. Far beyond 1000 the Gamma shape
/// I/(g − 1) underflows and every count becomes 0.
constexpr double kMaxNoiseGain = 1000.0;

/// |Δn| of Birefringence and of every Layers tuple: a refractive-index difference, about 1e-3 in
/// nerve tissue and 0.17 in calcite; above 1 it is not a birefringence, and near 1e308 the phase
/// overflows to inf and the images become NaN.
constexpr double kMaxBirefringence = 1.0;

/// List lengths of RotationAngles, TiltAngles and TiltAzimuths, and of their product (tilted
/// views): beyond these the images are not more useful, only larger.
constexpr int kMaxRotationAngles = 3600;
constexpr int kMaxTiltAngles = 64;
constexpr int kMaxTiltAzimuths = 360;
constexpr int kMaxTiltedViews = 1024;

} // namespace pli
} // namespace fiberpli
