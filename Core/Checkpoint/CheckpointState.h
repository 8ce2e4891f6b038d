/// CheckpointState: whether a solver state read from a checkpoint can be resumed (docs/solver.md
/// §14). A checkpoint's checksum only says that the file is as it was written; an edited file
/// with a recomputed checksum, or a state written by a faulty run, must not be trusted further
/// than fresh input is. So a resumed model passes the checks of fresh input, and every scalar of
/// the state must be one a run with these options can reach.
#pragma once

#include "Model/FiberModel.h"
#include "Solver/CollisionSolver.h"

#include <string>

namespace fiberpli
{

/// "" when `state` with `model` (this rank's piece; `ranks` = the ranks of the run, 1 when
/// serial) is a state a run with `options` can have reached, else what is not, naming the field
/// and the value ("the saved radius scale is nan, must be in [0.5, 1]"). A model that breaks the
/// data contract gives "" here: CollisionSolverRun::resume refuses it as it refuses fresh input.
/// Checks: coordinates the solver can resolve (Solver/ShapeControl.h), the
/// per-fiber sizes and flags (an active fiber has two distinct points, an inactive one has not;
/// a closed fiber's closure is the lattice vector from its first to its last point), finite
/// velocities and source indices, home ranks in range, and the scalars: step counters in
/// [0, MaxSteps], radius scale in [initial scale, 1], segment length as the options give it,
/// move cap and push scale within what the options and the radii allow, progress in [0, 1].
std::string checkResumedState(const FiberModel& model, const CollisionSolverState& state,
  const CollisionSolverOptions& options, int ranks);

} // namespace fiberpli
