#include "Tissue/ShapeOptions.h"

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
  std::ostringstream msg;
  const int model = static_cast<int>(o.gRatioModel);
  GRatioModel known;
  if (!std::isfinite(o.tortuosity) || o.tortuosity < 1.0)
  {
    msg << "Tortuosity is " << o.tortuosity << ", must be >= 1 (1 = straight fibers)";
  }
  else if (o.tortuosity > 3.0)
  {
    msg << "Tortuosity is " << o.tortuosity << ", must be at most 3 (white matter is below 1.5)";
  }
  else if (o.undulating() &&
    (!std::isfinite(o.undulationWavelength) || o.undulationWavelength <= 0.0))
  {
    msg << "UndulationWavelength is " << o.undulationWavelength << ", must be > 0";
  }
  else if (!std::isfinite(o.dispersionC2) || o.dispersionC2 <= 1.0 / 3.0 || o.dispersionC2 > 1.0)
  {
    msg << "DispersionC2 is " << o.dispersionC2
        << ", must be in (1/3, 1] (1 = no dispersion, 1/3 = isotropic)";
  }
  else if (!std::isfinite(o.beadingCV) || o.beadingCV < 0.0 || o.beadingCV > kMaxBeadingCV)
  {
    msg << "BeadingCV is " << o.beadingCV << ", must be in [0, " << kMaxBeadingCV << "] (0 = off)";
  }
  else if (o.beaded() && (!std::isfinite(o.beadingLength) || o.beadingLength <= 0.0))
  {
    msg << "BeadingLength is " << o.beadingLength << ", must be > 0";
  }
  else if (!std::isfinite(o.gRatio) || o.gRatio < 0.0 || o.gRatio >= 1.0)
  {
    msg << "GRatio is " << o.gRatio << ", must be in (0, 1) (0 = no myelin)";
  }
  else if (!gRatioModelFromCode(model, known).empty())
  {
    msg << gRatioModelFromCode(model, known);
  }
  return msg.str();
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
