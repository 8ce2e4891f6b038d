#include "Parallel/Collectives.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace fiberpli
{

RankFailure agreeOnFailure(Comm& comm, const std::string& localError)
{
  std::vector<std::int64_t> failed(static_cast<std::size_t>(comm.size()), 0);
  failed[static_cast<std::size_t>(comm.rank())] = localError.empty() ? 0 : 1;
  comm.sum(failed);
  const auto first = std::find(failed.begin(), failed.end(), 1);
  RankFailure agreed;
  if (first == failed.end())
  {
    return agreed;
  }
  const std::size_t who = static_cast<std::size_t>(first - failed.begin());
  std::vector<std::vector<char>> out(static_cast<std::size_t>(comm.size()));
  if (who == static_cast<std::size_t>(comm.rank()))
  {
    for (std::vector<char>& b : out)
      b.assign(localError.begin(), localError.end());
  }
  const std::vector<std::vector<char>> in = comm.exchange(out);
  agreed.rank = static_cast<int>(who);
  agreed.message.assign(in[who].begin(), in[who].end());
  agreed.all =
    std::count(failed.begin(), failed.end(), 1) == static_cast<std::ptrdiff_t>(failed.size());
  return agreed;
}

std::string agreeOnError(Comm& comm, const std::string& localError)
{
  const RankFailure agreed = agreeOnFailure(comm, localError);
  if (!agreed.failed())
  {
    return {};
  }
  // When only some ranks failed, say which one (the same text on every rank); when all failed
  // (a bad option, the same everywhere) the message stands alone.
  return agreed.all ? agreed.message
                    : "rank " + std::to_string(agreed.rank) + ": " + agreed.message;
}

bool anyRank(Comm& comm, bool value)
{
  std::vector<std::int64_t> v{ value ? 1 : 0 };
  comm.sum(v);
  return v[0] > 0;
}

double maxOverRanks(Comm& comm, double value)
{
  std::vector<double> v{ value };
  comm.max(v);
  return v[0];
}

double minOverRanks(Comm& comm, double value)
{
  return -maxOverRanks(comm, -value);
}

void ExactSum::add(double term)
{
  double q = std::nearbyint(std::ldexp(term, 32)); // an integer below 2^96: three exact digits
  for (std::uint64_t& limb : limbs_)
  {
    const double digit = std::fmod(q, 4294967296.0);
    limb += static_cast<std::uint64_t>(digit);
    q = std::ldexp(q - digit, -32);
  }
}

double ExactSum::total(Comm* comm) const
{
  std::vector<std::int64_t> limbs(3);
  std::uint64_t carry = 0;
  for (std::size_t i = 0; i < 3; ++i) // carried into 32-bit digits: a rank sum cannot overflow
  {
    const std::uint64_t v = limbs_[i] + carry;
    limbs[i] = static_cast<std::int64_t>(v & 0xffffffffu);
    carry = v >> 32;
  }
  limbs[2] += static_cast<std::int64_t>(carry << 32);
  if (comm)
  {
    comm->sum(limbs);
  }
  std::uint64_t d[3];
  carry = 0;
  for (std::size_t i = 0; i < 3; ++i)
  {
    const std::uint64_t v = static_cast<std::uint64_t>(limbs[i]) + carry;
    d[i] = i < 2 ? (v & 0xffffffffu) : v;
    carry = v >> 32;
  }
  return std::ldexp(static_cast<double>(d[2]), 32) + static_cast<double>(d[1]) +
    std::ldexp(static_cast<double>(d[0]), -32);
}

double globalNthValue(const std::vector<double>& local, std::int64_t k, Comm& comm)
{
  std::vector<std::int64_t> n{ static_cast<std::int64_t>(local.size()) };
  comm.sum(n);
  if (n[0] == 0)
  {
    return 0.0;
  }
  // Non-negative doubles sort like their bit patterns: find the smallest pattern v with more
  // than k values <= v.
  std::vector<std::uint64_t> bits(local.size());
  for (std::size_t i = 0; i < local.size(); ++i)
    std::memcpy(&bits[i], &local[i], sizeof(double));
  std::uint64_t lo = 0, hi = 0x7ff0000000000000ull; // +inf
  while (lo < hi)
  {
    const std::uint64_t mid = lo + (hi - lo) / 2;
    std::vector<std::int64_t> c{ static_cast<std::int64_t>(
      std::count_if(bits.begin(), bits.end(), [mid](std::uint64_t b) { return b <= mid; })) };
    comm.sum(c);
    if (c[0] > k)
      hi = mid;
    else
      lo = mid + 1;
  }
  double v;
  std::memcpy(&v, &lo, sizeof(double));
  return v;
}

} // namespace fiberpli
