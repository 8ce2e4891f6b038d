/// refill: a buffer reused every step, set to n copies of a value.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace fiberpli
{

/// v = n copies of x, the capacity growing by half when it must grow. std::vector::assign
/// reallocates to exactly n: a per-step buffer whose size creeps up by a few elements a step (the
/// points of a solve as shape control splits links) was then allocated afresh nearly every step,
/// and a large one, which the allocator maps from the system, had every page faulted in again.
template <class T>
void refill(std::vector<T>& v, std::size_t n, const T& x)
{
  if (n > v.capacity())
  {
    v.reserve(std::max(n, v.capacity() + v.capacity() / 2));
  }
  v.assign(n, x);
}

} // namespace fiberpli
