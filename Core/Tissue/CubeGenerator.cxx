#include "Tissue/CubeGenerator.h"

#include "Model/FiberPieces.h"
#include "Tissue/BeadPhasing.h"
#include "Tissue/Beading.h"
#include "Tissue/DiskPacking.h"
#include "Tissue/Dispersion.h"
#include "Tissue/LatticeDispersion.h"
#include "Tissue/LatticeSeeding.h"
#include "Tissue/Seeds.h"
#include "Tissue/Stratification.h"
#include "Util/MemoryBudget.h"
#include "Util/Random.h"
#include "Util/ValueCheck.h"

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
Fiber makeStraightFiber(const CubeOptions& o, int k, int j)
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
  return drawFiberRadius(
    rng, o.fiberRadius, o.radiusSpread, o.radiusDistribution, 0.25 * o.edgeLength);
}

// The span of fiber j of population k: its end-to-end vector (closed: its lattice vector), one
// edge along the population's axis (|axis| edges for a crossing-angle axis of a periodic cell).
// With dispersion the direction is drawn from the Watson distribution about the axis (|cos θ| at
// the population's quantile sequence, the azimuth from stream Dispersion (k, j)); a periodic fiber
// takes a nearby short lattice direction instead, so that it still closes.
Vec3 fiberSpan(const CubeOptions& o, int k, int j)
{
  const PopulationAxis axis = cubePopulationAxes(o)[static_cast<std::size_t>(k)];
  if (!o.realism.dispersed())
    return o.edgeLength * axis.lattice;
  const auto group = static_cast<std::uint64_t>(k);
  const double offset =
    shapeStream(o.seed, ShapeFeature::Dispersion, group, kGroupStream).uniform();
  const double u1 = dispersionQuantile(offset, static_cast<std::uint64_t>(j));
  const double u2 =
    shapeStream(o.seed, ShapeFeature::Dispersion, group, static_cast<std::uint64_t>(j)).uniform();
  if (o.periodic)
  {
    const double kappa =
      latticeDispersionKappa(axis, o.realism.dispersionC2, o.seed, static_cast<std::uint64_t>(k));
    return o.edgeLength * latticeDispersedDirection(axis, *watsonTableForKappa(kappa), u1, u2);
  }
  return o.edgeLength *
    watsonDirection(axis.direction, normalized(axis.across1), normalized(axis.across2),
      *watsonTableForC2(o.realism.dispersionC2), u1, u2);
}

// Fiber j of population k is not today's straight fiber of n points: it undulates, is dispersed,
// or its population runs along a crossing-angle axis.
bool reshaped(const CubeOptions& o, int k)
{
  return o.realism.undulating() || o.realism.dispersed() ||
    !cubePopulationAxes(o)[static_cast<std::size_t>(k)].standard;
}

// The point count of a fiber: the straight one's, or with undulation spread ≈ SegmentLength apart
// along the longer path.
std::size_t shapedPointCount(const CubeOptions& o, int k, int j)
{
  if (!reshaped(o, k))
    return static_cast<std::size_t>(pointsPerFiber(o));
  return undulatedPointCount(
    norm(fiberSpan(o, k, j)), o.realism.tortuosity, o.segmentLength, o.periodic ? 3 : 2);
}

// The beading profile of fiber j of population k on the nominal arc positions of its n points
// (equally spaced over its target path length τ·|span|), stream Beading (k, j).
BeadingProfile cubeBeading(const CubeOptions& o, int k, int j, std::size_t n)
{
  const double length = o.realism.tortuosity * norm(fiberSpan(o, k, j));
  std::vector<double> arc(n);
  for (std::size_t i = 0; i < n; ++i)
    arc[i] = length * static_cast<double>(i) / static_cast<double>(n - 1);
  RandomStream rng = shapeStream(
    o.seed, ShapeFeature::Beading, static_cast<std::uint64_t>(k), static_cast<std::uint64_t>(j));
  return drawBeading(rng, arc, o.realism.beadingLength, o.realism.beadingCV, o.periodic);
}

