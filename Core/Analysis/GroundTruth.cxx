#include "Analysis/GroundTruth.h"

#include "Section/LinkTable.h"
#include "Section/SectionReach.h"
#include "Util/MemoryBudget.h"
#include "Util/Threads.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace fiberpli
{

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::uint32_t kNoOwner = std::numeric_limits<std::uint32_t>::max();

/// Link-table bins of 16 × 16 voxel columns: a pixel row looks only at the links near it.
constexpr std::int64_t kBinSize = 16;

/// One voxel column of a pixel row's owner buffer (z slowest: index (k·wy + y)·wx + x).
struct OwnerColumn
{
  double* d2;
  std::uint32_t* owner;
  std::int64_t stride; ///< wx·wy, one z step
  std::uint32_t g;

  bool skip(std::int64_t) const { return false; }
  void cover(std::int64_t k, double d2k, double)
  {
    const std::size_t v = static_cast<std::size_t>(k * stride);
    if (ownerWins(d2k, g, d2[v], owner[v] == kNoOwner ? 0 : owner[v]))
    {
      d2[v] = d2k;
      owner[v] = g;
    }
  }
};
} // namespace

Status computeGroundTruth(const FiberModel& model, const PixelGrid& grid,
  const GroundTruthOptions& options, const GridRange& range, GroundTruthMaps& maps,
  const ProgressFn& progress)
{
  std::int64_t nx = 0, ny = 0;
  std::string err = checkPixelGrid(grid, nx, ny);
  if (!err.empty())
  {
    return err;
  }
  err = validatePixelRange(nx, ny, range);
  if (!err.empty())
  {
    return err;
  }
  err = ValueChecks().positive("radius scale", options.radiusScale).error();
  if (!err.empty())
  {
    return err;
  }
  if (options.nPhi < 1 || options.nAlpha < 1)
  {
    std::ostringstream msg;
    msg << "histogram bins " << options.nPhi << " x " << options.nAlpha << " must be >= 1 each";
    return msg.str();
  }
  err = validateModel(model);
  if (!err.empty())
  {
    return err;
  }
  const SectionLattice& lat = grid.lattice;
  const double scale = grid.scale();
  const std::int64_t nz = lat.n[2];
  // The voxel columns of the range (empty when the range is).
  GridRange cols{ 0, 0, 0, 0 };
  if (range.nx() > 0 && range.ny() > 0)
  {
    cols = voxelColumnsOf(grid, range);
  }
  // One pixel row's voxels are held at once per thread.
  const double rowVoxels =
    static_cast<double>(cols.nx()) * std::ceil(1.0 / scale + 1.0) * static_cast<double>(nz);
  if (rowVoxels > 2147483647.0)
  {
    std::ostringstream msg;
    msg << "one pixel row holds " << rowVoxels
        << " voxels; use a larger VoxelSize or a smaller range";
    return msg.str();
  }

  const std::size_t nHist = options.histogram
    ? static_cast<std::size_t>(options.nPhi) * static_cast<std::size_t>(options.nAlpha)
    : 0;
  const int nThreads = resolveThreadCount(options.threads);
  std::size_t linkCount = 0;
  for (const Fiber& f : model.fibers)
  {
    linkCount += f.size() > 1 ? f.size() - 1 : 0;
  }
  // Five maps (and the histograms) of the whole grid, a copy of the range's maps in the caller's
  // output, per thread one pixel row of voxel owners (distance + link id), and the links (with
  // their axes and at least one bin entry each).
  const double pixelBytes =
    static_cast<double>(nx) * static_cast<double>(ny) * (5.0 + static_cast<double>(nHist)) * 8.0;
  const double bytes = pixelBytes + 5.0 * 8.0 * static_cast<double>(range.count()) +
    static_cast<double>(nThreads) * rowVoxels * 12.0 +
    static_cast<double>(linkCount) * (sizeof(SectionLink) + sizeof(Vec3) + sizeof(std::uint32_t));
  std::ostringstream what;
  what << "the ground truth of " << nx << " x " << ny << " pixels (PixelSize " << grid.pixelSize
       << ", VoxelSize " << lat.voxel << ", " << nz << " voxels deep)";
  err = checkMemoryBudget(bytes, what.str());
  if (!err.empty())
  {
    return err;
  }
  const std::size_t npx = static_cast<std::size_t>(nx * ny);
  maps.nx = nx;
  maps.ny = ny;
  for (auto* v : { &maps.fraction, &maps.direction, &maps.inclination, &maps.inclinationSigned,
         &maps.anisotropy })
  {
    v->resize(npx, kNaN);
  }
  maps.histogram.assign(npx * nHist, 0.0);
  if (range.count() <= 0)
  {
    return {};
  }

  // Every bundle is a slot, all of the same scale S: the links in the simulation's order g.
  const std::vector<int> slots = bundlesOf(model);
  LinkTable table;
  buildLinkTable(model, slots, std::vector<double>(slots.size(), options.radiusScale),
    options.maxRadius ? RadiusModel::Max : RadiusModel::Linear, lat, cols, kBinSize, table);
  std::vector<Vec3> axis(table.links.size());
  for (std::size_t g = 0; g < axis.size(); ++g)
  {
    axis[g] = normalized(table.links[g].q - table.links[g].p);
  }
  // Voxel columns of every pixel column, the same for every row.
  std::vector<std::int64_t> spanX(static_cast<std::size_t>(2 * range.nx()));
  for (std::int64_t i = range.i0; i < range.i1; ++i)
  {
    voxelsOfPixel(i, scale, lat.n[0], spanX[static_cast<std::size_t>(2 * (i - range.i0))],
      spanX[static_cast<std::size_t>(2 * (i - range.i0) + 1)]);
  }
  const std::int64_t vx0 = cols.i0, vx1 = cols.i1;
  const std::int64_t rows = range.ny();
  const std::int64_t block = std::max<std::int64_t>(1, rows / 50);

  for (std::int64_t jb = range.j0; jb < range.j1; jb += block)
  {
    const std::int64_t je = std::min(range.j1, jb + block);
#pragma omp parallel for num_threads(nThreads) schedule(dynamic, 1)
    for (std::int64_t j = jb; j < je; ++j)
    {
      std::int64_t vy0, vy1;
      voxelsOfPixel(j, scale, lat.n[1], vy0, vy1);
      const std::int64_t wx = vx1 - vx0, wy = vy1 - vy0;
      const std::size_t nVox = static_cast<std::size_t>(wx * wy * nz);
      std::vector<double> bestD2(nVox, std::numeric_limits<double>::infinity());
      std::vector<std::uint32_t> owner(nVox, kNoOwner);
      const GridRange row{ vx0, vx1, vy0, vy1 };
      std::vector<std::uint32_t> cand;
      candidateLinks(table, row, cand);
      for (const std::uint32_t g : cand)
      {
        forEachCoveredVoxel(table, g, row, nz,
          [&](std::int64_t i, std::int64_t jj)
          {
            const std::size_t v = static_cast<std::size_t>((jj - vy0) * wx + (i - vx0));
            return OwnerColumn{ bestD2.data() + v, owner.data() + v, wx * wy, g };
          });
      }
      TruthAccumulator acc(options.nPhi, options.nAlpha);
      for (std::int64_t i = range.i0; i < range.i1; ++i)
      {
        const std::int64_t ia = spanX[static_cast<std::size_t>(2 * (i - range.i0))];
        const std::int64_t ib = spanX[static_cast<std::size_t>(2 * (i - range.i0) + 1)];
        acc.reset();
        for (std::int64_t k = 0; k < nz; ++k)
        {
          for (std::int64_t jj = vy0; jj < vy1; ++jj)
          {
            for (std::int64_t iv = ia; iv < ib; ++iv)
            {
              const std::uint32_t o =
                owner[static_cast<std::size_t>(((k * wy) + (jj - vy0)) * wx + (iv - vx0))];
              if (o != kNoOwner)
              {
                acc.addTissue(axis[o]);
              }
              else
              {
                acc.addBackground();
              }
            }
          }
        }
        const std::size_t p = static_cast<std::size_t>(i + nx * j);
        const PixelTruth t = acc.result(nHist > 0 ? maps.histogram.data() + p * nHist : nullptr);
        maps.fraction[p] = t.fraction;
        maps.direction[p] = t.direction;
        maps.inclination[p] = t.inclination;
        maps.inclinationSigned[p] = t.inclinationSigned;
        maps.anisotropy[p] = t.anisotropy;
      }
    }
    if (!reportProgress(progress, static_cast<double>(je - range.j0) / static_cast<double>(rows)))
    {
      return Status::stopped();
    }
  }
  return {};
}

