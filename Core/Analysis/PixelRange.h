/// PixelRange: the sub-rectangle of an nx × ny image (x fastest) that one Core analysis call
/// computes (docs/pli-analysis.md §1; docs/pli-simulation.md §6: an MPI piece or an UPDATE_EXTENT).
/// Every map function reads and writes full-size arrays but touches only the pixels in the range.
#pragma once

#include "Util/Progress.h"
#include "Util/Threads.h"

#include <cstdint>
#include <sstream>
#include <string>

namespace fiberpli
{

/// Pixels [i0, i1) × [j0, j1) of an nx × ny image; pixel (i, j) has linear index i + nx·j.
struct PixelRange
{
  std::int64_t i0 = 0;
  std::int64_t i1 = 0;
  std::int64_t j0 = 0;
  std::int64_t j1 = 0;

  std::int64_t width() const { return i1 - i0; }
  std::int64_t height() const { return j1 - j0; }
  std::int64_t count() const { return width() * height(); }
};

/// The whole nx × ny image.
inline PixelRange wholeImage(std::int64_t nx, std::int64_t ny) { return { 0, nx, 0, ny }; }

/// Empty string when nx, ny >= 0 and the range lies inside the image (an empty range is allowed),
/// else a message naming the offending bound.
inline std::string validatePixelRange(std::int64_t nx, std::int64_t ny, const PixelRange& r)
{
  std::ostringstream msg;
  if (nx < 0 || ny < 0)
  {
    msg << "image size " << nx << " x " << ny << " is negative";
  }
  else if (r.i0 < 0 || r.i1 > nx || r.i0 > r.i1)
  {
    msg << "pixel range i [" << r.i0 << ", " << r.i1 << ") is not inside [0, " << nx << ")";
  }
  else if (r.j0 < 0 || r.j1 > ny || r.j0 > r.j1)
  {
    msg << "pixel range j [" << r.j0 << ", " << r.j1 << ") is not inside [0, " << ny << ")";
  }
  return msg.str();
}

/// Runs f(pixelIndex) for every pixel of the range, OpenMP over pixels with `threads` threads
/// (0 = all). Rows are processed in blocks so that progress is reported from the calling thread
/// between parallel regions (Util/Progress.h). f must only write per-pixel outputs, so the result
/// does not depend on the thread count. Returns false when progress asked to stop.
template <class F>
bool forEachPixel(std::int64_t nx, const PixelRange& r, int threads, const ProgressFn& progress, F&& f)
{
  const int nThreads = resolveThreadCount(threads);
  const std::int64_t rows = r.height();
  const std::int64_t width = r.width();
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