// The volume a fiber adds to the volume-fraction count: π r² L for a straight fiber (as always);
// with shape knobs the capsules' Σ π ρ_link² · link length of its target path (ρ_link the larger
// radius of the link's two points, as the solver's volume_fraction counts).
double fiberVolume(const CubeOptions& o, int k, int j)
{
  const double r = cubeFiberRadius(o, k, j);
  if (!o.realism.beaded() && !reshaped(o, k))
    return M_PI * r * r * o.edgeLength;
  const std::size_t n = shapedPointCount(o, k, j);
  const double length = o.realism.tortuosity * norm(fiberSpan(o, k, j));
  if (!o.realism.beaded())
    return M_PI * r * r * length;
  const std::vector<double> f = beadingFactors(cubeBeading(o, k, j, n));
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    const double rho = r * std::max(f[i], f[i + 1]);
    sum += rho * rho;
  }
  return M_PI * sum * length / static_cast<double>(n - 1);
}

// The fiber with its shape knobs: undulated (and dispersed) points from cubeFiberShape, or the
// straight fiber; then the beaded radii.
Fiber makeFiber(const CubeOptions& o, int k, int j, bool* reached, const Vec3& fieldShift = {},
  std::size_t beadShift = 0)
{
  Fiber f;
  if (reshaped(o, k))
  {
    const FiberShape shape = cubeFiberShape(o, k, j, fieldShift);
    if (reached)
      *reached = shape.reached;
    f.bundle = k;
    f.points = shape.points();
    f.radii.assign(f.points.size(), shape.radius);
  }
  else
  {
    f = makeStraightFiber(o, k, j);
  }
  if (o.realism.beaded())
  {
    const std::vector<double> factor = beadingFactors(cubeBeading(o, k, j, f.points.size()));
    // A closed fiber's profile turned by beadShift points (its last point repeats the first).
    const std::size_t m = o.periodic ? factor.size() - 1 : factor.size();
    for (std::size_t i = 0; i < f.radii.size(); ++i)
      f.radii[i] *= beadShift == 0 ? factor[i] : factor[(i % m + beadShift) % m];
  }
  return f;
}

// PopulationShares that differ from today's even split (empty or all equal is today's).
bool customShares(const CubeOptions& o)
{
  if (static_cast<int>(o.populationShares.size()) < o.populations)
    return false;
  for (int k = 1; k < o.populations; ++k)
    if (o.populationShares[static_cast<std::size_t>(k)] != o.populationShares[0])
      return true;
  return false;
}

// The shares of the populations, summing to 1.
std::vector<double> normalizedShares(const CubeOptions& o)
{
  std::vector<double> w(o.populationShares.begin(), o.populationShares.begin() + o.populations);
  double sum = 0.0;
  for (double x : w)
    sum += x;
  for (double& x : w)
    x /= sum;
  return w;
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
  if (customShares(o))
  {
    // The next fiber goes to the population furthest below its share of the volume (ties: the
    // lower index), so every population ends within one fiber of its share.
    const std::vector<double> w = normalizedShares(o);
    std::vector<double> byPopulation(counts.size(), 0.0);
    for (int i = 0; i < bound && volume < reached; ++i)
    {
      std::size_t k = 0;
      for (std::size_t q = 1; q < counts.size(); ++q)
        if (byPopulation[q] / w[q] < byPopulation[k] / w[k])
          k = q;
      const double v = fiberVolume(o, static_cast<int>(k), counts[k]);
      byPopulation[k] += v;
      volume += v;
      ++counts[k];
    }
    return counts;
  }
  for (int i = 0; i < bound && volume < reached; ++i)
  {
    const int k = i % o.populations;
    volume += fiberVolume(o, k, i / o.populations);
    ++counts[static_cast<std::size_t>(k)];
  }
  return counts;
}

