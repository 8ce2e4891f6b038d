#include "Field/FieldFibers.h"

#include "Field/OccupancyGrid.h"

#include "Tissue/Beading.h"
#include "Tissue/Myelin.h"
#include "Util/MemoryBudget.h"
#include "Util/NumberFormat.h"
#include "Util/Random.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

namespace fiberpli
{

namespace
{
constexpr int kSeedTries = 100000;           // uniform tries for one seed position
constexpr std::size_t kDiscardLimit = 10000; // consecutive seeds without a segment: give up
constexpr int kMaxSeedCandidates = 64;
constexpr int kCandidateBatch = 8; // candidates traced per parallel batch
// [ours] The occupancy grid's voxels: the fiber radius, coarser when the region would need more
// than this many (one byte each).
constexpr std::size_t kMaxOccupancyVoxels = std::size_t(1) << 27;

double boxVolume(const OrientationField& f)
{
  const Vec3 e = f.upper() - f.lower();
  return e.x * e.y * e.z;
}

std::vector<double> shares(const FieldFiberOptions& o, int fields)
{
  // Fewer values than fields (or none): equal shares.
  std::vector<double> s(static_cast<std::size_t>(fields), 1.0);
  if (static_cast<int>(o.populationShares.size()) >= fields)
  {
    std::copy_n(o.populationShares.begin(), fields, s.begin());
  }
  const double total = std::accumulate(s.begin(), s.end(), 0.0);
  for (double& v : s)
  {
    v /= total;
  }
  return s;
}

/// Largest-remainder split of n over the shares.
std::vector<int> splitCount(int n, const std::vector<double>& s)
{
  std::vector<int> counts(s.size());
  std::vector<std::pair<double, std::size_t>> remainders;
  int given = 0;
  for (std::size_t k = 0; k < s.size(); ++k)
  {
    const double exact = n * s[k];
    counts[k] = static_cast<int>(std::floor(exact));
    given += counts[k];
    remainders.emplace_back(exact - counts[k], k);
  }
  std::stable_sort(remainders.begin(), remainders.end(),
    [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t r = 0; given < n; ++r, ++given)
  {
    ++counts[remainders[r % remainders.size()].second];
  }
  return counts;
}

/// Σ over links of π · (r_i² + r_i+1²)/2 · length.
double fiberVolume(const Fiber& f)
{
  double v = 0.0;
  for (std::size_t i = 1; i < f.points.size(); ++i)
  {
    v += 0.5 * (f.radii[i - 1] * f.radii[i - 1] + f.radii[i] * f.radii[i]) *
      distance(f.points[i - 1], f.points[i]);
  }
  return M_PI * v;
}

/// Multiplies the radii by the fiber's beading profile along its points.
void bead(Fiber& f, const ShapeOptions& realism, RandomStream&& rng)
{
  std::vector<double> arc(f.points.size(), 0.0);
  for (std::size_t i = 1; i < f.points.size(); ++i)
  {
    arc[i] = arc[i - 1] + distance(f.points[i - 1], f.points[i]);
  }
  const std::vector<double> factors =
    beadingFactors(drawBeading(rng, arc, realism.beadingLength, realism.beadingCV, false));
  for (std::size_t i = 0; i < f.radii.size(); ++i)
  {
    f.radii[i] *= factors[i];
  }
}

/// A seed uniform over the non-empty part of the field, from the fiber's stream.
bool drawSeed(const OrientationField& f, RandomStream& rng, Vec3& seed)
{
  const Vec3 lo = f.lower();
  const Vec3 hi = f.upper();
  for (int t = 0; t < kSeedTries; ++t)
  {
    seed = { rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y), rng.uniform(lo.z, hi.z) };
    if (fieldIsFull(f, seed))
    {
      return true;
    }
  }
  return false;
}

/// The traced line of the seed whose line overlaps the occupancy least per µm (the first of equal
/// ones; without occupancy the first seed's). A line shorter than a third of a segment (a seed in
/// a sliver of the field) is no fiber: it would add next to no volume, so a field of slivers could
/// make fibers without end. Empty when every seed gives such a line. The seeds are traced in
/// batches (the first alone, then kCandidateBatch at a time on `threads` threads), stopping after
/// the batch that holds a line without overlap: the first such line is then the least, so the
/// choice is that of tracing them one by one, for any thread count.
TracedLine bestLine(const OrientationField& field, const std::vector<Vec3>& seeds, double radius,
  const TraceOptions& trace, const OccupancyGrid* occupancy, int threads)
{
  const int n = occupancy ? static_cast<int>(seeds.size()) : 1;
  threads = std::max(1, threads);
  std::vector<TracedLine> lines(static_cast<std::size_t>(n));
  std::vector<double> overlaps(static_cast<std::size_t>(n), -1.0); // -1: no fiber
  const auto evaluate = [&](int c)
  {
    TracedLine& line = lines[static_cast<std::size_t>(c)];
    line = traceFieldLine(field, seeds[static_cast<std::size_t>(c)], trace);
    const double length = line.length();
    if (line.points.size() >= 2 && length >= trace.segmentLength / 3.0)
    {
      // Per µm of line: the sum would favour short lines (those leaving the region early).
      overlaps[static_cast<std::size_t>(c)] =
        occupancy ? static_cast<double>(occupancy->overlap(line.points, radius)) / length : 0.0;
    }
  };
  int best = -1;
  for (int first = 0; first < n;)
  {
    const int last = first == 0 ? 1 : std::min(n, first + kCandidateBatch);
#pragma omp parallel for num_threads(threads)                                                      \
  schedule(dynamic, 1) if (threads > 1 && last - first > 1)
    for (int c = first; c < last; ++c)
    {
      evaluate(c);
    }
    for (int c = first; c < last; ++c)
    {
      const double overlap = overlaps[static_cast<std::size_t>(c)];
      if (overlap >= 0.0 && (best < 0 || overlap < overlaps[static_cast<std::size_t>(best)]))
      {
        best = c;
      }
    }
    if (best >= 0 && overlaps[static_cast<std::size_t>(best)] == 0.0)
    {
      break; // the first line without overlap, whatever the batches
    }
    first = last;
  }
  return best < 0 ? TracedLine() : std::move(lines[static_cast<std::size_t>(best)]);
}

} // namespace

double fieldRegionVolume(const std::vector<const OrientationField*>& fields)
{
  if (fields.empty() || fields[0]->size() == 0)
  {
    return 0.0;
  }
  const std::size_t n = fields[0]->size();
  std::size_t full = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    full += std::any_of(fields.begin(), fields.end(),
      [i](const OrientationField* f) { return norm2(f->vectors[i]) > 0.0; });
  }
  return boxVolume(*fields[0]) * static_cast<double>(full) / static_cast<double>(n);
}

