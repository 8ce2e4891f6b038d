#include "Metrics/FiberMetrics.h"

#include "Model/PeriodicCellRule.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace fiberpli
{
namespace
{

const double NaN = std::numeric_limits<double>::quiet_NaN();

std::string boxText(const Vec3& lo, const Vec3& hi)
{
  std::ostringstream s;
  s << lo.x << " " << hi.x << " " << lo.y << " " << hi.y << " " << lo.z << " " << hi.z;
  return s.str();
}

/// Empty when the cell is off (hi == lo on every axis, the default) or usable (finite, min < max on
/// every axis), else why not: a half-set or infinite cell would silently skip or break the images.
std::string checkCell(const PeriodicCell& cell)
{
  bool off = true;
  for (int i = 0; i < 3; ++i)
  {
    off = off && cell.hi[i] == cell.lo[i];
  }
  return off ? "" : validatePeriodicCell(cell);
}

/// The region of the volume fraction, or an error naming the offending value.
std::string chooseRegion(const FiberModel& model, const MetricsOptions& options, Vec3& lo, Vec3& hi)
{
  if (options.cell.enabled())
  {
    lo = options.cell.lo;
    hi = options.cell.hi;
    return "";
  }
  const bool fromBounds = options.boxLo.x > options.boxHi.x || options.boxLo.y > options.boxHi.y ||
    options.boxLo.z > options.boxHi.z;
  if (fromBounds)
  {
    modelBounds(model, false, lo, hi);
  }
  else
  {
    lo = options.boxLo;
    hi = options.boxHi;
  }
  for (int i = 0; i < 3; ++i)
  {
    if (!std::isfinite(lo[i]) || !std::isfinite(hi[i]) || !(hi[i] > lo[i]))
    {
      return std::string(fromBounds ? "the fibers' bounds " : "Box ") + boxText(lo, hi) +
        " enclose no volume (min < max needed on every axis" +
        (fromBounds ? "; set Box explicitly for flat models)" : ")");
    }
  }
  return "";
}

/// VoxelSize, or the automatic one: an eighth of the smallest radius, coarsened to the voxel limit.
double voxelEdge(const MetricsOptions& options, const MetricsResult& result)
{
  if (options.voxelSize > 0.0)
  {
    return options.voxelSize;
  }
  const Vec3 e = result.regionHi - result.regionLo;
  return std::max(result.shape.radius.min / 8.0, std::cbrt(e.x * e.y * e.z / options.automaticVoxelLimit));
}

} // namespace

namespace
{
/// Empty without a cell or when every link spans at most one cell edge along every axis. A longer
/// link wraps over the cell more than once: its nearest image is no longer the only one a pair
/// can meet, and its voxels are visited once per wrap (99 µm links in a 10 µm cell took a minute
/// for what one pass gives), so such a model is refused, naming the fiber, the link and the spans.
std::string checkLinksFitCell(const FiberModel& model, const PeriodicCell& cell)
{
  if (!cell.enabled())
  {
    return {};
  }
  static const char* const kAxis[3] = { "x", "y", "z" };
  const Vec3 e = cell.edge();
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fiber = model.fibers[f];
    for (std::size_t k = 0; k + 1 < fiber.points.size(); ++k)
    {
      const Vec3 d = fiber.points[k + 1] - fiber.points[k];
      for (int a = 0; a < 3; ++a)
      {
        if (std::fabs(d[a]) > e[a])
        {
          std::ostringstream s;
          s << "fiber " << f << " (fiber_id " << fiber.id << ") link " << k << " spans " << std::fabs(d[a])
            << " um along " << kAxis[a] << ", more than the periodic cell's edge " << e[a]
            << " um: links longer than the cell wrap over it and have no single nearest image (turn "
               "UsePeriodicCell off, or give the fibers shorter links, e.g. FiberCollisionSolver's SegmentLength)";
          return s.str();
        }
      }
    }
  }
  return {};
}
} // namespace

MetricsResult computeFiberMetrics(const FiberModel& model, const MetricsOptions& options,
  const ProgressFn& progress)
{
  MetricsResult result;
  result.volume.fraction = NaN;
  result.volume.errorBound = NaN;
  result.pairs.collisions = -1;
  result.pairs.minGap = NaN;
  result.error = checkCell(options.cell);
  if (result.error.empty())
  {
    result.error = checkLinksFitCell(model, options.cell);
  }
  if (!result.error.empty())
  {
    return result;
  }
  if (!(options.voxelSize >= 0.0) || !std::isfinite(options.voxelSize))
  {
    std::ostringstream s;
    s << "VoxelSize " << options.voxelSize << " must be >= 0 (0 = automatic)";
    result.error = s.str();
    return result;
  }
  result.fibers = model.fibers.size();
  result.points = model.numberOfPoints();
  result.links = model.numberOfLinks();
  const CapsuleSet set = makeCapsules(model, options.cell);
  result.shape = fiberShape(model, set);
  if (model.empty())
  {
    return result;
  }

  const double volumeShare = options.volumeFraction ? (options.pairs ? 0.7 : 1.0) : 0.0;
  if (options.volumeFraction)
  {
    result.error = chooseRegion(model, options, result.regionLo, result.regionHi);
    if (!result.error.empty())
    {
      return result;
    }
    const ProgressFn volumeProgress = [&](double f) { return reportProgress(progress, volumeShare * f); };
    if (options.monteCarlo)
    {
      result.volume = monteCarloVolumeFraction(set, result.regionLo, result.regionHi, options.samples, options.seed,
        options.cell, options.numberOfThreads, volumeProgress);
    }
    else
    {
      const double h = voxelEdge(options, result);
      const double voxels = voxelCount(result.regionLo, result.regionHi, h);
      if (voxels > options.voxelLimit)
      {
        std::ostringstream s;
        s << "VoxelSize " << h << " gives " << voxels << " voxels in " << boxText(result.regionLo, result.regionHi)
          << ", more than " << options.voxelLimit << "; use a larger VoxelSize or a smaller Box";
        result.error = s.str();
        return result;
      }
      result.volume = volumeFraction(set, result.regionLo, result.regionHi, h, options.cell, options.numberOfThreads,
        volumeProgress);
    }
    if (!result.volume.error.empty() || result.volume.aborted)
    {
      result.error = result.volume.error;
      result.aborted = result.volume.aborted;
      return result;
    }
  }
  if (options.pairs)
  {
    result.pairs = compareCapsulePairs(set, options.cell, options.numberOfThreads,
      [&](double f) { return reportProgress(progress, volumeShare + (1.0 - volumeShare) * f); });
    result.aborted = result.pairs.aborted;
  }
  return result;
}

} // namespace fiberpli
