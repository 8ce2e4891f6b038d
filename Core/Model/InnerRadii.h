/// InnerRadii: the optional point array `inner_radius` (docs/data-contract.md §2) in Core form — the
/// axon's radius inside a myelin sheath, one value per point of every fiber, beside the outer
/// `radius` that collisions use. Kept apart from FiberModel so that every algorithm that reshapes
/// fibers (the solver splits and moves points) stays unaware of it; the VTK layer interpolates the
/// array like any other point array.
#pragma once

#include "Model/FiberModel.h"

#include <string>
#include <vector>

namespace fiberpli
{

/// Empty (no myelin anywhere), or one vector per fiber of the model with one value per point.
using InnerRadii = std::vector<std::vector<double>>;

/// Empty when `inner` is empty or fits the model: one vector per fiber, one value per point, each
/// finite with 0 < inner <= radius (equal = no sheath at that point). Else a message naming the
/// fiber (index and fiber_id), the point and the value; badFiber (optional) receives the fiber's index.
std::string validateInnerRadii(const FiberModel& model, const InnerRadii& inner, std::size_t* badFiber = nullptr);

/// The model with every radius replaced by its inner radius (the axons alone); `inner` must be
/// valid and non-empty.
FiberModel axonModel(const FiberModel& model, const InnerRadii& inner);

} // namespace fiberpli
