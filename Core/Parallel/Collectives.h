/// Collectives: the reductions FiberPLI's parallel code builds on its ranks' Comm
/// (Parallel/Comm.h): the one rule by which ranks agree on a failure (docs/data-contract.md §5),
/// logical or, exact minimum and maximum, a sum with the same bits on every rank, and the k-th
/// value of all ranks' values. Every function is collective: all ranks call it in the same order.
#pragma once

#include "Parallel/Comm.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

/// What the ranks agree on when some failed (the one rule, docs/data-contract.md §5): which rank's
/// message wins (the lowest failing rank) and whether every rank failed. The same on every rank.
struct RankFailure
{
  int rank = -1;       ///< the lowest failing rank; -1: no rank failed
  std::string message; ///< that rank's error
  bool all = false;    ///< every rank failed
  bool failed() const { return rank >= 0; }
};
/// Every rank passes its own error ("" = success). Collective.
RankFailure agreeOnFailure(Comm& comm, const std::string& localError);

/// The solver's text of agreeOnFailure, on every rank: "" when no rank failed, else the winning
/// message as it is when every rank failed, else as "rank R: <message>" (so that the other ranks'
/// reports name the rank whose piece failed). Collective.
std::string agreeOnError(Comm& comm, const std::string& localError);
/// Logical or / exact minimum and maximum over all ranks. Collective.
bool anyRank(Comm& comm, bool value);
double minOverRanks(Comm& comm, double value);
double maxOverRanks(Comm& comm, double value);

/// Deterministic sum of non-negative terms: the same bits on every rank, independent of the terms'
/// order and of how they are split over ranks. Each term is rounded to a multiple of 2^-32 (terms
/// below 2^64) and the multiples are summed exactly as integers; only the final conversion of that
/// integer to a double rounds (up to three roundings of its 32-bit digits, so within a few ulp of
/// the exact sum of the rounded terms, not necessarily the nearest double).
class ExactSum
{
public:
  void add(double term);
  /// Collective: the sum over all ranks (same bits on every rank); comm null = this rank only.
  double total(Comm* comm) const;

private:
  std::uint64_t limbs_[3] = { 0, 0, 0 }; // the fixed-point sum in 32-bit digits (with carries)
};

/// Value of rank k (0-based, ascending) of all ranks' values (as std::nth_element on the union),
/// exactly, by bisection on the bit patterns of non-negative doubles; 0 when there are none.
/// Collective (64 integer sums).
double globalNthValue(const std::vector<double>& local, std::int64_t k, Comm& comm);

} // namespace fiberpli
