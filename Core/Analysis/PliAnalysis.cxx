#include "Analysis/PliAnalysis.h"

#include "Analysis/RetardationInclination.h"
#include "Model/DataNames.h"
#include "Util/EnumCode.h"
#include "Util/ValueCheck.h"

#include <cmath>
#include <limits>
#include <sstream>

namespace fiberpli
{

std::string inclinationMethodFromCode(int code, InclinationMethod& method)
{
  return enumFromCode(
    code, 2, "InclinationMethod", "0 (Auto), 1 (Retardation) or 2 (Tilt)", method);
}

std::string checkPliAnalysisOptions(const PliAnalysisOptions& options)
{
  const double gain = options.noiseGain;
  return ValueChecks()
    .within("ReferenceRetardation", options.referenceRetardation, 0.0, 1.0, " (0 = automatic)")
    .require(gain == -1.0 || (gain >= 0.0 && gain <= kMaxAnalysisNoiseGain), "NoiseGain", gain,
      "-1 (from the data) or in [0, " + formatNumber(kMaxAnalysisNoiseGain) + "]")
    .error();
}

Status analysePli(const PliStack& stack, const PliAnalysisOptions& options, const GridRange& range,
  PliAnalysisMaps& maps, const ProgressFn& progress)
{
  const std::string optionError = checkPliAnalysisOptions(options);
  if (!optionError.empty())
  {
    return optionError;
  }
  bool haveTilts = stack.tilts.size() >= 2 && stack.tilts.size() == stack.tiltViews.size();
  for (std::size_t t = 0; haveTilts && t < stack.tilts.size(); ++t)
  {
    haveTilts = stack.tilts[t] != nullptr && stack.tiltViews[t].theta > 0.0;
  }
  InclinationMethod method = options.method;
  if (method == InclinationMethod::Auto)
  {
    method = haveTilts ? InclinationMethod::Tilt : InclinationMethod::Retardation;
  }
  if (method == InclinationMethod::Tilt && !haveTilts)
  {
    std::ostringstream msg;
    msg << "InclinationMethod is Tilt but the input has ";
    if (stack.tilts.size() != stack.tiltViews.size())
    {
      msg << stack.tilts.size() << " tilted stacks (" << plifield::kIntensityTiltPrefix << "*) for "
          << stack.tiltViews.size() << " tilted views (" << plifield::kTiltAngles << " / "
          << plifield::kTiltDirections << ")";
    }
    else if (stack.tilts.size() < 2)
    {
      msg << stack.tilts.size() << " tilted views (" << plifield::kIntensityTiltPrefix
          << "*), the tilt fit needs at least 2";
    }
    else
    {
      for (std::size_t t = 0; t < stack.tilts.size(); ++t)
      {
        if (!stack.tilts[t])
        {
          msg << "no " << plifield::intensityTilt(t);
          break;
        }
        if (!(stack.tiltViews[t].theta > 0.0))
        {
          msg << plifield::kTiltAngles << "[" << t
              << "] = " << stack.tiltViews[t].theta * 180.0 / M_PI << " deg (needs > 0)";
          break;
        }
      }
    }
    return msg.str();
  }
  maps.method = method;

  // EPA first: up to half of the progress for the tilt fit's sake, all of it otherwise.
  const double epaShare = method == InclinationMethod::Tilt ? 0.1 : 0.9;
  EpaMaps epa;
  epa.transmittance.swap(maps.transmittance);
  epa.direction.swap(maps.direction);
  epa.retardation.swap(maps.retardation);
  Status status = computeEpa(stack.intensity, stack.nx, stack.ny, stack.rho, range, options.threads,
    epa, [&](double f) { return reportProgress(progress, epaShare * f); });
  maps.transmittance.swap(epa.transmittance);
  maps.direction.swap(epa.direction);
  maps.retardation.swap(epa.retardation);
  if (!status.ok())
  {
    return status;
  }

  if (method == InclinationMethod::Retardation)
  {
    maps.inclinationSigned.clear();
    maps.relativeThickness.clear();
    maps.chi2.clear();
    double rRef = options.referenceRetardation;
    if (rRef == 0.0)
    {
      rRef = maxRetardation(maps.retardation.data(), stack.nx, range);
      if (options.globalMaxRetardation)
      {
        rRef = options.globalMaxRetardation(rRef);
      }
      // A zero maximum leaves the automatic mode: every pixel then reads 90° by the r = 0 rule.
      rRef = rRef > 0.0 ? rRef : 1.0;
    }
    maps.referenceRetardation = rRef;
    const std::string err = inclinationMapFromRetardation(
      maps.retardation.data(), stack.nx, stack.ny, range, rRef, options.threads, maps.inclination);
    if (!err.empty())
    {
      return err;
    }
    return reportProgress(progress, 1.0) ? Status() : Status::stopped();
  }

  TiltFitOptions to;
  to.views = stack.tiltViews;
  to.convention = stack.convention;
  to.gain =
    options.noiseGain >= 0.0 ? options.noiseGain : (stack.noiseGain >= 0.0 ? stack.noiseGain : 3.0);
  TiltMaps tm;
  status = computeTiltFit(stack.intensity, stack.tilts, stack.nx, stack.ny, stack.rho, to, range,
    options.threads, tm,
    [&](double f) { return reportProgress(progress, epaShare + (1.0 - epaShare) * f); });
  if (!status.ok())
  {
    return status;
  }
  maps.referenceRetardation = 0.0;
  maps.inclination.swap(tm.inclination);
  maps.inclinationSigned.swap(tm.inclinationSigned);
  maps.relativeThickness.swap(tm.relativeThickness);
  maps.chi2.swap(tm.chi2);
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::int64_t j = range.j0; j < range.j1; ++j)
  {
    for (std::int64_t i = range.i0; i < range.i1; ++i)
    {
      const std::size_t p = static_cast<std::size_t>(i + stack.nx * j);
      if (std::isnan(tm.direction[p]))
      {
        maps.transmittance[p] = maps.retardation[p] = nan;
      }
      maps.direction[p] = tm.direction[p];
    }
  }
  return {};
}

} // namespace fiberpli
