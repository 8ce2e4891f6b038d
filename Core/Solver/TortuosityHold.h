/// TortuosityHold: a solve whose result has the tortuosity asked, from above too (docs/solver.md
/// §5.5). Interwoven fibers of a dense crossing pass over and under each other; that weave comes on
/// top of the undulation they were made with (asked 1.25, solved 1.34–1.37), and taking it out
/// during the solve fights the packing (the fibers crumple). So the hold works on the input: it
/// solves, measures each bundle's mean solved tortuosity, and while a bundle is off its target by
/// more than the tolerance it solves again from the input with that bundle's undulation scaled
/// down (or up) by the excess measured, a secant step per solve: the fibers start from shapes
/// that leave room for their weave.
#pragma once

#include "Model/FiberModel.h"
#include "Solver/CollisionSolver.h"

namespace fiberpli
{

/// Scales the fiber's deviation from its axis (TortuosityControl.h, fiberDeviation) by one factor
/// k >= 0 so that its tortuosity becomes `target` (to 1e-9 relative; k = 0, its projection on the
/// axis, when even that is longer): the ends of an open fiber stay, a closed fiber stays closed
/// exactly. A fiber of fewer than 3 points, without a chord or with tortuosity <= 1 is left.
/// Returns the factor applied (1 when left).
double scaleUndulation(Fiber& f, double target, const Vec3* closure = nullptr);

/// Bundles farther off their target than this after the solve are solved again (a fraction of
/// the excess τ* − 1: half the tolerance the realism targets allow).
constexpr double kTortuosityHoldTolerance = 0.05;
/// At most this many solves in all.
constexpr int kTortuosityHoldSolves = 4;

/// solveCollisions (same contract: model in place, comm collective, same bits for any rank and
/// thread count) holding every bundle's mean tortuosity at options.tortuosity (> 1; holdTortuosity
/// set): after a solve each bundle's mean over its undulating fibers (input tortuosity > 1) is
/// measured, summed exactly over the ranks; while one is off by more than kTortuosityHoldTolerance
/// of the excess, the run starts again from the input with that bundle's fibers scaled
/// (scaleUndulation) to an input tortuosity moved by a secant step on (input, solved), the
/// solver's tortuosity rule holding each fiber at least at its own input tortuosity, up to
/// kTortuosityHoldSolves solves. Progress is shared between the solves; result.tortuositySolves
/// counts them; a bundle still off after the last gets a warning naming it and its mean. Bundles
/// are told apart when their ids span at most 1024 values, else all count as one.
CollisionSolverResult solveHoldingTortuosity(FiberModel& model,
  const CollisionSolverOptions& options, const ProgressFn& progress = {}, Comm* comm = nullptr);

} // namespace fiberpli
