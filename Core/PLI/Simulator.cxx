#include "PLI/Simulator.h"

#include "PLI/RayMarcher.h"
#include "PLI/Voxeliser.h"
#include "Util/MemoryBudget.h"
#include "Util/Threads.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#ifdef _OPENMP
#include <omp.h>
#endif

namespace fiberpli
{
namespace pli
{

namespace
{
double now()
{
#ifdef _OPENMP
  return omp_get_wtime();
#else
  return 0.0;
#endif
}

std::int64_t floorDiv(std::int64_t a, std::int64_t b)
{
  return a >= 0 ? a / b : -((-a + b - 1) / b);
}

GridRange grow(const GridRange& c, std::int64_t h)
{
  return GridRange{ c.i0 - h, c.i1 + h, c.j0 - h, c.j1 + h };
}
} // namespace

std::int64_t tiltHalo(const SectionLattice& lattice, const std::vector<View>& views, Interp interp)
{
  double th = 0.0;
  for (const View& v : views)
    th = std::max(th, v.theta);
  if (th > 0.0)
    return RayMarcher::lateralReach(lattice.n[2], th) + 2;
  // Untilted rays still read the +1 neighbour of the interpolation stencil.
  return interp == Interp::NN ? 0 : 1;
}

GridRange linkRegion(const SectionLattice& lat, const SimParams& par,
  const std::vector<View>& views, const GridRange& cols)
{
  const std::int64_t halo = tiltHalo(lat, views, par.interp);
  // Links of every column any ray reads: on the tilted sensor the stretched image of cols.
  GridRange region = grow(cols, halo);
  for (const View& v : views)
  {
    const GridRange r = grow(RayMarcher(lat, par, v, LabelProps()).midPlaneColumns(cols), halo);
    region = GridRange{ std::min(region.i0, r.i0), std::max(region.i1, r.i1),
      std::min(region.j0, r.j0), std::max(region.j1, r.j1) };
  }
  return region;
}

double estimateSimulationBytes(const SectionLattice& lat, const SimParams& par,
  const std::vector<View>& views, const GridRange& cols)
{
  const double h = static_cast<double>(tiltHalo(lat, views, par.interp));
  const double B = std::min<double>(par.tile, std::max<double>(cols.nx(), cols.ny()));
  const double threads = resolveThreadCount(par.threads);
  // The tilted sensor's block covers the stretched mid-plane points of the tile (+3: floor, ±1).
  double stretch = 1.0;
  for (const View& v : views)
    stretch = std::max(stretch, v.theta > 0.0 ? v.stretch : 1.0);
  const double side = stretch == 1.0 ? B + 2 * h : B * stretch + 2 * h + 3;
  const double tile = side * side * static_cast<double>(lat.n[2]) * kTileBytesPerVoxel;
  const double outBytes = static_cast<double>(views.size()) * static_cast<double>(cols.nx()) *
    static_cast<double>(cols.ny()) * static_cast<double>(par.rho.size()) * sizeof(double);
  return threads * tile + outBytes;
}

std::string validateSimulation(const SectionLattice& lat, const SimParams& par,
  const std::vector<View>& views, const GridRange& cols)
{
  std::ostringstream m;
  const std::string voxel = ValueChecks().positive("VoxelSize", lat.voxel).error();
  const std::string optics = ValueChecks()
                               .positive("Wavelength", par.wavelengthNm)
                               .atLeast("LightIntensity", par.lightIntensity, 0.0)
                               .positive("StepSize", par.step)
                               .error();
  if (!voxel.empty())
    m << voxel;
  else if (lat.n[0] < 1 || lat.n[1] < 1 || lat.n[2] < 1)
    m << "VolumeOfInterest gives " << lat.n[0] << " x " << lat.n[1] << " x " << lat.n[2]
      << " voxels at VoxelSize " << lat.voxel << ", needs at least one voxel per axis";
  else if (!optics.empty())
    m << optics;
  else if (par.rho.empty())
    m << "NumberOfRotations is 0, needs polarizer angles";
  else if (par.tile < 1)
    m << mustBe("tile size", par.tile, ">= 1");
  else if (cols.nx() < 1 || cols.ny() < 1)
    m << "column range [" << cols.i0 << "," << cols.i1 << ")x[" << cols.j0 << "," << cols.j1
      << ") is empty";
  if (!m.str().empty())
    return m.str();
  for (std::size_t v = 0; v < views.size(); ++v)
  {
    if (!(views[v].theta >= 0.0 && views[v].theta < M_PI / 4.0))
    {
      m << "TiltAngle of view " << v << " is " << views[v].theta * 180.0 / M_PI
        << " deg in tissue, must be in [0, 45)";
      return m.str();
    }
  }
  std::ostringstream what;
  what << "VoxelSize " << lat.voxel << " with VolumeOfInterest (" << lat.n[0] << " x " << lat.n[1]
       << " x " << lat.n[2] << " voxels)";
  const std::string tooBig =
    checkMemoryBudget(estimateSimulationBytes(lat, par, views, cols), what.str());
  if (!tooBig.empty())
    return tooBig + ": increase VoxelSize or reduce the volume";
  // Steps per ray: StepSize far below the voxel size would take forever.
  if (static_cast<double>(lat.n[2]) / par.step > 1e7)
    m << "StepSize " << par.step << " gives more than 1e7 steps per ray";
  return m.str();
}

SimResult simulate(const FiberModel& model, const TissueSpec& spec, const SectionLattice& lat,
  const SimParams& par, const std::vector<View>& views, const GridRange& cols,
  std::vector<Stack>& out, const ProgressFn& progress)
{
  SimResult res;
  res.status.error = validateSimulation(lat, par, views, cols);
  if (!res.status.ok())
    return res;
  const int nrho = static_cast<int>(par.rho.size());
  const std::int64_t halo = tiltHalo(lat, views, par.interp);
  const std::int64_t B = par.tile;
  res.estimatedBytes = static_cast<std::size_t>(estimateSimulationBytes(lat, par, views, cols));

  const LabelProps props = LabelProps::fromSpec(spec);
  std::vector<RayMarcher> marchers;
  for (const View& v : views)
    marchers.emplace_back(lat, par, v, props);
  const GridRange region = linkRegion(lat, par, views, cols);
  LinkTable table;
  tissueLinkTable(model, spec, lat, region, B, table);
  res.estimatedBytes += table.links.size() * sizeof(SectionLink);
  if (table.zeroLengthLinks > 0)
    res.status.warnings.push_back(
      std::to_string(table.zeroLengthLinks) + " zero-length links skipped");
  if (table.unknownBundleFibers > 0)
    res.status.warnings.push_back(
      std::to_string(table.unknownBundleFibers) + " fibers of bundles without layers skipped");

  out.assign(views.size(), Stack());
  for (Stack& s : out)
    s.resize(cols, nrho);

  // Tiles aligned to the global B grid, so a split changes which tile a column is in but never
  // how it is computed.
  std::vector<GridRange> tiles;
  for (std::int64_t ty = floorDiv(cols.j0, B); ty * B < cols.j1; ++ty)
    for (std::int64_t tx = floorDiv(cols.i0, B); tx * B < cols.i1; ++tx)
      tiles.push_back(GridRange{ std::max(cols.i0, tx * B), std::min(cols.i1, (tx + 1) * B),
        std::max(cols.j0, ty * B), std::min(cols.j1, (ty + 1) * B) });

  // Bow-tie of the tilted rays: at depth k a sample lies within (|k + ½ − n_z/2| + 1)·tan θ of its
  // column centre (the +1 covers the z stencil), plus 1 for floor and 1 for the lateral stencil.
  std::vector<std::int64_t> reach(static_cast<std::size_t>(lat.n[2]), halo);
  double tanMax = 0.0;
  for (const View& v : views)
    tanMax = std::max(tanMax, std::tan(v.theta));
  for (std::int64_t k = 0; k < lat.n[2]; ++k)
  {
    const double dz =
      std::fabs(static_cast<double>(k) + 0.5 - 0.5 * static_cast<double>(lat.n[2])) + 1.0;
    reach[static_cast<std::size_t>(k)] =
      std::min<std::int64_t>(halo, static_cast<std::int64_t>(std::ceil(dz * tanMax)) + 2);
  }

  const int threads = resolveThreadCount(par.threads);
  std::vector<TissueBlock> blocks(static_cast<std::size_t>(threads));
  std::vector<double> tVox(static_cast<std::size_t>(threads), 0.0),
    tProp(static_cast<std::size_t>(threads), 0.0);
  std::vector<std::int64_t> nVox(static_cast<std::size_t>(threads), 0),
    nSteps(static_cast<std::size_t>(threads), 0);
  std::vector<std::int64_t> labelled(tiles.size(), 0);
  std::vector<char> overlap(tiles.size(), 0);

  const std::int64_t nt = static_cast<std::int64_t>(tiles.size());
  // Batches keep every thread busy and give about 50 progress reports per run.
  const std::int64_t batch = std::max<std::int64_t>(2 * threads, (nt + 49) / 50);
  for (std::int64_t b0 = 0; b0 < nt; b0 += batch)
  {
    if (!reportProgress(progress, static_cast<double>(b0) / static_cast<double>(nt)))
    {
      res.status.aborted = true;
      out.clear();
      return res;
    }
    const std::int64_t b1 = std::min(nt, b0 + batch);
#pragma omp parallel for schedule(dynamic) num_threads(threads)
    for (std::int64_t ti = b0; ti < b1; ++ti)
    {
#ifdef _OPENMP
      const std::size_t me = static_cast<std::size_t>(omp_get_thread_num());
#else
      const std::size_t me = 0;
#endif
      const GridRange& tile = tiles[static_cast<std::size_t>(ti)];
      TissueBlock& block = blocks[me];
      // Views whose rays cross the mid-plane in the same columns share one block: all of them
      // when registered; on the tilted sensor each stretched view has its own (§4.6).
      std::vector<std::size_t> pending(views.size());
      for (std::size_t v = 0; v < views.size(); ++v)
        pending[v] = v;
      bool first = true;
      while (!pending.empty())
      {
        const double t0 = now();
        const GridRange core = marchers[pending.front()].midPlaneColumns(tile);
        block.reset(grow(core, halo), lat.n[2]);
        VoxeliseStats vs;
        HaloShape shape{ core, reach };
        voxeliseBlock(table, spec, lat, par.lateral, block, vs, &shape);
        overlap[static_cast<std::size_t>(ti)] |= vs.overlap ? 1 : 0;
        // The first block holding the tile's own columns (views[0], untilted, in a PLIPlan).
        if (first && block.contains(tile.i0, tile.j0) && block.contains(tile.i1 - 1, tile.j1 - 1))
        {
          std::int64_t inside = 0;
          for (std::int64_t j = std::max<std::int64_t>(tile.j0, 0); j < std::min(tile.j1, lat.n[1]);
               ++j)
            for (std::int64_t i = std::max<std::int64_t>(tile.i0, 0);
                 i < std::min(tile.i1, lat.n[0]); ++i)
              for (std::int64_t k = 0; k < lat.n[2]; ++k)
                inside += block.label(i, j, k) != 0 ? 1 : 0;
          labelled[static_cast<std::size_t>(ti)] = inside;
          first = false;
        }
        const double t1 = now();
        GridRange clamp = block.cols;
        if (par.lateral == LateralOutside::Background)
          clamp = GridRange{ 0, lat.n[0], 0, lat.n[1] };
        std::vector<std::size_t> later;
        for (std::size_t v : pending)
        {
          const GridRange c = marchers[v].midPlaneColumns(tile);
          if (c.i0 != core.i0 || c.i1 != core.i1 || c.j0 != core.j0 || c.j1 != core.j1)
          {
            later.push_back(v);
            continue;
          }
          for (std::int64_t j = tile.j0; j < tile.j1; ++j)
            for (std::int64_t i = tile.i0; i < tile.i1; ++i)
              marchers[v].march(block, i, j, clamp, &out[v].at(i, j, 0));
          nSteps[me] += marchers[v].numberOfSteps() * tile.nx() * tile.ny();
        }
        pending.swap(later);
        tVox[me] += t1 - t0;
        tProp[me] += now() - t1;
        nVox[me] += block.cols.nx() * block.cols.ny() * lat.n[2];
      }
    }
  }
  reportProgress(progress, 1.0);
  for (int t = 0; t < threads; ++t)
  {
    res.voxeliseCpuSeconds += tVox[static_cast<std::size_t>(t)];
    res.propagateCpuSeconds += tProp[static_cast<std::size_t>(t)];
    res.voxelsVoxelised += nVox[static_cast<std::size_t>(t)];
    res.raySteps += nSteps[static_cast<std::size_t>(t)];
  }
  std::int64_t total = 0;
  for (std::size_t t = 0; t < tiles.size(); ++t)
  {
    total += labelled[t];
    res.overlap = res.overlap || overlap[t] != 0;
  }
  if (total == 0)
  {
    res.emptySection = true;
    res.status.warnings.push_back("no fiber in the section: the image shows background only");
  }
  return res;
}

} // namespace pli
} // namespace fiberpli
