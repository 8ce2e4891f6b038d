/// FiberPieces: which fibers of a generated model piece p of P holds (docs/tissue-models.md §9).
/// Pieces are contiguous ranges of the global fiber order, so that the pieces put one after the
/// other in piece order are the whole model in its serial order, for any piece count.
#pragma once

#include <cstddef>

namespace fiberpli
{

/// Global fiber indices [begin, end).
struct FiberRange
{
  std::size_t begin = 0;
  std::size_t end = 0;

  std::size_t size() const { return end - begin; }
};

/// Piece `piece` of `pieces` of `total` fibers: [⌊total·p/P⌋, ⌊total·(p+1)/P⌋), so sizes differ by
/// at most one. pieces < 1 counts as 1; a piece outside [0, pieces) is empty.
inline FiberRange pieceRange(std::size_t total, int piece, int pieces)
{
  if (pieces < 1)
  {
    pieces = 1;
  }
  if (piece < 0 || piece >= pieces)
  {
    return FiberRange{ total, total };
  }
  // total·p/P without overflow for any realistic total (< 2^64 / 2^31).
  const auto cut = [&](int p)
  {
    return static_cast<std::size_t>(
      (static_cast<unsigned long long>(total) * static_cast<unsigned long long>(p)) /
      static_cast<unsigned long long>(pieces));
  };
  return FiberRange{ cut(piece), cut(piece + 1) };
}

} // namespace fiberpli
