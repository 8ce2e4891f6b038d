/// Comm: what FiberPLI's parallel code needs from its ranks: exact reductions, an all-to-all of
/// byte buffers and its form among partners (neighbours only). The distributed collision solver
/// (docs/solver.md §13), its checkpoints and the tile exchange (Parallel/TileExchange.h) run over
/// it; the rank collectives they share are in Parallel/Collectives.h. Pure C++; the VTK build
/// implements it over vtkMultiProcessController (Conversion/FiberSolverComm.h), the tests with
/// threads as ranks (Core/Testing/ThreadComm.h). Every call is collective: all ranks make the same
/// calls in the same order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fiberpli
{

class Comm
{
public:
  virtual ~Comm() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Element-wise sum over all ranks, in place (integers: exact, the same on every rank).
  virtual void sum(std::vector<std::int64_t>& values) = 0;
  /// Element-wise maximum over all ranks, in place (exact; a minimum is the maximum of −x).
  virtual void max(std::vector<double>& values) = 0;
  /// send[r] (size() buffers) goes to rank r; returns what every rank sent to this one, by rank.
  virtual std::vector<std::vector<char>> exchange(const std::vector<std::vector<char>>& send) = 0;
  /// exchange among partners only: send[r] is empty for every rank r not in `partners`
  /// (ascending, without this rank), nothing comes from them, and the relation is symmetric (r
  /// lists this rank when this rank lists r), so a transport needs no all-to-all of sizes. The
  /// default is exchange().
  virtual std::vector<std::vector<char>> exchangeWith(
    const std::vector<int>& partners, const std::vector<std::vector<char>>& send)
  {
    (void)partners;
    return exchange(send);
  }
  /// exchangeWith into `received` (size() buffers afterwards), keeping the buffers' capacity: a
  /// caller that passes the same buffers at every step gets no new memory from the allocator
  /// once they are large enough. Messages of megabytes are freshly mapped pages otherwise, each
  /// page a fault on first touch, and returned to the system when freed. The default copies
  /// exchangeWith's result into them.
  virtual void exchangeWithInto(const std::vector<int>& partners,
    const std::vector<std::vector<char>>& send, std::vector<std::vector<char>>& received)
  {
    const std::vector<std::vector<char>> in = exchangeWith(partners, send);
    received.resize(in.size());
    for (std::size_t q = 0; q < in.size(); ++q)
    {
      received[q].assign(in[q].begin(), in[q].end());
    }
  }
};

/// One rank: the reductions return their input, exchange returns send.
class SerialComm final : public Comm
{
public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  void sum(std::vector<std::int64_t>&) override {}
  void max(std::vector<double>&) override {}
  std::vector<std::vector<char>> exchange(const std::vector<std::vector<char>>& send) override
  {
    return send;
  }
};

} // namespace fiberpli