// The fibers a volume fraction takes (populationCounts' rule), counted up to kCountedFibers:
// beyond that `atLeast` is set and the count is a lower bound (enough for the memory check).
constexpr double kCountedFibers = 1e6;
double countedFibers(const CubeOptions& o, bool& atLeast)
{
  const double target =
    o.volumeFraction * o.edgeLength * o.edgeLength * o.edgeLength * (1.0 - 1e-12);
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
std::vector<std::vector<LatticeSite>> shuffledSites(
  const CubeOptions& o, const std::vector<int>& counts, double& spacing)
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
  w << "Seeding Lattice: the radii could not be separated in " << where << " (packing scale "
    << p.scale << " < 1 reached, RadiusSpread " << o.radiusSpread << ", " << p.centres.size()
    << " fibers";
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
std::vector<std::vector<LatticeSite>> packedSites(const CubeOptions& o,
  const std::vector<int>& counts, std::string& warning, const ProgressFn& progress, bool& aborted)
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
    const double widest =
      radii[k].empty() ? 0.0 : 2.0 * *std::max_element(radii[k].begin(), radii[k].end());
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

// The transverse position fiber j of population k was drawn at: the first two numbers of its
// stream, along the axes (k + 1) mod 3 and (k + 2) mod 3 (Seed2D x, y).
Seed2D drawnTransverse(const CubeOptions& o, std::size_t k, std::size_t j)
{
  const double half = 0.5 * o.edgeLength;
  RandomStream drawn(o.seed, k, j);
  const double t1 = drawn.uniform(-half, half);
  return { t1, drawn.uniform(-half, half) };
}

// Moves fiber f of population k rigidly across its axis from `from` to `to` (transverse
// coordinates along the axes (k + 1) mod 3 and (k + 2) mod 3).
void moveAcross(std::size_t k, const Seed2D& from, const Seed2D& to, Fiber& f)
{
  const int other1 = static_cast<int>(k + 1) % 3;
  const int other2 = static_cast<int>(k + 2) % 3;
  const double shift1 = to.x - from.x;
  const double shift2 = to.y - from.y;
  for (Vec3& p : f.points)
  {
    p[other1] += shift1;
    p[other2] += shift2;
  }
}

// Moves fiber j of population k from its drawn transverse position to its site, jittered
// uniformly in the disc of radius max(0, spacing/2 − r) by the stream (seed, 3 + k, 1 + j).
void placeOnSite(const CubeOptions& o, std::size_t k, std::size_t j, const LatticeSite& site,
  double spacing, Fiber& f)
{
  const double room = std::max(0.0, 0.5 * spacing - o.fiberRadius);
  RandomStream jitter(o.seed, 3 + k, 1 + j);
  const double u1 = jitter.uniform();
  const Seed2D offset = randomSeedInDisc(u1, jitter.uniform(), room);
  moveAcross(k, drawnTransverse(o, k, j), { site.t1 + offset.x, site.t2 + offset.y }, f);
}

// Random seeding with Arrangement Interwoven: fiber j of population k (along a coordinate axis) is
// moved from its drawn transverse position into its stratum (Tissue/Stratification.h), the drawn
// position's fraction of the edge kept inside the stratum.
void placeInStratum(
  const CubeOptions& o, std::size_t k, std::size_t j, int stratum, int perSide, Fiber& f)
{
  const Seed2D drawn = drawnTransverse(o, k, j);
  moveAcross(k, drawn,
    { intoStratum(drawn.x, stratum % perSide, perSide, o.edgeLength),
      intoStratum(drawn.y, stratum / perSide, perSide, o.edgeLength) },
    f);
}

// The strata of every population for placeInStratum, balanced by the fibers' volumes (empty lists
// where fibers stay where drawn):
// Random seeding with Arrangement Interwoven, populations along a coordinate axis (a crossing-angle
// population wraps obliquely through the cell and spreads by itself).
std::vector<std::vector<int>> populationStrata(const CubeOptions& o, const std::vector<int>& counts)
{
  std::vector<std::vector<int>> strata(counts.size());
  if (o.seeding != CubeSeeding::Random || o.arrangement != CubeArrangement::Interwoven)
    return strata;
  const std::vector<PopulationAxis> axes = cubePopulationAxes(o);
  for (std::size_t k = 0; k < counts.size(); ++k)
  {
    if (!axes[k].standard)
      continue;
    std::vector<double> volumes(static_cast<std::size_t>(counts[k]));
    for (std::size_t j = 0; j < volumes.size(); ++j)
      volumes[j] = fiberVolume(o, static_cast<int>(k), static_cast<int>(j));
    strata[k] = assignStrata(
      volumes, strataPerSide(volumes.size()), o.seed, shapeStreamKey(ShapeFeature::Stratum, k));
  }
  return strata;
}

// Lattice seeding by a disk packing (packedSites) rather than the lattice: one population with
// varying radii; two with varying radii (slabs) unless Interwoven is asked for, or with Sheets.
bool packsDisks(const CubeOptions& o)
{
  if (o.populations == 2 && o.arrangement == CubeArrangement::Sheets)
    return true;
  if (o.populations == 2 && o.arrangement == CubeArrangement::Interwoven)
    return false;
  return polydisperse(o) && o.populations <= 2;
}

// Sheets with Random seeding: the z-range [lo, hi] of population 0 and of population 1 (lo0, hi0,
// lo1, hi1), population 0 at the bottom, the thickness by the shares of the fiber cross-section
// (Σ r², as the slabs of the polydisperse Lattice seeding).
std::vector<double> sheetHeights(const CubeOptions& o, const std::vector<int>& counts)
{
  double area[2] = { 0.0, 0.0 };
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < counts[static_cast<std::size_t>(k)]; ++j)
    {
      const double r = cubeFiberRadius(o, k, j);
      area[k] += r * r;
    }
  const double L = o.edgeLength;
  const double h0 = area[0] + area[1] > 0.0 ? L * area[0] / (area[0] + area[1]) : 0.5 * L;
  return { -0.5 * L, -0.5 * L + h0, -0.5 * L + h0, 0.5 * L };
}

