#include "FiberSolverComm.h"

#include <vtkCommunicator.h>
#include <vtkMPI.h>
#include <vtkMPICommunicator.h>
#include <vtkMultiProcessController.h>

#include <algorithm>

namespace fiberpli
{

namespace
{
// The point-to-point messages of the solver and of FiberTileExchange (vtkMultiProcessController
// reserves 1–4, vtkCommunicator 10–16).
constexpr int kExchangeTag = 48151;
constexpr int kSizeTag = 48152; // the sizes, without MPI or among partners
// vtkMPICommunicator's non-blocking calls take an int count: longer buffers go as several
// messages, which MPI delivers in the order they were sent (same sender, tag and communicator).
constexpr std::size_t kChunk = std::size_t(1) << 30;

std::size_t Chunks(std::size_t bytes)
{
  return (bytes + kChunk - 1) / kChunk;
}

/// MPI: the sizes by MPI_Alltoall (each rank learns the R sizes addressed to it, O(R) memory), or
/// among `partners` only (non-null: a symmetric list) by non-blocking sends and receives of the
/// sizes to and from them, then every non-empty receive and send posted at once and one wait on
/// all, so no rank waits for a pair it is not part of.
void ExchangeMPI(vtkMPICommunicator& mpi, const std::vector<std::vector<char>>& send,
  std::vector<std::vector<char>>& received, const std::vector<int>* partners = nullptr)
{
  const int n = mpi.GetNumberOfProcesses();
  const int me = mpi.GetLocalProcessId();
  std::vector<long long> out(static_cast<std::size_t>(n)), in(static_cast<std::size_t>(n), 0);
  for (int q = 0; q < n; ++q)
  {
    out[static_cast<std::size_t>(q)] =
      static_cast<long long>(send[static_cast<std::size_t>(q)].size());
  }
  if (partners)
  {
    // Each size as 8 bytes (the non-blocking calls take chars).
    std::vector<vtkMPICommunicator::Request> sizes(2 * partners->size());
    std::size_t k = 0;
    for (int q : *partners)
      mpi.NoBlockReceive(reinterpret_cast<char*>(&in[static_cast<std::size_t>(q)]),
        static_cast<int>(sizeof(long long)), q, kSizeTag, sizes[k++]);
    for (int q : *partners)
      mpi.NoBlockSend(reinterpret_cast<const char*>(&out[static_cast<std::size_t>(q)]),
        static_cast<int>(sizeof(long long)), q, kSizeTag, sizes[k++]);
    if (k > 0)
    {
      mpi.WaitAll(static_cast<int>(k), sizes.data());
    }
  }
  else
  {
    MPI_Alltoall(
      out.data(), 1, MPI_LONG_LONG, in.data(), 1, MPI_LONG_LONG, *mpi.GetMPIComm()->GetHandle());
  }
  std::size_t count = 0;
  for (int q = 0; q < n; ++q)
  {
    if (q != me)
    {
      received[static_cast<std::size_t>(q)].resize(
        static_cast<std::size_t>(in[static_cast<std::size_t>(q)]));
      count += Chunks(received[static_cast<std::size_t>(q)].size()) +
        Chunks(send[static_cast<std::size_t>(q)].size());
    }
  }
  std::vector<vtkMPICommunicator::Request> requests(count);
  std::size_t next = 0;
  // Receives first, so that most messages find their buffer already posted.
  for (int q = 0; q < n; ++q)
  {
    std::vector<char>& b = received[static_cast<std::size_t>(q)];
    for (std::size_t at = 0; q != me && at < b.size(); at += kChunk)
    {
      const int length = static_cast<int>(std::min(kChunk, b.size() - at));
      mpi.NoBlockReceive(b.data() + at, length, q, kExchangeTag, requests[next++]);
    }
  }
  for (int q = 0; q < n; ++q)
  {
    const std::vector<char>& b = send[static_cast<std::size_t>(q)];
    for (std::size_t at = 0; q != me && at < b.size(); at += kChunk)
    {
      const int length = static_cast<int>(std::min(kChunk, b.size() - at));
      mpi.NoBlockSend(b.data() + at, length, q, kExchangeTag, requests[next++]);
    }
  }
  if (count > 0)
  {
    mpi.WaitAll(static_cast<int>(count), requests.data());
  }
}

/// Another controller with several processes (no non-blocking calls): every pair of ranks
/// (i < j) in one global order, i sends then receives, j receives then sends, each message
/// preceded by its size. Deadlock-free with blocking sends (the first unfinished pair has both
/// ranks at it), O(R) memory, but a chain of waits.
void ExchangePairwise(vtkMultiProcessController& c, const std::vector<std::vector<char>>& send,
  std::vector<std::vector<char>>& received)
{
  const int n = c.GetNumberOfProcesses();
  const int me = c.GetLocalProcessId();
  const auto sendTo = [&](int q)
  {
    const std::vector<char>& b = send[static_cast<std::size_t>(q)];
    long long size = static_cast<long long>(b.size());
    c.Send(&size, 1, q, kSizeTag);
    if (size > 0)
    {
      c.Send(b.data(), static_cast<vtkIdType>(b.size()), q, kExchangeTag);
    }
  };
  const auto receiveFrom = [&](int q)
  {
    long long size = 0;
    c.Receive(&size, 1, q, kSizeTag);
    std::vector<char>& b = received[static_cast<std::size_t>(q)];
    b.resize(static_cast<std::size_t>(size));
    if (size > 0)
    {
      c.Receive(b.data(), static_cast<vtkIdType>(b.size()), q, kExchangeTag);
    }
  };
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
}
} // namespace

FiberSolverComm::FiberSolverComm(vtkMultiProcessController* controller)
  : Controller(controller)
{
}

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
  this->Controller->AllReduce(
    in.data(), out.data(), static_cast<vtkIdType>(in.size()), vtkCommunicator::SUM_OP);
  values.assign(out.begin(), out.end());
}

