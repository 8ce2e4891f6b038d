#include "FiberSolverComm.h"

#include <vtkCommunicator.h>
#include <vtkMultiProcessController.h>

namespace fiberpli
{

namespace
{
constexpr int kExchangeTag = 48151; // the solver's point-to-point messages
}

FiberSolverComm::FiberSolverComm(vtkMultiProcessController* controller) : Controller(controller) {}

int FiberSolverComm::rank() const
{
  return this->Controller->GetLocalProcessId();
}

int FiberSolverComm::size() const
{
  return this->Controller->GetNumberOfProcesses();
}

void FiberSolverComm::sum(std::vector<std::int64_t>& values)
{
  std::vector<long long> in(values.begin(), values.end()), out(values.size());
  this->Controller->AllReduce(in.data(), out.data(), static_cast<vtkIdType>(in.size()), vtkCommunicator::SUM_OP);
  values.assign(out.begin(), out.end());
}

void FiberSolverComm::max(std::vector<double>& values)
{
  std::vector<double> out(values.size());
  this->Controller->AllReduce(values.data(), out.data(), static_cast<vtkIdType>(values.size()), vtkCommunicator::MAX_OP);
  values = out;
}

std::vector<std::vector<char>> FiberSolverComm::exchange(const std::vector<std::vector<char>>& send)
{
  const int n = this->size();
  const int me = this->rank();
  // sizes[r * n + q]: bytes rank r sends to rank q.
  std::vector<long long> mine(static_cast<std::size_t>(n)), sizes(static_cast<std::size_t>(n) * n);
  for (int q = 0; q < n; ++q)
  {
    mine[static_cast<std::size_t>(q)] = static_cast<long long>(send[static_cast<std::size_t>(q)].size());
  }
  this->Controller->AllGather(mine.data(), sizes.data(), n);
  std::vector<std::vector<char>> received(static_cast<std::size_t>(n));
  received[static_cast<std::size_t>(me)] = send[static_cast<std::size_t>(me)];
  const auto sendTo = [&](int q) {
    const std::vector<char>& b = send[static_cast<std::size_t>(q)];
    if (!b.empty())
    {
      this->Controller->Send(b.data(), static_cast<vtkIdType>(b.size()), q, kExchangeTag);
    }
  };
  const auto receiveFrom = [&](int q) {
    std::vector<char>& b = received[static_cast<std::size_t>(q)];
    b.resize(static_cast<std::size_t>(sizes[static_cast<std::size_t>(q) * n + me]));
    if (!b.empty())
    {
      this->Controller->Receive(b.data(), static_cast<vtkIdType>(b.size()), q, kExchangeTag);
    }
  };
  // The pairs (i, j), i < j, in lexicographic order; each rank takes part in those with it.
  for (int i = 0; i < n; ++i)
  {
    for (int j = i + 1; j < n; ++j)
    {
      if (me == i)
      {
        sendTo(j);
        receiveFrom(j);
      }
      else if (me == j)
      {
        receiveFrom(i);
        sendTo(i);
      }
    }
  }
  return received;
}

} // namespace fiberpli