std::string validateFieldFiberOptions(
  const FieldFiberOptions& o, const OrientationField& field, int fields)
{
  if (o.numberOfFibers < 0)
  {
    return "NumberOfFibers is " + std::to_string(o.numberOfFibers) +
      ", must be >= 0 (0 = use VolumeFraction)";
  }
  if (o.numberOfFibers == 0 && !(o.volumeFraction > 0.0 && o.volumeFraction <= 0.9))
  {
    return "VolumeFraction is " + formatNumber(o.volumeFraction) + ", must be in (0, 0.9]";
  }
  if (!(std::isfinite(o.fiberRadius) && o.fiberRadius > 0.0))
  {
    return "FiberRadius is " + formatNumber(o.fiberRadius) + ", must be > 0";
  }
  std::string problem = validateRadiusDistribution(o.radiusDistribution, o.radiusSpread);
  if (problem.empty())
  {
    problem = validateTraceOptions(o.trace);
  }
  if (!problem.empty())
  {
    return problem;
  }
  if (fields < 1 || fields > 2)
  {
    return "the source takes 1 or 2 orientation fields, not " + std::to_string(fields);
  }
  if (!o.populationShares.empty())
  {
    for (int k = 0; k < fields && k < static_cast<int>(o.populationShares.size()); ++k)
    {
      const double s = o.populationShares[static_cast<std::size_t>(k)];
      if (!(std::isfinite(s) && s > 0.0))
      {
        return "PopulationShares value " + std::to_string(k + 1) + " is " + formatNumber(s) +
          ", must be > 0";
      }
    }
  }
  if (o.seedCandidates < 1 || o.seedCandidates > kMaxSeedCandidates)
  {
    return "SeedCandidates is " + std::to_string(o.seedCandidates) + ", must be in [1, " +
      std::to_string(kMaxSeedCandidates) + "]";
  }
  problem = validateShapeOptions(o.realism);
  if (problem.empty() && (o.realism.undulating() || o.realism.dispersed()))
  {
    problem = "Tortuosity and DispersionC2 are not offered by the field source (the field sets the "
              "fibers' course)";
  }
  if (!problem.empty())
  {
    return problem;
  }
  problem = validateOrientationField(field);
  if (!problem.empty())
  {
    return problem;
  }
  const Vec3 e = field.upper() - field.lower();
  const double smallestEdge = std::min({ e.x, e.y, e.z });
  if (o.fiberRadius >= 0.5 * smallestEdge)
  {
    return "FiberRadius is " + formatNumber(o.fiberRadius) +
      " µm, must be below half the region's smallest edge (" + formatNumber(smallestEdge) + " µm)";
  }
  // Memory: the points of the target total length (or of the count, each fiber one diagonal long).
  const double h = o.trace.segmentLength;
  const double diagonal = norm(e);
  double fibers = 0.0;
  double points = 0.0;
  if (o.numberOfFibers > 0)
  {
    fibers = o.numberOfFibers;
    points = fibers * (std::ceil(diagonal / h) + 2.0);
  }
  else
  {
    const double rmin = o.fiberRadius * minimumRadiusFactor(o.radiusDistribution, o.radiusSpread);
    const double totalLength = o.volumeFraction * boxVolume(field) / (M_PI * rmin * rmin);
    points = totalLength / h;
    fibers = totalLength / std::max(h, smallestEdge);
    points += 2.0 * fibers;
  }
  return checkMemoryBudget(fiberModelBytes(fibers, points),
    "FiberFieldSource: about " + formatNumber(std::round(points)) + " fiber points (" +
      (o.numberOfFibers > 0 ? "NumberOfFibers " + std::to_string(o.numberOfFibers)
                            : "VolumeFraction " + formatNumber(o.volumeFraction)) +
      ", SegmentLength " + formatNumber(h) + " µm, FiberRadius " + formatNumber(o.fiberRadius) +
      " µm)");
}

