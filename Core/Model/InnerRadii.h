/// InnerRadii: the optional point array `inner_radius` (docs/data-contract.md §2) in Core form —
/// Fiber::innerRadii, the axon's radius inside a myelin sheath at each point, beside the outer
/// `radius` that collisions use. A fiber without it has no sheath. The VTK layer fills it only for
/// the algorithms that use it (FiberMetrics, PLISimulation); the solver never sees it (the VTK
/// layer interpolates the array like any other point array where links are split).
#pragma once

#include "Model/FiberModel.h"

#include <cstddef>
#include <string>

namespace fiberpli
{

/// True when at least one fiber carries inner radii.
bool hasInnerRadii(const FiberModel& model);

/// Empty when every fiber's innerRadii is empty or fits it: one value per point, each finite with
/// 0 < inner <= radius (equal = no sheath at that point). Else a message naming the fiber (index
/// and fiber_id), the point and the value; badFiber (optional) receives the fiber's index.
std::string validateInnerRadii(const FiberModel& model, std::size_t* badFiber = nullptr);

/// The axons alone: every fiber with inner radii gets them as its radii (and none of its own);
/// fibers without keep their radii (an unmyelinated fiber is all axon).
FiberModel axonModel(const FiberModel& model);

} // namespace fiberpli
