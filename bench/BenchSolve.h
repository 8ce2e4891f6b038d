// Shared helpers of the benchmark drivers that solve on the Core: a model's hash, and a solve
// stepped to its end with a line of timings every N steps.
#pragma once

#include "BenchUtil.h"
#include "Solver/CollisionSolver.h"
#include "Util/Fnv1a.h"

#include <cstdint>

namespace fiberpli::bench
{

/// Adds every fiber's points and radii to the FNV-1a hash h: the same model bit for bit, the
/// same hash (pieces added in rank order hash as the whole model).
inline void addToHash(std::uint64_t& h, const FiberModel& model)
{
  for (const Fiber& f : model.fibers)
  {
    fnv1aAdd(h, f.points.data(), f.points.size() * sizeof(Vec3));
    fnv1aAdd(h, f.radii.data(), f.radii.size() * sizeof(double));
  }
}

inline unsigned long long modelHash(const FiberModel& model)
{
  std::uint64_t h = kFnv1aOffset;
  addToHash(h, model);
  return static_cast<unsigned long long>(h);
}

/// Starts `run` and steps it until it ends; after every `every`-th step (0 = never) calls
/// line(step, wall seconds since the start, wall and CPU seconds per step since the last line).
template <class Line>
void stepWithTimings(CollisionSolverRun& run, int every, Line&& line)
{
  const double t0 = seconds();
  double tl = t0, cl = cpuSeconds();
  if (!run.start())
  {
    return;
  }
  while (run.step())
  {
    const int s = run.state().steps;
    if (every > 0 && s % every == 0)
    {
      const double t = seconds(), c = cpuSeconds();
      line(s, t - t0, (t - tl) / every, (c - cl) / every);
      tl = t;
      cl = c;
    }
  }
}

} // namespace fiberpli::bench
