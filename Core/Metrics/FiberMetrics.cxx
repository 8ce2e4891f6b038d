#include "Metrics/FiberMetrics.h"

#include "Model/PeriodicCellRule.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

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
  return std::max(
    result.shape.radius.min / 8.0, std::cbrt(e.x * e.y * e.z / options.automaticVoxelLimit));
}

/// One measurement of the volume fraction kind (outer capsules or axons) with the chosen method.
VolumeFractionResult measureVolume(const CapsuleSet& set, const MetricsOptions& options,
  const MetricsResult& result, double h, const ProgressFn& progress)
{
  if (options.monteCarlo)
  {
    return monteCarloVolumeFraction(set, result.regionLo, result.regionHi, options.samples,
      options.seed, options.cell, options.numberOfThreads, progress);
  }
  return volumeFraction(
    set, result.regionLo, result.regionHi, h, options.cell, options.numberOfThreads, progress);
}

/// Copies an error or abort of a part into the result; true when the run must stop.
bool stops(const Status& part, MetricsResult& result)
{
  if (!part.error.empty() || part.aborted)
  {
    result.error = part.error;
    result.aborted = part.aborted;
    return true;
  }
  return false;
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
          s << "fiber " << f << " (fiber_id " << fiber.id << ") link " << k << " spans "
            << std::fabs(d[a]) << " um along " << kAxis[a]
            << ", more than the periodic cell's edge " << e[a]
            << " um: links longer than the cell wrap over it and have no single nearest image "
               "(turn "
               "UsePeriodicCell off, or give the fibers shorter links, e.g. FiberCollisionSolver's "
               "SegmentLength)";
          return s.str();
        }
      }
    }
  }
  return {};
}
} // namespace

MetricsResult computeFiberMetrics(
  const FiberModel& model, const MetricsOptions& options, const ProgressFn& progress)
{
  MetricsResult result;
  result.volume.fraction = NaN;
  result.volume.errorBound = NaN;
  result.axonVolume.fraction = NaN;
  result.axonVolume.errorBound = NaN;
  result.myelinFraction = NaN;
  result.extraAxonalFraction = NaN;
  result.mixing.minimum = NaN;
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
  if (options.histogramBins < 1 || options.histogramBins > 1000000)
  {
    result.error =
      "HistogramBins " + std::to_string(options.histogramBins) + " must be in [1, 1000000]";
    return result;
  }
  result.error = validateInnerRadii(model);
  if (!result.error.empty())
  {
    return result;
  }
  result.fibers = model.fibers.size();
  result.points = model.numberOfPoints();
  result.links = model.numberOfLinks();
  const CapsuleSet set = makeCapsules(model, options.cell);
  result.shape = fiberShape(model, set);
  result.realism =
    measureRealism(model, result.shape, static_cast<std::size_t>(options.histogramBins));
  if (model.empty())
  {
    return result;
  }

  // Progress: the parts that run share [0, 1] by their rough cost (today's default run, volume and
  // pairs, keeps its 0.7 / 0.3 split).
  const bool axons = options.volumeFraction && hasInnerRadii(model);
  const bool sampledMixing = options.mixing && result.realism.populations.size() > 1;
  const double volumeCost = options.volumeFraction ? 0.7 : 0.0;
  const double axonCost = axons ? 0.7 : 0.0;
  const double mixingCost = sampledMixing ? 0.7 : 0.0;
  const double pairsCost = options.pairs ? 0.3 : 0.0;
  const double total = std::max(1e-300, volumeCost + axonCost + mixingCost + pairsCost);
  double done = 0.0;
  const auto part = [&](double cost)
  {
    const double offset = done / total, share = cost / total;
    done += cost;
    return ProgressFn([&progress, offset, share](double f)
      { return reportProgress(progress, offset + share * f); });
  };

  bool haveRegion = false;
  if (options.volumeFraction || sampledMixing)
  {
    // Without the volume fraction a region enclosing no volume (a flat model) only leaves the
    // mixing figure NaN, as before the mixing existed.
    const std::string regionError = chooseRegion(model, options, result.regionLo, result.regionHi);
    haveRegion = regionError.empty();
    if (!haveRegion && options.volumeFraction)
    {
      result.error = regionError;
      return result;
    }
  }
  if (options.volumeFraction)
  {
    const double h = options.monteCarlo ? 0.0 : voxelEdge(options, result);
    if (!options.monteCarlo)
    {
      const double voxels = voxelCount(result.regionLo, result.regionHi, h);
      if (voxels > options.voxelLimit)
      {
        std::ostringstream s;
        s << "VoxelSize " << h << " gives " << voxels << " voxels in "
          << boxText(result.regionLo, result.regionHi) << ", more than " << options.voxelLimit
          << "; use a larger VoxelSize or a smaller Box";
        result.error = s.str();
        return result;
      }
    }
    result.volume = measureVolume(set, options, result, h, part(volumeCost));
    if (stops(result.volume, result))
    {
      return result;
    }
    if (axons)
    {
      // The same estimator on the inner capsules: the same voxels (or points) judge both, so the
      // myelin fraction is a difference of two counts over one grid.
      const CapsuleSet axonSet = makeCapsules(axonModel(model), options.cell);
      result.axonVolume = measureVolume(axonSet, options, result, h, part(axonCost));
      if (stops(result.axonVolume, result))
      {
        return result;
      }
      result.myelinFraction = result.volume.fraction - result.axonVolume.fraction;
    }
    result.extraAxonalFraction = 1.0 - result.volume.fraction;
  }
  if (options.mixing)
  {
    if (sampledMixing && haveRegion)
    {
      result.mixing = measureMixing(model, set, result.regionLo, result.regionHi, options.samples,
        options.seed, options.cell, options.numberOfThreads, part(mixingCost));
      if (stops(result.mixing, result))
      {
        return result;
      }
    }
    else if (!sampledMixing)
    {
      // One population holds all the fiber volume of every sub-cube.
      result.mixing.bundles = { model.fibers.front().bundle };
      result.mixing.minShare = { 1.0 };
      result.mixing.volumeShare = { 1.0 };
      result.mixing.minimum = 1.0;
    }
  }
  if (options.pairs)
  {
    result.pairs = compareCapsulePairs(set, options.cell, options.numberOfThreads, part(pairsCost));
    result.aborted = result.pairs.aborted;
  }
  return result;
}

} // namespace fiberpli
