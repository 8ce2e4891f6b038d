/// Progress callback of every long Core algorithm: called from the calling thread (never inside an
/// OpenMP region) with the fraction done in [0, 1]; returning false asks the algorithm to stop.
#pragma once

#include <functional>

namespace fiberpli
{

using ProgressFn = std::function<bool(double fraction)>;

/// Calls progress if it is set; true means "go on".
inline bool reportProgress(const ProgressFn& progress, double fraction)
{
  return !progress || progress(fraction);
}

} // namespace fiberpli
