#include "Analysis/GroundTruth.h"

#include "Util/MemoryBudget.h"
#include "Util/Threads.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace fiberpli
{

namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Link
{
  Vec3 p, ax;          // start and Q − P
  double l2, rP, rQ;   // |ax|², radii
  Vec3 lo, hi;         // AABB grown by S·max(rP, rQ)
  Vec3 axis;           // unit(Q − P)
  std::int64_t g;      // global link index: bundle order, fiber order, link order
};

// docs/pli-simulation.md §5.2: the one integer function shared with the simulator.
std::int64_t pixelOf(std::int64_t voxel, double scale)
{
  return static_cast<std::int64_t>(std::floor((static_cast<double>(voxel) + 0.5) * scale));
}

// Voxel indices [v0, v1) whose pixel lies in [p0, p1): contiguous because pixelOf is monotonic.
void voxelSpan(std::int64_t nVox, double scale, std::int64_t p0, std::int64_t p1, std::int64_t& v0, std::int64_t& v1)
{
  v0 = nVox;
  v1 = nVox;
  for (std::int64_t v = 0; v < nVox; ++v)
  {
    const std::int64_t p = pixelOf(v, scale);
    if (p >= p0 && v0 == nVox)
    {
      v0 = v;
    }
    if (p >= p1)
    {
      v1 = v;
      break;
    }
  }
  v1 = std::max(v0, v1);
}

std::vector<Link> collectLinks(const FiberModel& model, double scaleS)
{
  std::vector<std::size_t> order(model.fibers.size());
  for (std::size_t f = 0; f < order.size(); ++f)
  {
    order[f] = f;
  }
  std::stable_sort(order.begin(), order.end(),
    [&](std::size_t a, std::size_t b) { return model.fibers[a].bundle < model.fibers[b].bundle; });
  std::vector<Link> links;
  std::int64_t g = 0;
  for (std::size_t f : order)
  {
    const Fiber& fib = model.fibers[f];
    for (std::size_t k = 0; k + 1 < fib.size(); ++k, ++g)
    {
      Link L;
      L.p = fib.points[k];
      L.ax = fib.points[k + 1] - fib.points[k];
      L.l2 = norm2(L.ax);
      if (L.l2 == 0.0)
      {
        continue; // no axis to own a voxel (§3.3 skips zero-length links)
      }
      L.rP = fib.radii[k];
      L.rQ = fib.radii[k + 1];
      const double grow = scaleS * std::max(L.rP, L.rQ);
      const Vec3& q = fib.points[k + 1];
      L.lo = { std::min(L.p.x, q.x) - grow, std::min(L.p.y, q.y) - grow, std::min(L.p.z, q.z) - grow };
      L.hi = { std::max(L.p.x, q.x) + grow, std::max(L.p.y, q.y) + grow, std::max(L.p.z, q.z) + grow };
      L.axis = L.ax / std::sqrt(L.l2);
      L.g = g;
      links.push_back(L);
    }
  }
  return links;
}

// Index range [a, b) of voxel centres origin + (i + ½)·h inside [lo, hi], clipped to [c0, c1).
void centresIn(double lo, double hi, double origin, double h, std::int64_t c0, std::int64_t c1, std::int64_t& a,
  std::int64_t& b)
{
  const double fa = std::ceil((lo - origin) / h - 0.5);
  const double fb = std::floor((hi - origin) / h - 0.5) + 1.0;
  a = static_cast<std::int64_t>(std::max(static_cast<double>(c0), std::min(static_cast<double>(c1), fa)));
  b = static_cast<std::int64_t>(std::max(static_cast<double>(a), std::min(static_cast<double>(c1), fb)));
}
} // namespace

TruthLattice latticeForPixelGrid(const Vec3& corner, double pixelSize, std::int64_t nx, std::int64_t ny,
  double zMin, double zMax, int samplesPerPixel)
{
  TruthLattice l;
  const int s = samplesPerPixel < 1 ? 1 : samplesPerPixel;
  l.origin = { corner.x, corner.y, zMin };
  l.pixelSize = pixelSize;
  l.voxelSize = pixelSize / s;
  l.n[0] = nx * s;
  l.n[1] = ny * s;
  l.n[2] = std::max<std::int64_t>(1, std::llround((zMax - zMin) / l.voxelSize));
  return l;
}

