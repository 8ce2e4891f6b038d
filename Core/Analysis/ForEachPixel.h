/// ForEachPixel: the pixel loop of the analysis maps over the sub-rectangle of an nx × ny image
/// (x fastest, Section/PixelGrid.h GridRange) that one Core analysis call computes
/// (docs/pli-analysis.md §1; docs/pli-simulation.md §6: an MPI piece or an UPDATE_EXTENT). Every
/// map function reads and writes full-size arrays but touches only the pixels in the range.
#pragma once

#include "Section/PixelGrid.h"
#include "Util/Progress.h"
#include "Util/Threads.h"

#include <cstdint>

namespace fiberpli
{

/// Runs f(pixelIndex) for every pixel of the range, OpenMP over pixels with `threads` threads
/// (0 = all). Rows are processed in blocks so that progress is reported from the calling thread
/// between parallel regions (Util/Progress.h). f must only write per-pixel outputs, so the result
/// does not depend on the thread count. Returns false when progress asked to stop.
template <class F>
bool forEachPixel(
  std::int64_t nx, const GridRange& r, int threads, const ProgressFn& progress, F&& f)
{
  const int nThreads = resolveThreadCount(threads);
  const std::int64_t rows = r.ny();
  const std::int64_t width = r.nx();
  if (rows <= 0 || width <= 0)
  {
    return reportProgress(progress, 1.0);
  }
  // About 100 progress reports, but never blocks so small that starting the threads dominates.
  std::int64_t block = rows / 100;
  if (block * width < 16384)
  {
    block = (16384 + width - 1) / width;
  }
  for (std::int64_t jb = r.j0; jb < r.j1; jb += block)
  {
    const std::int64_t je = jb + block < r.j1 ? jb + block : r.j1;
    const std::int64_t n = (je - jb) * width;
#pragma omp parallel for num_threads(nThreads) schedule(dynamic, 64)
    for (std::int64_t k = 0; k < n; ++k)
    {
      const std::int64_t i = r.i0 + k % width;
      const std::int64_t j = jb + k / width;
      f(i + nx * j);
    }
    if (!reportProgress(progress, static_cast<double>(je - r.j0) / static_cast<double>(rows)))
    {
      return false;
    }
  }
  return true;
}

} // namespace fiberpli