FieldFiberResult generateFieldFibers(const std::vector<const OrientationField*>& fields,
  const FieldFiberOptions& o, const ProgressFn& progress)
{
  FieldFiberResult result;
  if (fields.empty())
  {
    result.error = "no orientation field";
    return result;
  }
  const int populations = static_cast<int>(fields.size());
  result.error = validateFieldFiberOptions(o, *fields[0], populations);
  if (!result.error.empty())
  {
    return result;
  }
  for (const OrientationField* f : fields)
  {
    if (f->dimensions != fields[0]->dimensions || !(f->origin == fields[0]->origin) ||
      !(f->spacing == fields[0]->spacing) || f->vectors.size() != fields[0]->vectors.size())
    {
      result.error = "the orientation fields do not share one grid";
      return result;
    }
  }
  result.regionVolume = fieldRegionVolume(fields);
  for (int k = 0; k < populations; ++k)
  {
    if (nonEmptyShare(*fields[static_cast<std::size_t>(k)]) == 0.0)
    {
      result.error = std::string("the ") +
        (k == 0 ? "orientation field"
                : "second orientation field (SecondOrientationArray, or components 3-5 of a "
                  "6-component OrientationArray)") +
        " is empty everywhere (every vector zero or not finite)";
      return result;
    }
  }

  const std::vector<double> share = shares(o, populations);
  const bool byCount = o.numberOfFibers > 0;
  const std::vector<int> counts =
    byCount ? splitCount(o.numberOfFibers, share) : std::vector<int>();
  const double target = o.volumeFraction * result.regionVolume;
  const Vec3 extent = fields[0]->upper() - fields[0]->lower();
  const double maxRadius = 0.25 * std::min({ extent.x, extent.y, extent.z });

  std::vector<double> volume(static_cast<std::size_t>(populations), 0.0);
  std::vector<std::uint64_t> drawn(static_cast<std::size_t>(populations), 0);
  std::vector<int> made(static_cast<std::size_t>(populations), 0);
  double total = 0.0;
  std::size_t discardedInARow = 0;
  std::unique_ptr<OccupancyGrid> occupancy;
  if (o.seedCandidates > 1)
  {
    occupancy = std::make_unique<OccupancyGrid>(
      fields[0]->lower(), fields[0]->upper(), o.fiberRadius, kMaxOccupancyVoxels);
  }
  while (true)
  {
    // The next population: in count mode the fibers of 0, then of 1; by volume the one furthest
    // below its share of the target.
    int k = -1;
    if (byCount)
    {
      for (int p = 0; p < populations && k < 0; ++p)
      {
        k = made[static_cast<std::size_t>(p)] < counts[static_cast<std::size_t>(p)] ? p : -1;
      }
      if (k < 0)
      {
        break;
      }
    }
    else
    {
      if (total >= target)
      {
        break;
      }
      double deficit = -1.0;
      for (int p = 0; p < populations; ++p)
      {
        const double d =
          1.0 - volume[static_cast<std::size_t>(p)] / (share[static_cast<std::size_t>(p)] * target);
        if (d > deficit)
        {
          deficit = d;
          k = p;
        }
      }
    }
    const OrientationField& field = *fields[static_cast<std::size_t>(k)];
    const std::uint64_t index = drawn[static_cast<std::size_t>(k)]++;
    RandomStream rng(o.seed, static_cast<std::uint64_t>(k), index);
    std::vector<Vec3> seeds(static_cast<std::size_t>(o.seedCandidates));
    for (Vec3& seed : seeds)
    {
      if (!drawSeed(field, rng, seed))
      {
        result.error = "no seed found on the non-empty part of the " +
          std::string(k == 0 ? "orientation field" : "second orientation field") + " in " +
          std::to_string(kSeedTries) + " uniform tries (it is almost all empty)";
        return result;
      }
    }
    const double radius =
      drawFiberRadius(rng, o.fiberRadius, o.radiusSpread, o.radiusDistribution, maxRadius);
    TracedLine line = bestLine(field, seeds, radius, o.trace, occupancy.get(), o.threads);
    if (line.points.empty())
    {
      ++result.discardedSeeds;
      if (++discardedInARow >= kDiscardLimit)
      {
        result.error = "the last " + std::to_string(kDiscardLimit) +
          " seeds gave no fiber of a third of SegmentLength or more (the field is full only in "
          "slivers thinner "
          "than that across its direction)";
        return result;
      }
      continue;
    }
    discardedInARow = 0;
    Fiber fiber;
    fiber.id = static_cast<std::int64_t>(result.model.fibers.size());
    fiber.bundle = k;
    fiber.radii.assign(line.points.size(), radius);
    fiber.points = std::move(line.points);
    if (o.realism.beaded())
    {
      bead(fiber, o.realism,
        shapeStream(o.seed, ShapeFeature::Beading, static_cast<std::uint64_t>(k), index));
    }
    const double added = fiberVolume(fiber);
    volume[static_cast<std::size_t>(k)] += added;
    total += added;
    ++made[static_cast<std::size_t>(k)];
    if (occupancy)
    {
      occupancy->add(fiber.points, fiber.radii);
    }
    result.model.fibers.push_back(std::move(fiber));
    if (result.model.fibers.size() % 64 == 0)
    {
      const double done = byCount
        ? static_cast<double>(result.model.fibers.size()) / o.numberOfFibers
        : total / target;
      if (!reportProgress(progress, std::min(done, 1.0)))
      {
        FieldFiberResult stopped;
        stopped.aborted = true;
        return stopped;
      }
    }
  }
  addMyelin(result.model, o.realism); // inner radii with myelin on
  result.volumeFraction = result.regionVolume > 0.0 ? total / result.regionVolume : 0.0;
  return result;
}

} // namespace fiberpli
