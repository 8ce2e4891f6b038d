/**
 * @class   FiberSolverComm
 * @brief   the distributed collision solver's communicator (Core/Solver/SolverComm.h) over a
 *          vtkMultiProcessController
 *
 * Reductions are the controller's AllReduce (long long sums, double maxima: exact, the same on
 * every rank); the all-to-all first all-gathers the buffer sizes, then every pair of ranks (i < j)
 * exchanges in one global order (i sends then receives, j receives then sends), which cannot
 * deadlock with blocking sends: the first unfinished pair in that order always has both ranks at it.
 * docs/solver.md §13.
 */
#ifndef FiberSolverComm_h
#define FiberSolverComm_h

#include "FiberPLIConversionModule.h" // for export macro
#include "Solver/SolverComm.h"

class vtkMultiProcessController;

namespace fiberpli
{

class FIBERPLICONVERSION_EXPORT FiberSolverComm final : public SolverComm
{
public:
  explicit FiberSolverComm(vtkMultiProcessController* controller);
  int rank() const override;
  int size() const override;
  void sum(std::vector<std::int64_t>& values) override;
  void max(std::vector<double>& values) override;
  std::vector<std::vector<char>> exchange(const std::vector<std::vector<char>>& send) override;

private:
  vtkMultiProcessController* Controller;
};

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberSolverComm.h