// Moves fiber j of population k (0 or 1; both axes lie in the x–y plane) along z from its drawn
// position into its sheet: the drawn z ∈ [−L/2, L/2) maps linearly onto the sheet, less the
// fiber's radius at both sides.
void placeInSheet(
  const CubeOptions& o, std::size_t k, std::size_t j, const std::vector<double>& sheets, Fiber& f)
{
  const double half = 0.5 * o.edgeLength;
  const Seed2D drawn = drawnTransverse(o, k, j);
  // population 0: (y, z) = (t1, t2); population 1: (z, x) = (t1, t2)
  const double z = k == 0 ? drawn.y : drawn.x;
  const double r = std::min(cubeFiberRadius(o, static_cast<int>(k), static_cast<int>(j)),
    0.5 * (sheets[2 * k + 1] - sheets[2 * k]));
  const double lo = sheets[2 * k] + r, hi = sheets[2 * k + 1] - r;
  const double moved = lo + (z + half) / o.edgeLength * (hi - lo);
  for (Vec3& p : f.points)
    p.z += moved - z;
}
} // namespace

FiberShape cubeFiberShape(const CubeOptions& o, int k, int j, const Vec3& fieldShift)
{
  const double half = 0.5 * o.edgeLength;
  FiberShape shape;
  // The transverse position as the straight fiber draws it (the first two numbers of its stream).
  RandomStream rng(o.seed, static_cast<std::uint64_t>(k), static_cast<std::uint64_t>(j));
  Vec3 start;
  start[k] = -half;
  start[(k + 1) % 3] = rng.uniform(-half, half);
  start[(k + 2) % 3] = rng.uniform(-half, half);
  // A population along a crossing-angle axis: the straight fiber's start plane would hold all of
  // its lines (an axis in that plane) or not spread them evenly, so the position along coordinate
  // k is drawn too (stream Placement), making the start uniform in the cell.
  if (!cubePopulationAxes(o)[static_cast<std::size_t>(k)].standard)
  {
    RandomStream place = shapeStream(o.seed, ShapeFeature::Placement, static_cast<std::uint64_t>(k),
      static_cast<std::uint64_t>(j));
    start[k] = place.uniform(-half, half);
  }
  const Vec3 span = fiberSpan(o, k, j);
  // An open dispersed fiber is tilted about its midpoint (the straight fiber's centre); a periodic
  // one starts where the straight one does.
  if (!o.periodic)
  {
    Vec3 mid = start;
    if (cubePopulationAxes(o)[static_cast<std::size_t>(k)].standard)
      mid[k] = 0.0;
    start = mid - 0.5 * span;
  }
  shape.base = straightBasePath(start, span, o.periodic);
  shape.pointCount = shapedPointCount(o, k, j);
  shape.radius = cubeFiberRadius(o, k, j);
  RandomStream jitter = shapeStream(
    o.seed, ShapeFeature::Jitter, static_cast<std::uint64_t>(k), static_cast<std::uint64_t>(j));
  shape.jitter = drawJitter(jitter, shape.pointCount, o.displacement, o.periodic);
  if (o.realism.undulating())
  {
    if (o.undulationCoherence > 0.0)
    {
      // The population's field (its own stream), sampled along this fiber.
      RandomStream waves =
        shapeStream(o.seed, ShapeFeature::Undulation, static_cast<std::uint64_t>(k), kGroupStream);
      const Vec3 axis = cubePopulationAxes(o)[static_cast<std::size_t>(k)].direction;
      Vec3 e1, e2;
      e1[(k + 1) % 3] = 1.0;
      e2[(k + 2) % 3] = 1.0;
      shape.undulation = sampleUndulationField(
        drawUndulationField(waves, axis, e1, e2, o.realism.undulationWavelength,
          o.undulationCoherence, o.periodic ? o.edgeLength : 0.0),
        shape.base.points.front() + fieldShift, span);
    }
    else
    {
      RandomStream modes = shapeStream(o.seed, ShapeFeature::Undulation,
        static_cast<std::uint64_t>(k), static_cast<std::uint64_t>(j));
      shape.undulation =
        drawUndulation(modes, norm(span), o.realism.undulationWavelength, o.periodic);
    }
    shape.reached = calibrateUndulation(
      shape.base, shape.undulation, o.realism.tortuosity, shape.pointCount, &shape.jitter);
  }
  return shape;
}

