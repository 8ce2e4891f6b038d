/// SolverLinks: the flat capsule-link array the collision solver and its counts work on
/// (docs/solver.md §1), the median radius and the capsule volume of a model, and the memory a
/// point and a pair of a solve take.
#pragma once

#include "Index/CollisionGrid.h"
#include "Model/FiberModel.h"
#include "Parallel/Comm.h"

#include <cstddef>
#include <vector>

namespace fiberpli
{

/// The links buildLinks makes of fiber f of `model`: one fewer than its points when it has two or
/// more and is active (active optional), else none.
inline std::size_t linksOf(const FiberModel& model, const std::vector<char>* active, std::size_t f)
{
  const std::size_t n = model.fibers[f].points.size();
  return n >= 2 && !(active && !(*active)[f]) ? n - 1 : 0;
}

/// Flat link array of all fibers with >= 2 points; the index is the global link id (§1).
/// active (optional): only these fibers; pointOffset (optional): each fiber's first point in a
/// flat point array; closed (optional): fibers closed through a periodic cell; scale: capsule
/// radii × scale (growth); fiberRuns (optional): the first link of each fiber that has links (+ the
/// total), so that no pass over the links has to find where one fiber's links end.
void buildLinks(const FiberModel& model, const std::vector<char>* active, int threads,
  std::vector<CapsuleLink>& links, std::vector<std::size_t>* pointOffset,
  const std::vector<char>* closed = nullptr, double scale = 1.0,
  std::vector<std::size_t>* fiberRuns = nullptr);

/// Each fiber's first point in a flat point array of all fibers (+ the total): the slots of the
/// solver's per-point forces.
void pointOffsets(const FiberModel& model, std::vector<std::size_t>& offsets);

/// Median point radius of the fibers with >= 2 points; distributed (comm): of all ranks' fibers,
/// exactly the same value.
double medianRadius(const FiberModel& model, Comm* comm = nullptr);

/// Σ π ρ² · link length over all links (ρ = capsule radius), summed exactly: the same bits for
/// any order and split of the fibers; comm: over all ranks' fibers (collective).
double capsuleVolume(const FiberModel& model, Comm* comm = nullptr);

/// Bytes the solver keeps per point (model point and radius, velocity, source index, force, its
/// link and the grid's buffers; links ≈ points) and per colliding pair (the pair and its push).
double bytesPerPoint();
double bytesPerPair();

} // namespace fiberpli
