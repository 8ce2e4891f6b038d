/// Fnv1a: the one 64-bit FNV-1a hash of FiberPLI, for the checksums and fingerprints of the files
/// it writes (solver checkpoints, the .tck timestamp): fast, byte-order independent when fed
/// bytes, and the same on every machine, which is all a file check needs (not a cryptographic
/// hash).
#pragma once

#include <cstddef>
#include <cstdint>

namespace fiberpli
{

constexpr std::uint64_t kFnv1aOffset = 14695981039346656037ULL; ///< FNV's 64-bit offset basis
constexpr std::uint64_t kFnv1aPrime = 1099511628211ULL;         ///< FNV's 64-bit prime

/// Folds `n` bytes at `data` into `hash`, one byte at a time (xor, then multiply).
inline void fnv1aAdd(std::uint64_t& hash, const void* data, std::size_t n)
{
  const unsigned char* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < n; ++i)
  {
    hash = (hash ^ p[i]) * kFnv1aPrime;
  }
}

/// The hash of `n` bytes at `data`, started from `hash` (the offset basis unless given).
inline std::uint64_t fnv1a(const void* data, std::size_t n, std::uint64_t hash = kFnv1aOffset)
{
  fnv1aAdd(hash, data, n);
  return hash;
}

} // namespace fiberpli