std::string truthPixelGrid(const TruthLattice& l, std::int64_t& nx, std::int64_t& ny)
{
  std::ostringstream msg;
  if (!std::isfinite(l.voxelSize) || l.voxelSize <= 0.0)
  {
    msg << "VoxelSize is " << l.voxelSize << ", must be > 0";
  }
  else if (!std::isfinite(l.pixelSize) || l.pixelSize < l.voxelSize)
  {
    msg << "PixelSize is " << l.pixelSize << ", must be >= VoxelSize " << l.voxelSize;
  }
  else if (l.n[0] < 0 || l.n[1] < 0 || l.n[2] < 0)
  {
    msg << "voxel counts " << l.n[0] << " x " << l.n[1] << " x " << l.n[2] << " must be >= 0";
  }
  else if (!isFinite(l.origin))
  {
    msg << "lattice origin is not finite";
  }
  if (!msg.str().empty())
  {
    return msg.str();
  }
  const double scale = l.voxelSize / l.pixelSize;
  nx = std::llround(static_cast<double>(l.n[0]) * scale);
  ny = std::llround(static_cast<double>(l.n[1]) * scale);
  return {};
}

std::string computeGroundTruth(const FiberModel& model, const TruthLattice& lat,
  const GroundTruthOptions& options, const PixelRange& range, GroundTruthMaps& maps, const ProgressFn& progress)
{
  std::int64_t nx = 0, ny = 0;
  std::string err = truthPixelGrid(lat, nx, ny);
  if (!err.empty())
  {
    return err;
  }
  err = validatePixelRange(nx, ny, range);
  if (!err.empty())
  {
    return err;
  }
  if (!std::isfinite(options.radiusScale) || options.radiusScale <= 0.0)
  {
    std::ostringstream msg;
    msg << "radius scale is " << options.radiusScale << ", must be > 0";
    return msg.str();
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
  const double scale = lat.voxelSize / lat.pixelSize;
  std::int64_t vx0, vx1;
  voxelSpan(lat.n[0], scale, range.i0, range.i1, vx0, vx1);
  const std::int64_t nz = lat.n[2];
  // One pixel row's voxels are held at once per thread.
  const double rowVoxels = static_cast<double>(vx1 - vx0) * std::ceil(1.0 / scale + 1.0) * static_cast<double>(nz);
  if (rowVoxels > 2147483647.0)
  {
    std::ostringstream msg;
    msg << "one pixel row holds " << rowVoxels << " voxels; use a larger VoxelSize or a smaller range";
    return msg.str();
  }

  const std::size_t nHist =
    options.histogram ? static_cast<std::size_t>(options.nPhi) * static_cast<std::size_t>(options.nAlpha) : 0;
  const int nThreads = resolveThreadCount(options.threads);
  std::size_t linkCount = 0;
  for (const Fiber& f : model.fibers)
  {
    linkCount += f.size() > 1 ? f.size() - 1 : 0;
  }
  // Five maps (and the histograms) of the whole grid, a copy of the range's maps in the caller's
  // output, per thread one pixel row of voxel owners (distance + link pointer), and the links.
  const double pixelBytes = static_cast<double>(nx) * static_cast<double>(ny) * (5.0 + static_cast<double>(nHist)) * 8.0;
  const double bytes = pixelBytes + 5.0 * 8.0 * static_cast<double>(range.count()) +
    static_cast<double>(nThreads) * rowVoxels * 16.0 + static_cast<double>(linkCount) * sizeof(Link);
  std::ostringstream what;
  what << "the ground truth of " << nx << " x " << ny << " pixels (PixelSize " << lat.pixelSize << ", VoxelSize "
       << lat.voxelSize << ", " << nz << " voxels deep)";
  err = checkMemoryBudget(bytes, what.str());
  if (!err.empty())
  {
    return err;
  }
  const std::size_t npx = static_cast<std::size_t>(nx * ny);
  maps.nx = nx;
  maps.ny = ny;
  for (auto* v : { &maps.fraction, &maps.direction, &maps.inclination, &maps.inclinationSigned, &maps.anisotropy })
  {
    v->resize(npx, kNaN);
  }
  maps.histogram.assign(npx * nHist, 0.0);

  std::vector<Link> links = collectLinks(model, options.radiusScale);
  // Sorted by the bottom of their box, a row stops scanning at the first link above it. Ownership
  // does not depend on the scan order: it is the total order (d², then g) of §3.3.
  std::sort(links.begin(), links.end(), [](const Link& a, const Link& b) { return a.lo.y < b.lo.y; });
  // Voxel columns of every pixel column, the same for every row.
  std::vector<std::int64_t> spanX(static_cast<std::size_t>(2 * range.width()));
  for (std::int64_t i = range.i0; i < range.i1; ++i)
  {
    voxelSpan(lat.n[0], scale, i, i + 1, spanX[static_cast<std::size_t>(2 * (i - range.i0))],
      spanX[static_cast<std::size_t>(2 * (i - range.i0) + 1)]);
  }
  const double S2 = options.radiusScale * options.radiusScale;
  const double h = lat.voxelSize;
  const std::int64_t rows = range.height();
  const std::int64_t block = std::max<std::int64_t>(1, rows / 50);

  for (std::int64_t jb = range.j0; jb < range.j1; jb += block)
  {
    const std::int64_t je = std::min(range.j1, jb + block);
#pragma omp parallel for num_threads(nThreads) schedule(dynamic, 1)
    for (std::int64_t j = jb; j < je; ++j)
    {
      std::int64_t vy0, vy1;
      voxelSpan(lat.n[1], scale, j, j + 1, vy0, vy1);
      const std::int64_t wx = vx1 - vx0, wy = vy1 - vy0;
      const std::size_t nVox = static_cast<std::size_t>(wx * wy * nz);
      std::vector<double> bestD2(nVox, std::numeric_limits<double>::infinity());
      std::vector<const Link*> owner(nVox, nullptr);
      const double y0 = lat.origin.y + static_cast<double>(vy0) * h, y1 = lat.origin.y + static_cast<double>(vy1) * h;
      const double x0 = lat.origin.x + static_cast<double>(vx0) * h, x1 = lat.origin.x + static_cast<double>(vx1) * h;
      for (const Link& L : links)
      {
        if (L.lo.y > y1)
        {
          break; // every later link starts above this row
        }
        if (L.hi.y < y0 || L.hi.x < x0 || L.lo.x > x1)
        {
          continue;
        }
        std::int64_t ia, ib, ja, jbb, ka, kb;
        centresIn(L.lo.x, L.hi.x, lat.origin.x, h, vx0, vx1, ia, ib);
        centresIn(L.lo.y, L.hi.y, lat.origin.y, h, vy0, vy1, ja, jbb);
        centresIn(L.lo.z, L.hi.z, lat.origin.z, h, 0, nz, ka, kb);
        for (std::int64_t k = ka; k < kb; ++k)
        {
          for (std::int64_t jj = ja; jj < jbb; ++jj)
          {
            for (std::int64_t i = ia; i < ib; ++i)
            {
              const Vec3 c{ lat.origin.x + (static_cast<double>(i) + 0.5) * h,
                lat.origin.y + (static_cast<double>(jj) + 0.5) * h, lat.origin.z + (static_cast<double>(k) + 0.5) * h };
              double t = dot(c - L.p, L.ax) / L.l2;
              t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
              const double r = options.maxRadius ? std::max(L.rP, L.rQ) : (1.0 - t) * L.rP + t * L.rQ;
              const double d2 = norm2(c - (L.p + t * L.ax));
              if (d2 > S2 * r * r)
              {
                continue;
              }
              const std::size_t v = static_cast<std::size_t>(((k * wy) + (jj - vy0)) * wx + (i - vx0));
              // §3.3 total order: smaller d², then the larger global link index wins the tie.
              if (d2 < bestD2[v] || (d2 == bestD2[v] && owner[v] && L.g > owner[v]->g))
              {
                bestD2[v] = d2;
                owner[v] = &L;
              }
            }
          }
        }
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
              const Link* o = owner[static_cast<std::size_t>(((k * wy) + (jj - vy0)) * wx + (iv - vx0))];
              if (o)
              {
                acc.addTissue(o->axis);
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
      return "cancelled";
    }
  }
  return {};
}

TileReach groundTruthReach(const TruthLattice& lat, const GroundTruthOptions& options, const PixelRange& range)
{
  TileReach r;
  if (range.width() < 1 || range.height() < 1 || lat.n[2] < 1)
  {
    return r;
  }
  // A voxel bins into pixel i when its centre lies in [i, i + 1) pixels from the origin (§5.2).
  const double p = lat.pixelSize, h = lat.voxelSize;
  r.box[0] = lat.origin.x + static_cast<double>(range.i0) * p - h;
  r.box[1] = lat.origin.x + static_cast<double>(range.i1) * p + h;
  r.box[2] = lat.origin.y + static_cast<double>(range.j0) * p - h;
  r.box[3] = lat.origin.y + static_cast<double>(range.j1) * p + h;
  r.box[4] = lat.origin.z - h;
  r.box[5] = lat.origin.z + static_cast<double>(lat.n[2] + 1) * h;
  r.radiusScale = options.radiusScale;
  return r;
}

std::vector<double> modelOrientationHistogram(const FiberModel& model, int nPhi, int nTheta, bool normalise,
  bool perSolidAngle)
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
        d = -d; // θ > 90°: count the antipode on the upper half sphere
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