TileReach groundTruthReach(
  const PixelGrid& grid, const GroundTruthOptions& options, const GridRange& range)
{
  // The columns computeGroundTruth builds its link table for.
  if (range.nx() < 1 || range.ny() < 1)
  {
    return TileReach();
  }
  return columnsReach(grid.lattice, voxelColumnsOf(grid, range), options.radiusScale);
}

std::vector<double> modelOrientationHistogram(
  const FiberModel& model, int nPhi, int nTheta, bool normalise, bool perSolidAngle)
{
  if (nPhi < 1 || nTheta < 1)
  {
    return {};
  }
  std::vector<double> hist(static_cast<std::size_t>(nPhi) * static_cast<std::size_t>(nTheta), 0.0);
  const double dPhi = 360.0 / nPhi, dTheta = 90.0 / nTheta;
  double total = 0.0;
  for (const Fiber& f : model.fibers)
  {
    for (std::size_t k = 0; k + 1 < f.size(); ++k)
    {
      Vec3 d = f.points[k + 1] - f.points[k];
      const double len = norm(d);
      if (len == 0.0)
      {
        continue;
      }
      if (d.z < 0.0)
      {
        d = -d;                     // θ > 90°: count the antipode on the upper half sphere
        d += Vec3{ 0.0, 0.0, 0.0 }; // no signed zeros: atan2(−0, −0) is −π, not 0
      }
      double phi = std::atan2(d.y, d.x) * 180.0 / M_PI;
      phi = phi < 0.0 ? phi + 360.0 : phi;
      const double theta = std::acos(std::min(1.0, d.z / len)) * 180.0 / M_PI;
      const int ip = std::min(nPhi - 1, static_cast<int>(std::floor(phi / dPhi)));
      const int it = std::min(nTheta - 1, static_cast<int>(std::floor(theta / dTheta)));
      hist[static_cast<std::size_t>(it) * nPhi + ip] += 1.0;
      total += 1.0;
    }
  }
  if ((normalise || perSolidAngle) && total > 0.0)
  {
    for (double& x : hist)
    {
      x /= total;
    }
  }
  if (perSolidAngle)
  {
    const double dPhiRad = dPhi * M_PI / 180.0;
    for (int it = 0; it < nTheta; ++it)
    {
      const double lo = it * dTheta * M_PI / 180.0, hi = (it + 1) * dTheta * M_PI / 180.0;
      const double omega = (std::cos(lo) - std::cos(hi)) * dPhiRad;
      for (int ip = 0; ip < nPhi; ++ip)
      {
        hist[static_cast<std::size_t>(it) * nPhi + ip] /= omega;
      }
    }
  }
  return hist;
}

} // namespace fiberpli
