// ThreadComm: Comm with threads as ranks (in one process), for testing the parallel code (the
// distributed solver, the tile exchange) without MPI. runRanks(R, f) runs f(comm) on R threads and
// waits for all of them.
#pragma once

#include "Parallel/Comm.h"

#include <algorithm>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <thread>

namespace fiberpli_test
{

// What the ranks share: one slot per rank and a reusable barrier.
class ThreadBoard
{
public:
  explicit ThreadBoard(int ranks)
    : ranks_(ranks)
    , sums_(ranks)
    , maxima_(ranks)
    , mail_(ranks)
    , partners_(ranks)
  {
  }

  void barrier()
  {
    std::unique_lock<std::mutex> lock(mutex_);
    const long generation = generation_;
    if (++waiting_ == ranks_)
    {
      waiting_ = 0;
      ++generation_;
      cv_.notify_all();
      return;
    }
    cv_.wait(lock, [&] { return generation_ != generation; });
  }

  int ranks_;
  std::vector<std::vector<std::int64_t>> sums_;
  std::vector<std::vector<double>> maxima_;
  std::vector<std::vector<std::vector<char>>> mail_; // mail_[from][to]
  std::vector<std::vector<int>> partners_;           // of the last exchangeWith, per rank

private:
  std::mutex mutex_;
  std::condition_variable cv_;
  int waiting_ = 0;
  long generation_ = 0;
};

class ThreadComm final : public fiberpli::Comm
{
public:
  ThreadComm(ThreadBoard& board, int rank)
    : board_(board)
    , rank_(rank)
  {
  }
  int rank() const override { return rank_; }
  int size() const override { return board_.ranks_; }
  // Each operation: write my slot, barrier, read all slots, barrier (before anyone writes again).
  void sum(std::vector<std::int64_t>& v) override
  {
    board_.sums_[rank_] = v;
    board_.barrier();
    for (int r = 0; r < board_.ranks_; ++r)
      if (r != rank_)
        for (std::size_t i = 0; i < v.size(); ++i)
          v[i] += board_.sums_[r][i];
    board_.barrier();
  }
  void max(std::vector<double>& v) override
  {
    board_.maxima_[rank_] = v;
    board_.barrier();
    for (int r = 0; r < board_.ranks_; ++r)
      for (std::size_t i = 0; i < v.size(); ++i)
        v[i] = std::max(v[i], board_.maxima_[r][i]);
    board_.barrier();
  }
  std::vector<std::vector<char>> exchange(const std::vector<std::vector<char>>& send) override
  {
    board_.mail_[rank_] = send;
    board_.barrier();
    std::vector<std::vector<char>> received(board_.ranks_);
    for (int r = 0; r < board_.ranks_; ++r)
      received[r] = board_.mail_[r][rank_];
    board_.barrier();
    return received;
  }

  // As a neighbours-only transport: reads the mail of its partners only (what another rank sent
  // here is lost), and the partner lists must be symmetric and the mail to others empty (else
  // std::logic_error: a broken partner list would hang or lose data under MPI).
  std::vector<std::vector<char>> exchangeWith(
    const std::vector<int>& partners, const std::vector<std::vector<char>>& send) override
  {
    board_.mail_[rank_] = send;
    board_.partners_[rank_] = partners;
    board_.barrier();
    std::vector<std::vector<char>> received(board_.ranks_);
    bool symmetric = true;
    for (int r : partners)
    {
      const std::vector<int>& theirs = board_.partners_[r];
      symmetric = symmetric && std::binary_search(theirs.begin(), theirs.end(), rank_);
      received[r] = board_.mail_[r][rank_];
    }
    for (int r = 0; r < board_.ranks_; ++r)
      symmetric = symmetric &&
        (r == rank_ || send[r].empty() || std::binary_search(partners.begin(), partners.end(), r));
    board_.barrier();
    if (!symmetric)
      throw std::logic_error("exchangeWith: asymmetric partners or mail to a non-partner");
    return received;
  }

private:
  ThreadBoard& board_;
  int rank_;
};

// Runs f(comm) for every rank on its own thread.
inline void runRanks(int ranks, const std::function<void(fiberpli::Comm&)>& f)
{
  ThreadBoard board(ranks);
  std::vector<std::thread> threads;
  for (int r = 0; r < ranks; ++r)
  {
    threads.emplace_back(
      [&board, &f, r]
      {
        ThreadComm comm(board, r);
        f(comm);
      });
  }
  for (std::thread& t : threads)
    t.join();
}

} // namespace fiberpli_test
