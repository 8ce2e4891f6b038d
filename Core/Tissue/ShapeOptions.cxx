#include "Tissue/ShapeOptions.h"

#include "Util/ValueCheck.h"

#include <cmath>
#include <sstream>

namespace fiberpli
{

const char* gRatioModelName(GRatioModel model)
{
  switch (model)
  {
    case GRatioModel::Constant:
      return "Constant";
    case GRatioModel::Lee2019:
      return "Lee2019";
  }
  return "Unknown";
}

std::string validateShapeOptions(const ShapeOptions& o)
{
  const auto finite = [](double v) { return std::isfinite(v); };
  GRatioModel known;
  return ValueChecks()
    .require(finite(o.tortuosity) && o.tortuosity >= 1.0, "Tortuosity", o.tortuosity,
      ">= 1 (1 = straight fibers)")
    .require(
      o.tortuosity <= 3.0, "Tortuosity", o.tortuosity, "at most 3 (white matter is below 1.5)")
    .require(!o.undulating() || (finite(o.undulationWavelength) && o.undulationWavelength > 0.0),
      "UndulationWavelength", o.undulationWavelength, "> 0")
    .require(finite(o.dispersionC2) && o.dispersionC2 > 1.0 / 3.0 && o.dispersionC2 <= 1.0,
      "DispersionC2", o.dispersionC2, "in (1/3, 1] (1 = no dispersion, 1/3 = isotropic)")
    .require(finite(o.beadingCV) && o.beadingCV >= 0.0 && o.beadingCV <= kMaxBeadingCV, "BeadingCV",
      o.beadingCV, "in [0, " + formatNumber(kMaxBeadingCV) + "] (0 = off)")
    .require(!o.beaded() || (finite(o.beadingLength) && o.beadingLength > 0.0), "BeadingLength",
      o.beadingLength, "> 0")
    .require(finite(o.gRatio) && o.gRatio >= 0.0 && o.gRatio < 1.0, "GRatio", o.gRatio,
      "in (0, 1) (0 = no myelin)")
    .then(gRatioModelFromCode(static_cast<int>(o.gRatioModel), known))
    .error();
}

std::string shapeWarnings(const ShapeOptions& o, double segmentLength)
{
  if (!o.undulating() || o.undulationWavelength >= 4.0 * segmentLength)
    return {};
  std::ostringstream msg;
  msg << "UndulationWavelength " << o.undulationWavelength << " is shorter than 4 x SegmentLength ("
      << 4.0 * segmentLength << "): the points cannot follow the waves and the fibers zig-zag; "
      << "use a longer wavelength or a shorter SegmentLength";
  return msg.str();
}

} // namespace fiberpli
