#include "Analysis/PliStackRules.h"

#include "Model/DataNames.h"

#include <sstream>

namespace fiberpli
{
namespace
{
constexpr double kDeg = 3.14159265358979323846 / 180.0;
} // namespace

std::vector<double> polarizerAnglesOf(const PliStackFields& fields)
{
  std::vector<double> rho;
  if (fields.hasPolarizerAngles)
  {
    for (double a : fields.polarizerAngles)
    {
      rho.push_back(a * kDeg);
    }
    return rho;
  }
  const int n = fields.components;
  for (int k = 0; k < n; ++k)
  {
    rho.push_back(k * 180.0 / n * kDeg);
  }
  return rho;
}

std::string tiltViewsOf(
  const PliStackFields& fields, std::size_t stacks, std::vector<TiltView>& views)
{
  views.clear();
  if (stacks == 0)
  {
    return {};
  }
  std::vector<double> angles = fields.tiltAngles;
  std::vector<double> azimuths = fields.tiltDirections;
  if (!fields.hasTiltAngles)
  {
    angles.assign(stacks, fields.tiltAngle);
  }
  if (azimuths.empty() && stacks == 4)
  {
    azimuths = { 0.0, 90.0, 180.0, 270.0 };
  }
  std::ostringstream msg;
  if (angles.size() != stacks)
  {
    msg << "field data '" << plifield::kTiltAngles << "' has " << angles.size() << " values for "
        << stacks << " tilted views (" << plifield::kIntensityTiltPrefix << "*)";
    return msg.str();
  }
  if (azimuths.size() != stacks)
  {
    msg << "field data '" << plifield::kTiltDirections << "' has " << azimuths.size()
        << " values for " << stacks << " tilted views (" << plifield::kIntensityTiltPrefix << "*)";
    return msg.str();
  }
  for (std::size_t v = 0; v < stacks; ++v)
  {
    views.push_back(TiltView{ angles[v] * kDeg, azimuths[v] * kDeg });
  }
  return {};
}

std::string decodePliStack(
  const PliStackFields& fields, InclinationMethod method, PliStackLayout& layout)
{
  layout = PliStackLayout();
  std::ostringstream msg;
  if (fields.slices != 1)
  {
    msg << "the input has " << fields.slices
        << " slices along z; expected one slice (the PLISimulation image)";
    return msg.str();
  }
  if (!fields.hasIntensity)
  {
    msg << "the input has no point array '" << plifield::kIntensity
        << "' (one component per polarizer angle)";
    return msg.str();
  }
  const int n = fields.components;
  layout.rho = polarizerAnglesOf(fields);
  if (layout.rho.size() < 3)
  {
    msg << layout.rho.size() << " polarizer angles (field data '" << plifield::kPolarizerAngles
        << "' or the components of '" << plifield::kIntensity << "'); at least 3 are needed";
    return msg.str();
  }
  if (static_cast<std::size_t>(n) != layout.rho.size())
  {
    msg << "point array '" << plifield::kIntensity << "' has " << n
        << " components but field data '" << plifield::kPolarizerAngles << "' has "
        << layout.rho.size() << " angles; they must be equal";
    return msg.str();
  }
  for (std::size_t v = 0; v < fields.tiltComponents.size(); ++v)
  {
    if (fields.tiltComponents[v] != n)
    {
      msg << "point array '" << plifield::intensityTilt(v) << "' has " << fields.tiltComponents[v]
          << " components, '" << plifield::kIntensity << "' has " << n << "; they must be equal";
      return msg.str();
    }
  }
  layout.tiltStacks = fields.tiltComponents.size();
  const std::string tiltError = tiltViewsOf(fields, layout.tiltStacks, layout.tiltViews);
  if (!tiltError.empty())
  {
    return tiltError;
  }
  if (fields.tiltedSensor == 1.0 && layout.tiltStacks > 0)
  {
    if (method == InclinationMethod::Tilt)
    {
      msg << "InclinationMethod Tilt needs tilted views registered onto the sample's pixel grid, "
             "but these are on "
             "the tilted sensor's grid (field data "
          << plifield::kTiltedSensor
          << " = 1): simulate with TiltedSensor off, or use InclinationMethod Retardation";
      return msg.str();
    }
    layout.tiltStacks = 0; // Auto: the retardation method, from the untilted view alone
    layout.tiltViews.clear();
  }
  layout.convention = fields.tiltConvention == tiltConventionCode(TiltConvention::FastPLI)
    ? TiltConvention::FastPLI
    : TiltConvention::Physical;
  layout.noiseGain = fields.noiseGain;
  return {};
}

} // namespace fiberpli