std::vector<double> cubeDispersionC2(const CubeOptions& o)
{
  const std::vector<int> counts = populationCounts(o);
  std::vector<double> c2(counts.size(), 1.0);
  for (std::size_t k = 0; k < counts.size(); ++k)
  {
    if (counts[k] == 0 || !o.realism.dispersed())
      continue;
    const Vec3 axis = cubePopulationAxes(o)[k].direction;
    double sum = 0.0;
    for (int j = 0; j < counts[k]; ++j)
    {
      const double c = dot(normalized(fiberSpan(o, static_cast<int>(k), j)), axis);
      sum += c * c;
    }
    c2[k] = sum / counts[k];
  }
  return c2;
}

PeriodicCell cubeCell(const CubeOptions& o)
{
  const double half = 0.5 * o.edgeLength;
  return PeriodicCell{ { -half, -half, -half }, { half, half, half } };
}

namespace
{
// Empty when the used PopulationShares are usable: finite and > 0 (and so a positive sum).
std::string sharesProblem(const CubeOptions& o)
{
  if (o.populationShares.empty())
    return {};
  std::ostringstream msg;
  if (static_cast<int>(o.populationShares.size()) < o.populations)
  {
    msg << "PopulationShares has " << o.populationShares.size() << " values for " << o.populations
        << " populations";
    return msg.str();
  }
  for (int k = 0; k < o.populations; ++k)
  {
    const double w = o.populationShares[static_cast<std::size_t>(k)];
    if (!std::isfinite(w) || w <= 0.0)
    {
      return mustBe("PopulationShares value " + formatNumber(k), w, "> 0");
    }
  }
  return {};
}
} // namespace

namespace
{
// The messages for a seeding or arrangement outside its enum (a Core caller may cast any int).
std::string seedingProblem(const CubeOptions& o)
{
  CubeSeeding known;
  return cubeSeedingFromCode(static_cast<int>(o.seeding), known);
}

std::string arrangementProblem(const CubeOptions& o)
{
  CubeArrangement known;
  return cubeArrangementFromCode(static_cast<int>(o.arrangement), known);
}

// The values that are wrong on their own, whatever the others are, all of them: a user who typed
// several bad values learns of all at once instead of one per Apply.
std::string independentProblems(const CubeOptions& o)
{
  std::vector<std::string> problems;
  const auto add = [&problems](bool bad, const std::string& problem)
  {
    if (bad)
    {
      problems.push_back(problem);
    }
  };
  const auto finite = [](double v) { return std::isfinite(v); };
  add(o.populations < 1 || o.populations > 3, mustBe("Populations", o.populations, "1, 2 or 3"));
  add(o.numberOfFibers < 0, mustBe("NumberOfFibers", o.numberOfFibers, ">= 0"));
  add(!finite(o.fiberRadius) || o.fiberRadius <= 0.0, mustBe("FiberRadius", o.fiberRadius, "> 0"));
  add(!finite(o.edgeLength) || o.edgeLength <= 0.0,
    mustBe("EdgeLength", o.edgeLength, "> 2 * FiberRadius"));
  add(!finite(o.segmentLength) || o.segmentLength <= 0.0,
    mustBe("SegmentLength", o.segmentLength, "> 0"));
  add(!finite(o.displacement) || o.displacement < 0.0,
    mustBe("Displacement", o.displacement, ">= 0"));
  const std::string seedingCode = seedingProblem(o);
  add(!seedingCode.empty(), seedingCode);
  add(!finite(o.volumeFraction) || o.volumeFraction < 0.0 || o.volumeFraction >= 1.0,
    mustBe("VolumeFraction", o.volumeFraction, "in (0, 1) (0 = use NumberOfFibers)"));
  add(!finite(o.crossingAngle) || o.crossingAngle < 0.0 || o.crossingAngle > 90.0,
    mustBe("CrossingAngle", o.crossingAngle, "in [0, 90] degrees"));
  add(!finite(o.undulationCoherence) || o.undulationCoherence < 0.0,
    mustBe("UndulationCoherence", o.undulationCoherence, ">= 0 µm (0 = off)"));
  const std::string arrangementCode = arrangementProblem(o);
  add(!arrangementCode.empty(), arrangementCode);
  std::string all;
  for (const std::string& p : problems)
  {
    all += (all.empty() ? "" : "; ") + p;
  }
  return all;
}
} // namespace