void FiberSolverComm::max(std::vector<double>& values)
{
  std::vector<double> out(values.size());
  this->Controller->AllReduce(
    values.data(), out.data(), static_cast<vtkIdType>(values.size()), vtkCommunicator::MAX_OP);
  values = out;
}

std::vector<std::vector<char>> FiberSolverComm::exchange(const std::vector<std::vector<char>>& send)
{
  if (this->size() == 1) // vtkDummyController, or MPI on one rank
  {
    return send;
  }
  std::vector<std::vector<char>> received(send.size());
  received[static_cast<std::size_t>(this->rank())] = send[static_cast<std::size_t>(this->rank())];
  if (auto* mpi = vtkMPICommunicator::SafeDownCast(this->Controller->GetCommunicator()))
  {
    ExchangeMPI(*mpi, send, received);
  }
  else
  {
    ExchangePairwise(*this->Controller, send, received);
  }
  return received;
}

std::vector<std::vector<char>> FiberSolverComm::exchangeWith(
  const std::vector<int>& partners, const std::vector<std::vector<char>>& send)
{
  std::vector<std::vector<char>> received;
  this->exchangeWithInto(partners, send, received);
  return received;
}

void FiberSolverComm::exchangeWithInto(const std::vector<int>& partners,
  const std::vector<std::vector<char>>& send, std::vector<std::vector<char>>& received)
{
  auto* mpi = vtkMPICommunicator::SafeDownCast(this->Controller->GetCommunicator());
  if (this->size() == 1 || !mpi)
  {
    received = this->exchange(send);
    return;
  }
  // ExchangeMPI sizes every other rank's buffer to what it sent here (resize keeps capacity).
  received.resize(send.size());
  const auto me = static_cast<std::size_t>(this->rank());
  received[me].assign(send[me].begin(), send[me].end());
  ExchangeMPI(*mpi, send, received, &partners);
}

std::vector<long long> FiberSolverComm::allToAll(const std::vector<long long>& send, int per)
{
  std::vector<long long> received(send.size());
  if (auto* mpi = vtkMPICommunicator::SafeDownCast(this->Controller->GetCommunicator()))
  {
    MPI_Alltoall(send.data(), per, MPI_LONG_LONG, received.data(), per, MPI_LONG_LONG,
      *mpi->GetMPIComm()->GetHandle());
    return received;
  }
  // Without MPI: the same through exchange().
  const std::size_t n = static_cast<std::size_t>(this->size()),
                    bytes = sizeof(long long) * static_cast<std::size_t>(per);
  std::vector<std::vector<char>> out(n);
  for (std::size_t q = 0; q < n; ++q)
  {
    out[q].resize(bytes);
    std::copy_n(reinterpret_cast<const char*>(send.data() + q * per), bytes, out[q].data());
  }
  const std::vector<std::vector<char>> in = this->exchange(out);
  for (std::size_t q = 0; q < n; ++q)
  {
    std::copy_n(in[q].data(), bytes, reinterpret_cast<char*>(received.data() + q * per));
  }
  return received;
}

} // namespace fiberpli
