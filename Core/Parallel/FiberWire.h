/// FiberWire: fibers as byte records for the exchanges between ranks, with their position in the
/// global fiber order, so that a rank can put what it receives back into model order. Per fiber:
/// global index, id, bundle id and point count (64-bit integers), then per point x, y, z, radius
/// and inner radius (0 = none: a valid one is > 0), as doubles in the sender's byte order (all
/// ranks of a job run on one kind of machine).
#pragma once

#include "Model/FiberModel.h"

#include <cstddef>
#include <utility>
#include <vector>

namespace fiberpli
{

/// Bytes of one fiber record with `points` points.
constexpr std::size_t fiberWireBytes(std::size_t points)
{
  return 4 * sizeof(long long) + 5 * sizeof(double) * points;
}

/// Appends the fibers `which` of `model` to `out`; fiber f has global index offset + f.
void writeFibers(const FiberModel& model, const std::vector<std::size_t>& which, long long offset,
  std::vector<char>& out);

/// Appends every fiber record of `in` to `out` with its global index.
void readFibers(const std::vector<char>& in, std::vector<std::pair<long long, Fiber>>& out);

} // namespace fiberpli
