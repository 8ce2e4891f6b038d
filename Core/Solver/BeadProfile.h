/// BeadProfile: the solver's rule that keeps a beaded fiber's beads (docs/solver.md §5.4). A
/// point carries its radius; pushes slide points along a fiber, and the thick points of a bead
/// pressed by a neighbour end up closer together, so the bead shrinks into shorter links and the
/// fiber loses volume. With this rule the radius of a closed fiber is a function of arc length
/// instead: every point takes the fiber's input profile at its arc fraction plus one phase per
/// fiber, the circular mean of how far the points slid. The profile keeps its shape in arc length
/// and moves along the fiber as a whole when its points slide, so beads of neighbours can pass
/// each other. Sequential inside one fiber, independent between fibers.
#pragma once

#include "Model/FiberModel.h"
#include "Solver/ShapeControl.h"

#include <vector>

namespace fiberpli
{

/// The input profile (radii by input point index, the last repeating the first) at the index s
/// taken modulo the period (profile.size() − 1), linear between input points; profile must have
/// at least 2 entries.
double periodicProfileRadius(const std::vector<double>& profile, double s);

/// For a closed fiber (its last point is its first shifted by the closure) whose input profile
/// (state.inputRadii) is not constant: sets every point's source index to
/// wrap(a_i + φ) in [0, P), P = inputRadii.size() − 1, a_i = P × (arc length to point i) / (fiber
/// length), φ the circular mean over the points (the last one, which repeats the first, left out)
/// of source_i − a_i modulo P; and its radius to periodicProfileRadius at that index. A radius
/// moves only when it changes by more than 1e-9 of itself, so an unmoved fiber is left exactly as
/// it is. Returns true when a radius changed. Open fibers, constant profiles and fibers of fewer
/// than 3 points are left unchanged.
bool followBeadProfile(Fiber& f, FiberPointState& state);

} // namespace fiberpli
