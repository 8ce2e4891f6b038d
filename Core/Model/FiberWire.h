/// FiberWire: the one byte record of a fiber for the exchanges between ranks. A fiber is its id,
/// bundle id and point count (64-bit integers), then per point x, y, z, radius and inner radius
/// (0 = none: a valid one is > 0), as doubles in the sender's byte order (all ranks of a job run
/// on one kind of machine; the codec is Util/ByteBuffer.h). The tile exchange (Parallel/
/// TileExchange) sends records that start with the fiber's position in the global fiber order
/// (writeFibers, readFibers); the distributed solver (Solver/Decomposition) puts its own per-fiber
/// state around the same fiber record (putFiber, getFiber).
#pragma once

#include "Model/FiberModel.h"
#include "Util/ByteBuffer.h"

#include <cstddef>
#include <utility>
#include <vector>

namespace fiberpli
{

/// Bytes of one fiber record with `points` points, with its global index (writeFibers).
constexpr std::size_t fiberWireBytes(std::size_t points)
{
  return 4 * sizeof(long long) + 5 * sizeof(double) * points;
}

/// Appends the fiber's record (without a global index). Inner radii travel when the fiber has one
/// per point; otherwise the record says none.
void putFiber(ByteWriter& w, const Fiber& fiber);

/// Reads what putFiber wrote.
Fiber getFiber(ByteReader& r);

/// Appends the fibers `which` of `model` to `out`; fiber f has global index offset + f.
void writeFibers(const FiberModel& model, const std::vector<std::size_t>& which, long long offset,
  std::vector<char>& out);

/// Appends every fiber record of `in` to `out` with its global index.
void readFibers(const std::vector<char>& in, std::vector<std::pair<long long, Fiber>>& out);

} // namespace fiberpli
