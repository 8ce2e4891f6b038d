#include "Tissue/CubeGenerator.h"

#include "Model/FiberPieces.h"
#include "Tissue/DiskPacking.h"
#include "Tissue/LatticeSeeding.h"
#include "Tissue/Seeds.h"
#include "Util/MemoryBudget.h"
#include "Util/Random.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fiberpli
{

namespace
{
// A closed fiber needs 3 points: with 2, its only link would be its own neighbour.
int pointsPerFiber(const CubeOptions& o)
{
  const int minimum = o.periodic ? 3 : 2;
  return std::max(minimum, static_cast<int>(std::lround(o.edgeLength / o.segmentLength)) + 1);
}

// Upper bound of the fiber count (validation and the volume-fraction loop): the target volume
// over the volume of a fiber of the smallest radius a distribution can give.
double fiberCountEstimate(const CubeOptions& o)
{
  if (!(o.volumeFraction > 0.0))
  {
    return o.numberOfFibers;
  }
  const double rMin = o.fiberRadius * minimumRadiusFactor(o.radiusDistribution, o.radiusSpread);
  return o.volumeFraction * o.edgeLength * o.edgeLength / (M_PI * rMin * rMin) + 1.0;
}

// The largest link reach the collision solver can meet in a periodic cube (the pair search's rule,
// Geometry/PeriodicCell.h), with its SegmentLength equal to the cube's: a link spans at most one
// point spacing plus the displacement of both ends along an axis, and the solver's split leaves no
// link longer than 4/3 SegmentLength; plus both radii (FiberRadius: with a spread the solver
// still judges the radii it gets).
double solverLinkReach(const CubeOptions& o)
{
  const double spacing = o.edgeLength / (pointsPerFiber(o) - 1) + 2.0 * o.displacement;
  return std::min(spacing, 4.0 / 3.0 * o.segmentLength) + 2.0 * o.fiberRadius;
}

// Fiber j of population k (stream (seed, k, j)): straight along axis k, displaced; closed through
// the faces when periodic (the last point is the first shifted by one period, not drawn).
Fiber makeFiber(const CubeOptions& o, int k, int j)
{
  const int n = pointsPerFiber(o);
  const double half = 0.5 * o.edgeLength;
  const int axis = k;
  const int other1 = (axis + 1) % 3;
  const int other2 = (axis + 2) % 3;
  RandomStream rng(o.seed, static_cast<std::uint64_t>(k), static_cast<std::uint64_t>(j));
  Fiber f;
  f.bundle = k;
  const double t1 = rng.uniform(-half, half);
  const double t2 = rng.uniform(-half, half);
  f.points.resize(static_cast<std::size_t>(n));
  const int drawn = o.periodic ? n - 1 : n;
  for (int i = 0; i < drawn; ++i)
  {
    Vec3 p;
    p[axis] = -half + o.edgeLength * static_cast<double>(i) / static_cast<double>(n - 1);
    p[other1] = t1;
    p[other2] = t2;
    for (int a = 0; a < 3; ++a)
    {
      p[a] += rng.uniform(-o.displacement, o.displacement);
    }
    f.points[static_cast<std::size_t>(i)] = p;
  }
  if (o.periodic)
  {
    Vec3 last = f.points[0];
    last[axis] += o.edgeLength;
    f.points[static_cast<std::size_t>(n - 1)] = last;
  }
  // Drawn last so that cubes of constant radius keep their draws (and their bytes).
  const double r = o.radiusSpread > 0.0
    ? drawFiberRadius(rng, o.fiberRadius, o.radiusSpread, o.radiusDistribution, 0.25 * o.edgeLength)
    : o.fiberRadius;
  f.radii.assign(static_cast<std::size_t>(n), r);
  return f;
}
// The radius makeFiber(o, k, j) gives, without building the points: the same draws, the points'
// skipped (2 transverse, 3 per drawn point).
double cubeFiberRadius(const CubeOptions& o, int k, int j)
{
  if (!(o.radiusSpread > 0.0))
  {
    return o.fiberRadius;
  }
  const int n = pointsPerFiber(o);
  RandomStream rng(o.seed, static_cast<std::uint64_t>(k), static_cast<std::uint64_t>(j));
  const int skipped = 2 + 3 * (o.periodic ? n - 1 : n);
  for (int i = 0; i < skipped; ++i)
  {
    rng.next();
  }
  return drawFiberRadius(rng, o.fiberRadius, o.radiusSpread, o.radiusDistribution, 0.25 * o.edgeLength);
}

// Fibers per population. With a volume fraction: fibers in turn over the populations (0, 1, 2,
// 0, …) until their volume (each fiber's straight length is one period L) reaches the target, so
// the count is the smallest whose nominal fraction is at least the one asked for; only their radii
// are drawn, so every piece can count them all cheaply.
std::vector<int> populationCounts(const CubeOptions& o)
{
  std::vector<int> counts(static_cast<std::size_t>(o.populations), 0);
  if (!(o.volumeFraction > 0.0))
  {
    for (int k = 0; k < o.populations; ++k)
    {
      counts[static_cast<std::size_t>(k)] = cubePopulationSize(o, k);
    }
    return counts;
  }
  const double target = o.volumeFraction * o.edgeLength * o.edgeLength * o.edgeLength;
  const double bound = fiberCountEstimate(o);
  // The relative 1e-12 absorbs rounding: a target that a count meets exactly (φ = N π r² / L²)
  // gets N fibers, not N + 1.
  const double reached = target * (1.0 - 1e-12);
  double volume = 0.0;
  for (int i = 0; i < bound && volume < reached; ++i)
  {
    const int k = i % o.populations;
    const double r = cubeFiberRadius(o, k, i / o.populations);
    volume += M_PI * r * r * o.edgeLength;
    ++counts[static_cast<std::size_t>(k)];
  }
  return counts;
}

// The fibers a volume fraction takes (populationCounts' rule), counted up to kCountedFibers:
// beyond that `atLeast` is set and the count is a lower bound (enough for the memory check).
constexpr double kCountedFibers = 1e6;
double countedFibers(const CubeOptions& o, bool& atLeast)
{
  const double target = o.volumeFraction * o.edgeLength * o.edgeLength * o.edgeLength * (1.0 - 1e-12);
  const double bound = std::min(fiberCountEstimate(o), kCountedFibers);
  double volume = 0.0;
  double i = 0.0;
  for (; i < bound && volume < target; i += 1.0)
  {
    const int n = static_cast<int>(i);
    const double r = cubeFiberRadius(o, n % o.populations, n / o.populations);
    volume += M_PI * r * r * o.edgeLength;
  }
  atLeast = volume < target;
  return i;
}

// Lattice seeding: the sites of every population, shuffled by the stream (seed, 3 + k, 0) (keys
// 3..5 are not fiber streams: those have key1 = population 0..2). Fiber j of population k takes
// the j-th site.
std::vector<std::vector<LatticeSite>> shuffledSites(const CubeOptions& o, const std::vector<int>& counts,
  double& spacing)
{
  const PeriodicLattice lattice = periodicLattice(o.edgeLength, counts);
  spacing = lattice.spacing;
  std::vector<std::vector<LatticeSite>> all;
  for (std::size_t k = 0; k < counts.size(); ++k)
  {
    std::vector<LatticeSite> sites = lattice.sites[k];
    RandomStream shuffle(o.seed, 3 + k, 0);
    for (std::size_t i = sites.size(); i > 1; --i)
    {
      const auto pick = static_cast<std::size_t>(shuffle.uniform() * static_cast<double>(i));
      std::swap(sites[i - 1], sites[std::min(pick, i - 1)]);
    }
    all.push_back(std::move(sites));
  }
  return all;
}

// Radii differ from fiber to fiber (a spread with a distribution that uses it).
bool polydisperse(const CubeOptions& o)
{
  return o.radiusSpread > 0.0 && o.radiusDistribution != RadiusDistribution::Constant;
}

// Empty when packing p separated its disks, else the warning that the solver starts from overlaps.
// (An empty population has nothing to separate.)
std::string overlapWarning(const CubeOptions& o, const DiskPacking& p, const std::string& where)
{
  if (p.centres.empty() || p.scale >= 1.0)
    return {};
  std::ostringstream w;
  w << "Seeding Lattice: the radii could not be separated in " << where << " (packing scale " << p.scale
    << " < 1 reached, RadiusSpread " << o.radiusSpread << ", " << p.centres.size() << " fibers";
  if (o.volumeFraction > 0.0)
    w << ", VolumeFraction " << o.volumeFraction;
  w << "); the solver starts from overlapping fibers";
  return w.str();
}

// Lattice seeding with polydisperse radii, 1 or 2 populations (docs/periodic-cells.md,
// "Polydisperse seeding"): one site per fiber (fiber j of population k at sites[k][j]) from a
// disk packing of the actual radii (Tissue/DiskPacking.h, stream (seed, 6 + k, 0)). One
// population: the periodic cross-section. Two: population 0 (x-fibers, sites (y, z)) in the slab
// z in [−L/2, −L/2 + h0], population 1 (y-fibers, sites (z, x)) in the rest, h0 / L = the share
// of population 0 in the fiber cross-section; a slab is periodic along its fibers' other
// transverse axis and walled along z, so that no x-fiber crosses a y-fiber closer than their
// radii. warning: what is left overlapping (empty when every packing separates its disks).
// Progress over the packings; when it asks to stop, no sites (and aborted).
std::vector<std::vector<LatticeSite>> packedSites(const CubeOptions& o, const std::vector<int>& counts,
  std::string& warning, const ProgressFn& progress, bool& aborted)
{
  const double L = o.edgeLength;
  const double half = 0.5 * L;
  std::vector<std::vector<double>> radii(counts.size());
  std::vector<double> area(counts.size(), 0.0);
  for (std::size_t k = 0; k < counts.size(); ++k)
  {
    for (int j = 0; j < counts[k]; ++j)
    {
      radii[k].push_back(cubeFiberRadius(o, static_cast<int>(k), j));
      area[k] += radii[k].back() * radii[k].back();
    }
  }
  std::vector<std::vector<LatticeSite>> sites(counts.size());
  if (counts.size() == 1)
  {
    const DiskPacking p = packDisks(radii[0], DiskDomain{ L, L, true }, o.seed, 6, progress);
    aborted = p.aborted;
    if (aborted || p.centres.size() != radii[0].size())
      return {}; // no sites: a packing that placed no disks is never read (generateCube)
    warning = overlapWarning(o, p, "the cross-section");
    for (const Seed2D& c : p.centres)
      sites[0].push_back({ c.x - half, c.y - half });
    return sites;
  }
  const double total = area[0] + area[1];
  const double h0 = total > 0.0 ? L * area[0] / total : half;
  const auto half0 = [&](double f) { return reportProgress(progress, 0.5 * f); };
  const auto half1 = [&](double f) { return reportProgress(progress, 0.5 + 0.5 * f); };
  const DiskPacking p0 = packDisks(radii[0], DiskDomain{ L, h0, false }, o.seed, 6, half0);
  if (p0.aborted)
  {
    aborted = true;
    return {};
  }
  const DiskPacking p1 = packDisks(radii[1], DiskDomain{ L, L - h0, false }, o.seed, 7, half1);
  if (p1.aborted)
  {
    aborted = true;
    return {};
  }
  if (p0.centres.size() != radii[0].size() || p1.centres.size() != radii[1].size())
    return {}; // the radii could not be packed (validateRadiusDistribution keeps them usable)
  warning = overlapWarning(o, p0, "the slab of population 0");
  if (warning.empty())
    warning = overlapWarning(o, p1, "the slab of population 1");
  // A fiber wider than its slab cannot lie in it without crossing the other population.
  const double heights[2] = { h0, L - h0 };
  for (int k = 0; k < 2; ++k)
  {
    const double widest = radii[k].empty() ? 0.0 : 2.0 * *std::max_element(radii[k].begin(), radii[k].end());
    if (widest > heights[k])
    {
      std::ostringstream w;
      w << "Seeding Lattice: the slab of population " << k << " is " << heights[k]
        << " thick, thinner than its largest fiber's diameter " << widest << " (EdgeLength " << L
        << " is too small for two populations with RadiusSpread " << o.radiusSpread
        << "); the solver starts from overlapping fibers";
      warning = w.str();
    }
  }
  for (const Seed2D& c : p0.centres)
    sites[0].push_back({ c.x - half, c.y - half });
  for (const Seed2D& c : p1.centres)
    sites[1].push_back({ c.y - half + h0, c.x - half });
  return sites;
}

// Moves fiber j of population k from its drawn transverse position (the first two draws of its
// stream) to its site, jittered uniformly in the disc of radius max(0, spacing/2 − r) by the
// stream (seed, 3 + k, 1 + j).
void placeOnSite(const CubeOptions& o, std::size_t k, std::size_t j, const LatticeSite& site, double spacing,
  Fiber& f)
{
  const double half = 0.5 * o.edgeLength;
  const double room = std::max(0.0, 0.5 * spacing - o.fiberRadius);
  const int other1 = static_cast<int>(k + 1) % 3;
  const int other2 = static_cast<int>(k + 2) % 3;
  RandomStream drawn(o.seed, k, j);
  const double t1 = drawn.uniform(-half, half);
  const double t2 = drawn.uniform(-half, half);
  RandomStream jitter(o.seed, 3 + k, 1 + j);
  const double u1 = jitter.uniform();
  const Seed2D offset = randomSeedInDisc(u1, jitter.uniform(), room);
  const double shift1 = site.t1 + offset.x - t1;
  const double shift2 = site.t2 + offset.y - t2;
  for (Vec3& p : f.points)
  {
    p[other1] += shift1;
    p[other2] += shift2;
  }
}
} // namespace

PeriodicCell cubeCell(const CubeOptions& o)
{
  const double half = 0.5 * o.edgeLength;
  return PeriodicCell{ { -half, -half, -half }, { half, half, half } };
}

std::string validateCubeOptions(const CubeOptions& o, int pieces)
{
  std::ostringstream msg;
  const std::string radius = validateRadiusDistribution(o.radiusDistribution, o.radiusSpread);
  if (o.populations < 1 || o.populations > 3)
  {
    msg << "Populations is " << o.populations << ", must be 1, 2 or 3";
  }
  else if (o.numberOfFibers < 0)
  {
    msg << "NumberOfFibers is " << o.numberOfFibers << ", must be >= 0";
  }
  else if (!std::isfinite(o.fiberRadius) || o.fiberRadius <= 0.0)
  {
    msg << "FiberRadius is " << o.fiberRadius << ", must be > 0";
  }
  else if (!radius.empty())
  {
    msg << radius;
  }
  else if (!std::isfinite(o.edgeLength) || o.edgeLength <= 2.0 * o.fiberRadius)
  {
    msg << "EdgeLength is " << o.edgeLength << ", must be > 2 * FiberRadius";
  }
  else if (o.periodic && o.edgeLength < 4.0 * o.fiberRadius)
  {
    // A fiber would touch its own images across the cell.
    msg << "EdgeLength is " << o.edgeLength << ", must be >= two fiber diameters (4 * FiberRadius = "
        << 4.0 * o.fiberRadius << ") for a periodic cell";
  }
  else if (!std::isfinite(o.segmentLength) || o.segmentLength <= 0.0)
  {
    msg << "SegmentLength is " << o.segmentLength << ", must be > 0";
  }
  else if (o.periodic && std::isfinite(o.displacement) &&
    !periodicReachProblem(cubeCell(o), solverLinkReach(o)).empty())
  {
    // The solver's rule (Geometry/PeriodicCell.h) for the longest links it can make of these
    // fibers: a periodic cube the source accepts, the solver with the same SegmentLength accepts.
    msg << "EdgeLength is " << o.edgeLength << ", too small for SegmentLength " << o.segmentLength
        << ", Displacement " << o.displacement << " and FiberRadius " << o.fiberRadius << ": "
        << periodicReachProblem(cubeCell(o), solverLinkReach(o));
  }
  else if (!std::isfinite(o.displacement) || o.displacement < 0.0)
  {
    msg << "Displacement is " << o.displacement << ", must be >= 0";
  }
  else if (o.seeding == CubeSeeding::Lattice && !o.periodic)
  {
    msg << "Seeding is Lattice, which needs Periodic on (a lattice must be commensurate with a "
           "periodic cell)";
  }
  else if (o.seeding != CubeSeeding::Random && o.seeding != CubeSeeding::Lattice)
  {
    msg << "Seeding is " << static_cast<int>(o.seeding) << ", must be 0 (Random) or 1 (Lattice)";
  }
  else if (!std::isfinite(o.volumeFraction) || o.volumeFraction < 0.0 || o.volumeFraction >= 1.0)
  {
    msg << "VolumeFraction is " << o.volumeFraction << ", must be in (0, 1) (0 = use NumberOfFibers)";
  }
  else
  {
    // With VolumeFraction the fibers it takes, counted as generateCube counts them (the upper
    // estimate of fiberCountEstimate assumes the thinnest radius for every fiber, which for a
    // broad spread is orders of magnitude too many); counting stops at kCountedFibers.
    bool atLeast = false;
    const double fibers = o.volumeFraction > 0.0 ? countedFibers(o, atLeast) : fiberCountEstimate(o);
    const double points = fibers * (o.edgeLength / o.segmentLength + 2.0);
    const double share = 1.0 / std::max(1, pieces);
    std::ostringstream what;
    if (o.volumeFraction > 0.0)
      what << "VolumeFraction " << o.volumeFraction << " (" << (atLeast ? "at least " : "") << fibers << " fibers)";
    else
      what << "NumberOfFibers " << fibers;
    what << " with EdgeLength " << o.edgeLength << " and SegmentLength " << o.segmentLength << " (" << points
         << " points";
    if (pieces > 1)
    {
      what << ", a share of 1/" << pieces << " per piece";
    }
    what << ")";
    const std::string problem = checkMemoryBudget(fiberModelBytes(share * fibers, share * points), what.str());
    if (!problem.empty())
    {
      msg << problem << "; it would need too many points";
    }
    else if (o.seeding == CubeSeeding::Lattice && polydisperse(o) && o.populations <= 2)
    {
      // Every piece packs all fibers' disks.
      std::ostringstream packing;
      packing << "Seeding Lattice with RadiusSpread " << o.radiusSpread << " (a disk packing of " << fibers
              << " fibers, ";
      if (o.volumeFraction > 0.0)
        packing << "VolumeFraction " << o.volumeFraction; // the count above is the real one
      else
        packing << "NumberOfFibers " << o.numberOfFibers;
      packing << " with EdgeLength " << o.edgeLength << ", on every piece)";
      msg << checkMemoryBudget(diskPackingBytes(fibers), packing.str());
    }
  }
  return msg.str();
}

int cubePopulationSize(const CubeOptions& o, int k)
{
  return o.numberOfFibers / o.populations + (k < o.numberOfFibers % o.populations ? 1 : 0);
}

FiberModel generateCube(const CubeOptions& o, int piece, int pieces, std::string* warning, const ProgressFn& progress)
{
  const std::vector<int> counts = populationCounts(o);
  std::size_t total = 0;
  for (int c : counts)
  {
    total += static_cast<std::size_t>(c);
  }
  const FiberRange range = pieceRange(total, piece, pieces);
  // Packed sites are not jittered (spacing 0 leaves no room).
  double spacing = 0.0;
  std::vector<std::vector<LatticeSite>> sites;
  std::string packed;
  bool aborted = false;
  if (o.seeding == CubeSeeding::Lattice)
    sites = polydisperse(o) && o.populations <= 2 ? packedSites(o, counts, packed, progress, aborted)
                                                  : shuffledSites(o, counts, spacing);
  if (warning)
    *warning = packed;
  if (aborted)
    return {};
  FiberModel model;
  model.fibers.reserve(range.size());
  // Global order: population by population, fiber j of population k at first(k) + j.
  std::size_t first = 0;
  for (std::size_t k = 0; k < counts.size(); ++k)
  {
    const std::size_t count = static_cast<std::size_t>(counts[k]);
    const std::size_t from = std::max(range.begin, first) - first;
    const std::size_t to = std::min(range.end, first + count);
    for (std::size_t j = from; first + j < to; ++j)
    {
      Fiber f = makeFiber(o, static_cast<int>(k), static_cast<int>(j));
      if (!sites.empty())
      {
        placeOnSite(o, k, j, sites[k][j], spacing, f);
      }
      f.id = static_cast<std::int64_t>(first + j);
      model.fibers.push_back(std::move(f));
    }
    first += count;
  }
  return model;
}

} // namespace fiberpli
