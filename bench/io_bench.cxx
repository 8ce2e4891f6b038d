// io_bench: write and read a fiber model of N points (default 1,000,000) as fastPLI .dat and
// MRtrix .tck through the Core/IO path-level API (atomic write included), and report seconds per
// million points and peak RSS (VmHWM) of each phase. The peak is reset between phases through
// /proc/self/clear_refs, so the read figure shows what reading costs on top of the empty process.
// Usage: io_bench [points] [directory]   (files are removed at the end)
#include "IO/FiberFile.h"
#include "Util/Random.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

using namespace fiberpli;

namespace
{

long peakRssKiB()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.rfind("VmHWM:", 0) == 0)
    {
      return std::strtol(line.c_str() + 6, nullptr, 10);
    }
  }
  return -1;
}

void resetPeakRss()
{
  std::ofstream("/proc/self/clear_refs") << "5";
}

/// Fibers of 100 points along random directions in a 1 mm cube, radius around 1 µm; coordinates
/// have full double mantissas (the worst case for the text writer).
FiberModel makeModel(std::size_t points)
{
  FiberModel m;
  const std::size_t perFiber = 100;
  const std::size_t fibers = (points + perFiber - 1) / perFiber;
  m.fibers.resize(fibers);
  for (std::size_t k = 0; k < fibers; ++k)
  {
    RandomStream rng(1, k);
    Fiber& f = m.fibers[k];
    f.id = static_cast<std::int64_t>(k);
    f.bundle =
      static_cast<int>(3 * k / fibers); // contiguous bundles: the .dat writer keeps fiber order
    const std::size_t n = std::min(perFiber, points - k * perFiber);
    Vec3 p{ rng.uniform(-500, 500), rng.uniform(-500, 500), rng.uniform(-500, 500) };
    const Vec3 d = normalized(Vec3{ rng.normal(), rng.normal(), rng.normal() });
    for (std::size_t i = 0; i < n; ++i)
    {
      f.points.push_back(
        p + Vec3{ rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5), rng.uniform(-0.5, 0.5) });
      f.radii.push_back(rng.uniform(0.8, 1.2));
      p += 2.0 * d;
    }
  }
  return m;
}

double seconds(std::chrono::steady_clock::time_point a)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
}

} // namespace

int main(int argc, char** argv)
{
  const std::size_t points = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1000000;
  const std::string dir = argc > 2 ? argv[2] : "/tmp";
  if (points < 2)
  {
    std::fprintf(stderr, "points must be >= 2\n");
    return 1;
  }
  const double mega = static_cast<double>(points) / 1e6;
  std::printf("io_bench: %zu points, files in %s\n", points, dir.c_str());
  int status = 0;
  for (const char* ext : { "dat", "tck" })
  {
    const std::string path = dir + "/io_bench_" + std::to_string(::getpid()) + "." + ext;
    double writeSeconds = 0.0;
    long writePeak = 0;
    FiberModel reference;
    {
      FiberModel m = makeModel(points);
      resetPeakRss();
      const auto t0 = std::chrono::steady_clock::now();
      const std::string err = writeFiberFile(path, m);
      writeSeconds = seconds(t0);
      writePeak = peakRssKiB();
      if (!err.empty())
      {
        std::fprintf(stderr, "write failed: %s\n", err.c_str());
        return 1;
      }
      reference = std::move(m);
    }
    struct stat st;
    ::stat(path.c_str(), &st);
    const std::size_t modelPoints = reference.numberOfPoints();
    const std::string firstCheck = std::string(ext);
    // Keep only what the check needs so the read phase's peak is not inflated by the reference.
    const Vec3 lastPoint = reference.fibers.back().points.back();
    const double lastRadius = reference.fibers.back().radii.back();
    reference = FiberModel{};
    const long baseline = (resetPeakRss(), peakRssKiB());
    const auto t1 = std::chrono::steady_clock::now();
    const FiberReadResult r = readFiberFile(path, 1.0);
    const double readSeconds = seconds(t1);
    const long readPeak = peakRssKiB();
    ::unlink(path.c_str());
    if (!r.ok() || r.model.numberOfPoints() != modelPoints)
    {
      std::fprintf(stderr, "read failed: %s\n", r.error.c_str());
      return 1;
    }
    const Vec3 q = r.model.fibers.back().points.back();
    const bool exact = firstCheck == "dat"
      ? (q == lastPoint && r.model.fibers.back().radii.back() == lastRadius)
      : (q.x == static_cast<double>(static_cast<float>(lastPoint.x)));
    if (!exact)
    {
      std::fprintf(stderr, ".%s round trip changed the last point\n", ext);
      status = 1;
    }
    std::printf(
      ".%s  file %.1f MB | write %.3f s (%.3f s per 1M points), peak RSS %.1f MB | "
      "read %.3f s (%.3f s per 1M points), peak RSS %.1f MB (process before read %.1f MB, "
      "model %.1f MB)\n",
      ext, static_cast<double>(st.st_size) / 1e6, writeSeconds, writeSeconds / mega,
      writePeak / 1024.0, readSeconds, readSeconds / mega, readPeak / 1024.0, baseline / 1024.0,
      static_cast<double>(modelPoints) * (sizeof(Vec3) + sizeof(double)) / 1e6);
  }
  return status;
}
