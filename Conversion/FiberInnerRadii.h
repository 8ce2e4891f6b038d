/**
 * @file FiberInnerRadii.h
 * @brief the optional point array `inner_radius` (docs/data-contract.md §2) of fiber polydata as
 * the Core's InnerRadii, fiber by fiber in the order of a FiberConversion
 */
#ifndef FiberInnerRadii_h
#define FiberInnerRadii_h

#include "FiberPLIConversionModule.h" // for export macro
#include "FiberPolyData.h"
#include "Model/InnerRadii.h"

#include <string>

class vtkPolyData;

namespace fiberpli
{

/// Reads `inner_radius` of `input` into Fiber::innerRadii of the fibers of `conversion` (made by
/// FiberPolyData::ToModel from the same input, with its sourcePoints); without the array the
/// fibers keep none. Returns "" or an error prefixed by `who` (the inner radii then cleared): more
/// than one component, a wrong number of values, or a value that is not finite in (0, radius]
/// (naming the line cell, fiber and point).
FIBERPLICONVERSION_EXPORT std::string ReadInnerRadii(
  vtkPolyData* input, FiberConversion& conversion, const std::string& who);

/// Adds the point array `inner_radius` (double) to `output`, made by FiberPolyData::FromModel from
/// `model`, when some fiber of the model has inner radii; a fiber without them gets its radius (no
/// sheath). Points are in FromModel's order (fiber by fiber).
FIBERPLICONVERSION_EXPORT void AddInnerRadii(const FiberModel& model, vtkPolyData* output);

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberInnerRadii.h
