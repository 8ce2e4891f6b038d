/// CollisionSolverState: what a collision solve hands from one step to the next besides the model
/// (docs/solver.md §6.1); with the model, a complete checkpoint. Its own header so that the
/// distribution (Solver/Decomposition.h) and the checkpoints can hold it without the solver.
#pragma once

#include "Geometry/Vec3.h"
#include "Solver/ShapeControl.h"

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

/// Everything a run hands from one step to the next besides the model (docs/solver.md §6.1):
/// the model and this state are a complete checkpoint (resume them with the same options and
/// the run goes on bit for bit as if uninterrupted). Per-fiber vectors are in model order.
struct CollisionSolverState
{
  // Per fiber.
  std::vector<FiberPointState> points; ///< velocity and source index of every point
  std::vector<char> active;            ///< >= 2 distinct points: solved (else copied through)
  std::vector<char> closed;            ///< [ours] closed through the periodic cell ...
  std::vector<Vec3> closure;        ///< ... by this lattice vector (last point = first + closure)
  std::vector<std::int64_t> global; ///< index in the whole model (distributed runs; else 0, 1, …)
  std::vector<int> home;            ///< rank whose input piece held it (distributed runs; else 0)
  // Fixed when the run starts.
  double segmentLength = -1.0; ///< L̄ in use (µm, < 0 = no split/merge)
  double vMax = 0.0;           ///< largest move of a point per step (µm)
  double growthTolerance =
    0.0;                  ///< radius growth: deepest overlap (µm at full size) that lets it grow
  double pushScale = 1.0; ///< push multiplier set at the first detection (PushBoost)
  // Changed by the steps.
  int steps = 0;            ///< move steps done
  double scale = 1.0;       ///< capsule radii relative to the fibers' radii (radius growth)
  int sinceGrowth = 0;      ///< move steps since the last growth
  int sinceImprovement = 0; ///< detections since the best collision count last fell
  bool first = true;        ///< the next detection sets the best count unconditionally
  bool warnedStall = false; ///< the 1000-steps-without-progress warning was given
  std::size_t firstCount = static_cast<std::size_t>(-1); ///< collisions at the first detection
  std::size_t bestCollisions = 0;                        ///< smallest collision count seen ...
  int bestStep = 0;                                      ///< ... and its step
  bool changed = false;                                  ///< the last shape control changed a fiber
  double done = 0.0;                                     ///< progress estimate ...
  double reported = 0.0;             ///< ... and what the callback last saw (never goes back)
  std::vector<std::string> warnings; ///< so far
};

} // namespace fiberpli