std::string validateCubeOptions(const CubeOptions& o, int pieces)
{
  // Several wrong values: all named in one message. One alone: the checks below say it in the
  // same words, after the rules that depend on other values.
  const std::string independent = independentProblems(o);
  if (independent.find("; ") != std::string::npos)
  {
    return independent;
  }
  const std::string seedingCode = seedingProblem(o);
  const std::string arrangementCode = arrangementProblem(o);
  std::ostringstream msg;
  const std::string radius = validateRadiusDistribution(o.radiusDistribution, o.radiusSpread);
  if (o.populations < 1 || o.populations > 3)
  {
    msg << mustBe("Populations", o.populations, "1, 2 or 3");
  }
  else if (o.numberOfFibers < 0)
  {
    msg << mustBe("NumberOfFibers", o.numberOfFibers, ">= 0");
  }
  else if (!std::isfinite(o.fiberRadius) || o.fiberRadius <= 0.0)
  {
    msg << mustBe("FiberRadius", o.fiberRadius, "> 0");
  }
  else if (!radius.empty())
  {
    msg << radius;
  }
  else if (!std::isfinite(o.edgeLength) || o.edgeLength <= 2.0 * o.fiberRadius)
  {
    msg << mustBe("EdgeLength", o.edgeLength, "> 2 * FiberRadius");
  }
  else if (o.periodic && o.edgeLength < 4.0 * o.fiberRadius)
  {
    // A fiber would touch its own images across the cell.
    msg << mustBe("EdgeLength", o.edgeLength,
      ">= two fiber diameters (4 * FiberRadius = " + formatNumber(4.0 * o.fiberRadius) +
        ") for a periodic cell");
  }
  else if (!std::isfinite(o.segmentLength) || o.segmentLength <= 0.0)
  {
    msg << mustBe("SegmentLength", o.segmentLength, "> 0");
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
    msg << mustBe("Displacement", o.displacement, ">= 0");
  }
  else if (o.seeding == CubeSeeding::Lattice && !o.periodic)
  {
    msg << "Seeding is Lattice, which needs Periodic on (a lattice must be commensurate with a "
           "periodic cell)";
  }
  else if (!seedingCode.empty())
  {
    msg << seedingCode;
  }
  else if (!std::isfinite(o.volumeFraction) || o.volumeFraction < 0.0 || o.volumeFraction >= 1.0)
  {
    msg << mustBe("VolumeFraction", o.volumeFraction, "in (0, 1) (0 = use NumberOfFibers)");
  }
  else if (!validateShapeOptions(o.realism).empty())
  {
    msg << validateShapeOptions(o.realism);
  }
  else if (!std::isfinite(o.crossingAngle) || o.crossingAngle < 0.0 || o.crossingAngle > 90.0)
  {
    msg << mustBe("CrossingAngle", o.crossingAngle, "in [0, 90] degrees");
  }
  else if (!std::isfinite(o.undulationCoherence) || o.undulationCoherence < 0.0)
  {
    msg << mustBe("UndulationCoherence", o.undulationCoherence, ">= 0 µm (0 = off)");
  }
  else if (o.undulationCoherence > 0.0 && o.crossingAngle != 90.0 && o.populations >= 2)
  {
    msg << "UndulationCoherence is " << o.undulationCoherence << " with CrossingAngle "
        << o.crossingAngle
        << ", which needs every population along a coordinate axis (CrossingAngle 90)";
  }
  else if (o.crossingAngle != 90.0 && o.populations >= 2 && o.seeding == CubeSeeding::Lattice)
  {
    msg << "CrossingAngle is " << o.crossingAngle
        << ", which needs Seeding Random (the lattices are built "
           "for perpendicular populations)";
  }
  else if (!sharesProblem(o).empty())
  {
    msg << sharesProblem(o);
  }
  else if (!arrangementCode.empty())
  {
    msg << arrangementCode;
  }
  else if (o.arrangement == CubeArrangement::Sheets && o.populations != 2)
  {
    msg << "Arrangement is Sheets, which needs Populations 2 (it is " << o.populations << ")";
  }
  else
  {
    // With VolumeFraction the fibers it takes, counted as generateCube counts them (the upper
    // estimate of fiberCountEstimate assumes the thinnest radius for every fiber, which for a
    // broad spread is orders of magnitude too many); counting stops at kCountedFibers.
    bool atLeast = false;
    const double fibers =
      o.volumeFraction > 0.0 ? countedFibers(o, atLeast) : fiberCountEstimate(o);
    // Fibers along a crossing-angle axis span |axis| edges, dispersed periodic ones up to
    // kMaxDispersionPeriods times that; with a volume fraction longer fibers are fewer, so only a
    // fixed count needs the factor.
    double span = 1.0;
    for (const PopulationAxis& a : cubePopulationAxes(o))
      span = std::max(span, norm(a.lattice));
    if (o.realism.dispersed() && o.periodic)
      span *= kMaxDispersionPeriods;
    if (o.volumeFraction > 0.0)
      span = 1.0;
    const double points =
      fibers * (o.realism.tortuosity * span * o.edgeLength / o.segmentLength + 2.0);
    const double share = 1.0 / std::max(1, pieces);
    std::ostringstream what;
    if (o.volumeFraction > 0.0)
      what << "VolumeFraction " << o.volumeFraction << " (" << (atLeast ? "at least " : "")
           << fibers << " fibers)";
    else
      what << "NumberOfFibers " << fibers;
    what << " with EdgeLength " << o.edgeLength << " and SegmentLength " << o.segmentLength << " ("
         << points << " points";
    if (pieces > 1)
    {
      what << ", a share of 1/" << pieces << " per piece";
    }
    what << ")";
    const std::string problem =
      checkMemoryBudget(fiberModelBytes(share * fibers, share * points), what.str());
    if (!problem.empty())
    {
      msg << problem << "; it would need too many points";
    }
    else if (o.seeding == CubeSeeding::Lattice && packsDisks(o))
    {
      // Every piece packs all fibers' disks.
      std::ostringstream packing;
      packing << "Seeding Lattice with RadiusSpread " << o.radiusSpread << " (a disk packing of "
              << fibers << " fibers, ";
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
  if (!customShares(o))
    return o.numberOfFibers / o.populations + (k < o.numberOfFibers % o.populations ? 1 : 0);
  // Largest remainder: the floors of N·w, the fibers left to the largest fractions (ties: lower k).
  const std::vector<double> w = normalizedShares(o);
  std::vector<int> counts(w.size());
  std::vector<double> rest(w.size());
  int left = o.numberOfFibers;
  for (std::size_t q = 0; q < w.size(); ++q)
  {
    const double exact = o.numberOfFibers * w[q];
    counts[q] = static_cast<int>(std::floor(exact));
    rest[q] = exact - counts[q];
    left -= counts[q];
  }
  for (; left > 0; --left)
  {
    std::size_t best = 0;
    for (std::size_t q = 1; q < w.size(); ++q)
      if (rest[q] > rest[best])
        best = q;
    ++counts[best];
    rest[best] = -1.0;
  }
  return counts[static_cast<std::size_t>(k)];
}

const char* cubeArrangementName(CubeArrangement a)
{
  switch (a)
  {
    case CubeArrangement::Auto:
      return "Auto";
    case CubeArrangement::Interwoven:
      return "Interwoven";
    case CubeArrangement::Sheets:
      return "Sheets";
  }
  return "Unknown";
}

std::vector<PopulationAxis> cubePopulationAxes(const CubeOptions& o)
{
  return populationAxes(o.populations, o.crossingAngle, o.periodic);
}

FiberModel generateCube(
  const CubeOptions& o, int piece, int pieces, std::string* warning, const ProgressFn& progress)
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
  // Progress: the disk packing (when there is one) the first 70 %, the fibers' points the rest.
  const bool packing = o.seeding == CubeSeeding::Lattice && packsDisks(o);
  const double made = packing ? 0.7 : 0.0;
  const ProgressFn packingProgress = [&](double f) { return reportProgress(progress, made * f); };
  if (o.seeding == CubeSeeding::Lattice)
    sites = packing ? packedSites(o, counts, packed, packingProgress, aborted)
                    : shuffledSites(o, counts, spacing);
  const std::vector<double> sheets =
    o.seeding == CubeSeeding::Random && o.arrangement == CubeArrangement::Sheets
    ? sheetHeights(o, counts)
    : std::vector<double>{};
  const std::vector<std::vector<int>> strata = populationStrata(o, counts);
  // Bead phases of every fiber (every piece computes all of them: a fiber's phase depends on its
  // neighbours').
  std::vector<std::vector<std::size_t>> phases;
  if (o.beadPhasing && o.periodic && o.realism.beaded() && !sites.empty())
  {
    for (std::size_t k = 0; k < counts.size(); ++k)
    {
      std::vector<std::vector<double>> radii;
      std::vector<Seed2D> centres;
      for (int j = 0; j < counts[k]; ++j)
      {
        const int kk = static_cast<int>(k);
        const std::size_t n = shapedPointCount(o, kk, j);
        std::vector<double> r = beadingFactors(cubeBeading(o, kk, j, n));
        r.pop_back();
        const double radius = cubeFiberRadius(o, kk, j);
        for (double& x : r)
          x *= radius;
        radii.push_back(std::move(r));
        centres.push_back(
          { sites[k][static_cast<std::size_t>(j)].t1, sites[k][static_cast<std::size_t>(j)].t2 });
      }
      phases.push_back(beadPhases(radii, centres, o.edgeLength));
    }
  }
  if (warning)
    *warning = packed;
  if (aborted)
    return {};
  FiberModel model;
  model.fibers.reserve(range.size());
  std::size_t unreached = 0;
  // Global order: population by population, fiber j of population k at first(k) + j.
  std::size_t first = 0;
  for (std::size_t k = 0; k < counts.size(); ++k)
  {
    const std::size_t count = static_cast<std::size_t>(counts[k]);
    const std::size_t from = std::max(range.begin, first) - first;
    const std::size_t to = std::min(range.end, first + count);
    for (std::size_t j = from; first + j < to; ++j)
    {
      // Every 256 fibers: a (100 µm)^3 cell of thousands of fibers takes seconds here.
      const std::size_t done = model.fibers.size();
      if (done % 256 == 0 && done > 0 &&
        !reportProgress(progress,
          made + (1.0 - made) * static_cast<double>(done) / static_cast<double>(range.size())))
        return {};
      bool reached = true;
      const std::size_t beadShift = phases.empty() ? 0 : phases[k][j];
      Fiber f = makeFiber(o, static_cast<int>(k), static_cast<int>(j), &reached, {}, beadShift);
      const auto place = [&](Fiber& g)
      {
        if (!sites.empty())
        {
          placeOnSite(o, k, j, sites[k][j], spacing, g);
        }
        if (!sheets.empty())
        {
          placeInSheet(o, k, j, sheets, g);
        }
        if (!strata[k].empty())
        {
          placeInStratum(o, k, j, strata[k][j], strataPerSide(count), g);
        }
      };
      if (o.undulationCoherence > 0.0 && o.realism.undulating())
      {
        // A shared field is sampled where the fiber ends up: the seeding's translation first.
        const Vec3 drawn = f.points.front();
        place(f);
        const Vec3 shift = f.points.front() - drawn;
        f = makeFiber(o, static_cast<int>(k), static_cast<int>(j), &reached, shift, beadShift);
      }
      unreached += reached ? 0 : 1;
      place(f);
      f.id = static_cast<std::int64_t>(first + j);
      model.fibers.push_back(std::move(f));
    }
    first += count;
  }
  if (warning && !shapeWarnings(o.realism, o.segmentLength).empty())
    *warning += (warning->empty() ? "" : "; ") + shapeWarnings(o.realism, o.segmentLength);
  if (warning && unreached > 0)
  {
    std::ostringstream w;
    w << (warning->empty() ? "" : "; ") << "Tortuosity " << o.realism.tortuosity
      << ": the Displacement " << o.displacement << " alone makes " << unreached
      << " fiber(s) of this piece longer than that, left "
      << "without undulation (lower Displacement, or raise Tortuosity)";
    *warning += w.str();
  }
  return model;
}

} // namespace fiberpli
