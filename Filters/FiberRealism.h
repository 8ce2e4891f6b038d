/**
 * @file FiberRealism.h
 * @brief the realism knobs FiberCubeSource and FiberBundleSource share, read into the Core options
 *
 * Both sources have the same properties (Tortuosity, UndulationWavelength, DispersionC2,
 * BeadingCV, BeadingLength, GRatio, GRatioModel; docs/tissue-models.md §10); this is the one place
 * that maps them onto fiberpli::ShapeOptions.
 */
#ifndef FiberRealism_h
#define FiberRealism_h

#include "Tissue/ShapeOptions.h"

namespace fiberpli
{

/// The realism knobs of a source (anything with the knobs' getters) as Core options: "" or the
/// message naming a GRatioModel code outside the enum.
template <typename Source>
std::string RealismKnobs(Source* source, ShapeOptions& realism)
{
  realism.tortuosity = source->GetTortuosity();
  realism.undulationWavelength = source->GetUndulationWavelength();
  realism.dispersionC2 = source->GetDispersionC2();
  realism.beadingCV = source->GetBeadingCV();
  realism.beadingLength = source->GetBeadingLength();
  realism.gRatio = source->GetGRatio();
  return gRatioModelFromCode(source->GetGRatioModel(), realism.gRatioModel);
}

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberRealism.h
