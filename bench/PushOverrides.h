// The solver benchmarks' push-schedule flags (--overlap-push, --separation-speed,
// --max-displacement, --drag, --push-boost): a value given on the command line replaces the
// solver's default, an absent one (the sentinel) keeps it.
#pragma once

#include "Solver/CollisionSolver.h"

namespace fiberpli::bench
{

struct PushOverrides
{
  double overlapPush = -1.0;     // used when >= 0
  double separationSpeed = -1.0; // used when > 0
  double maxDisplacement = -1.0; // used when > 0
  double drag = -1.0;            // used when >= 0
  double pushBoost = -1.0;       // used when >= 1

  void apply(CollisionSolverOptions& o) const
  {
    if (overlapPush >= 0.0)
      o.overlapPush = overlapPush;
    if (separationSpeed > 0.0)
      o.separationSpeed = separationSpeed;
    if (maxDisplacement > 0.0)
      o.maxDisplacement = maxDisplacement;
    if (drag >= 0.0)
      o.drag = drag;
    if (pushBoost >= 1.0)
      o.pushBoost = pushBoost;
  }
};

} // namespace fiberpli::bench
