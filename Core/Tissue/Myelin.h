/// Myelin: the inner (axon) radius of a myelinated fiber from its outer radius
/// (docs/tissue-models.md §10.4). The outer radius is the fiber's `radius`, the one collisions use;
/// the sheath is the shell between the inner radius and it.
#pragma once

#include "Model/FiberModel.h"
#include "Tissue/ShapeOptions.h"

namespace fiberpli
{

/// Myelin thickness (µm) of an axon of inner diameter d (µm, > 0) after Lee et al. 2019:
/// 0.35 + 0.006·d + 0.024·ln d.
double lee2019MyelinThickness(double innerDiameter);

/// The inner radius of a fiber of outer radius R > 0: Constant: gRatio·R; Lee2019: d/2 where d
/// solves R = d/2 + lee2019MyelinThickness(d) (the right side grows strictly with d, from −∞, so
/// there is exactly one d > 0 for every R > 0; found by bisection to 1e-12 relative). gRatio must
/// be in (0, 1) for Constant and is not used by Lee2019.
double innerRadius(double outerRadius, double gRatio, GRatioModel model);

/// With myelin on (realism.myelinated()), gives every fiber its inner radii (Fiber::innerRadii,
/// one per point, innerRadius of its radius); with myelin off the model is left as it is.
void addMyelin(FiberModel& model, const ShapeOptions& realism);

} // namespace fiberpli
