/**
 * @class   FiberSolverComm
 * @brief   the Core's communicator (Core/Parallel/Comm.h) over a vtkMultiProcessController
 *
 * The one place FiberPLI's reductions and exchanges between ranks reach the controller: the
 * distributed collision solver, the tile exchange (FiberTileExchange) and the error agreement,
 * largest values and periodic-cell comparison of FiberCollective all go through it.
 * Reductions are the controller's AllReduce (long long sums, double maxima: exact, the same on
 * every rank). The all-to-all under MPI: MPI_Alltoall of the sizes (a rank learns only the R sizes
 * addressed to it), then non-blocking receives and sends of the non-empty buffers and one wait on
 * all (no R x R size matrix, no serial chain of rank pairs); among partners only (exchangeWith)
 * the sizes go to and come from the partners alone. Other multi-process controllers fall back to
 * blocking pairwise sends in one global order; one rank returns its input.
 * docs/solver.md §13.
 */
#ifndef FiberSolverComm_h
#define FiberSolverComm_h

#include "FiberPLIConversionModule.h" // for export macro
#include "Parallel/Comm.h"

class vtkMultiProcessController;

namespace fiberpli
{

class FIBERPLICONVERSION_EXPORT FiberSolverComm final : public Comm
{
public:
  explicit FiberSolverComm(vtkMultiProcessController* controller);
  int rank() const override;
  int size() const override;
  void sum(std::vector<std::int64_t>& values) override;
  void max(std::vector<double>& values) override;
  std::vector<std::vector<char>> exchange(const std::vector<std::vector<char>>& send) override;
  /// Under MPI: the sizes to and from the partners only (non-blocking, one wait), then the
  /// non-empty buffers as in exchange; no all-to-all. Other controllers: exchange().
  std::vector<std::vector<char>> exchangeWith(
    const std::vector<int>& partners, const std::vector<std::vector<char>>& send) override;
  /// exchangeWith into the caller's buffers, their capacity kept (Comm::exchangeWithInto).
  void exchangeWithInto(const std::vector<int>& partners,
    const std::vector<std::vector<char>>& send, std::vector<std::vector<char>>& received) override;
  /// send holds `per` numbers for each rank in rank order; returns the `per` numbers every rank
  /// addressed to this one, in rank order (MPI_Alltoall under MPI; collective).
  std::vector<long long> allToAll(const std::vector<long long>& send, int per);

private:
  vtkMultiProcessController* Controller;
};

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberSolverComm.h
