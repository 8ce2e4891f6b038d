/// SolverSnapshots: the states of one solve kept to show its iterations as time steps
/// (FiberCollisionSolver's IterationsAsTime): the input at step 0, then every Δ-th step, at most
/// `capacity` states; when full, every second kept state is dropped and Δ doubles, so the kept
/// steps stay evenly spaced (0, Δ, 2Δ, …) over the whole run whatever its length. The final state
/// is added last and replaces a snapshot of its own step.
#pragma once

#include "Model/FiberModel.h"

#include <cstddef>
#include <vector>

namespace fiberpli
{

class SolverSnapshots
{
public:
  /// Starts over with the input as the state of step 0. interval >= 1, capacity >= 2.
  void start(const FiberModel& input, int interval, std::size_t capacity);
  /// The solver's step observer: keeps `current` when `step` is a multiple of Δ.
  void observe(int step, const FiberModel& current);
  /// Adds the solve's final state at `step` (without start(): the only state).
  void finish(FiberModel&& final, int step);
  /// The last state at or before time t (a step number); the first state when t is before it.
  /// Needs at least one state.
  std::size_t atTime(double t) const;
  /// Δ now (doubled at each thinning).
  int interval() const { return interval_; }

  std::vector<FiberModel> models; ///< kept states, oldest first
  std::vector<int> steps;         ///< the solver step of each of models

private:
  int interval_ = 1;
  std::size_t capacity_ = 0;
};

} // namespace fiberpli
