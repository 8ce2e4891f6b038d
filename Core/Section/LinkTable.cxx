#include "Section/LinkTable.h"

#include <numeric>

namespace fiberpli
{

namespace
{
double magnitude(const Vec3& v)
{
  return std::max({ std::abs(v.x), std::abs(v.y), std::abs(v.z) });
}

// Whether b is a translated by the closure of a (b starts where a ends), see fiberStrands.
bool continues(const Fiber& a, const Fiber& b)
{
  if (a.bundle != b.bundle || a.size() < 2 || a.size() != b.size() || a.radii != b.radii ||
    a.innerRadii != b.innerRadii)
    return false;
  const Vec3 t = b.points.front() - a.points.front();
  const double tol = 1e-9 * std::max(1.0, magnitude(t) + magnitude(a.points.back()));
  if (magnitude(b.points.front() - a.points.back()) > tol || magnitude(t) <= tol)
    return false;
  for (std::size_t i = 1; i < a.size(); ++i)
  {
    if (magnitude(b.points[i] - a.points[i] - t) > tol)
      return false;
  }
  return true;
}

std::int32_t findRoot(std::vector<std::int32_t>& parent, std::int32_t f)
{
  while (parent[static_cast<std::size_t>(f)] != f)
    f = parent[static_cast<std::size_t>(f)] =
      parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(f)])];
  return f;
}
} // namespace

std::vector<std::int32_t> fiberStrands(const FiberModel& model)
{
  const std::size_t n = model.fibers.size();
  std::vector<std::int32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  // Fibers by the x of their first point, so that the fibers starting where one ends are found
  // by a binary search (the cost is n log n plus the candidates).
  std::vector<std::int32_t> byStart;
  for (std::size_t f = 0; f < n; ++f)
  {
    if (model.fibers[f].size() >= 2)
      byStart.push_back(static_cast<std::int32_t>(f));
  }
  auto startX = [&](std::int32_t f)
  { return model.fibers[static_cast<std::size_t>(f)].points.front().x; };
  std::sort(byStart.begin(), byStart.end(),
    [&](std::int32_t a, std::int32_t b)
    { return startX(a) < startX(b) || (startX(a) == startX(b) && a < b); });
  for (const std::int32_t a : byStart)
  {
    const Fiber& fa = model.fibers[static_cast<std::size_t>(a)];
    const double x = fa.points.back().x;
    const double slack = 1e-6 * std::max(1.0, std::abs(x)); // wider than continues' tolerance
    auto it = std::lower_bound(byStart.begin(), byStart.end(), x - slack,
      [&](std::int32_t f, double v) { return startX(f) < v; });
    for (; it != byStart.end() && startX(*it) <= x + slack; ++it)
    {
      if (*it != a && continues(fa, model.fibers[static_cast<std::size_t>(*it)]))
      {
        const std::int32_t ra = findRoot(parent, a), rb = findRoot(parent, *it);
        parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
      }
    }
  }
  for (std::size_t f = 0; f < n; ++f)
    parent[f] = findRoot(parent, static_cast<std::int32_t>(f));
  return parent;
}

std::vector<int> bundlesOf(const FiberModel& model)
{
  std::vector<int> ids;
  for (const Fiber& f : model.fibers)
    ids.push_back(f.bundle);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

void buildLinkTable(const FiberModel& model, const std::vector<int>& slotBundles,
  const std::vector<double>& slotScale, RadiusModel radius, const SectionLattice& lat,
  const GridRange& region, std::int64_t binSize, LinkTable& t)
{
  t = LinkTable();
  t.radius = radius;
  t.binSize = std::max<std::int64_t>(1, binSize);
  t.scale = slotScale;
  t.scale.resize(slotBundles.size(), 0.0);
  t.bx0 = region.i0;
  t.by0 = region.j0;
  t.nbx = std::max<std::int64_t>(1, (region.nx() + t.binSize - 1) / t.binSize);
  t.nby = std::max<std::int64_t>(1, (region.ny() + t.binSize - 1) / t.binSize);
  t.bins.assign(static_cast<std::size_t>(t.nbx * t.nby), {});

  // The order g: bundle slot, then fiber index, then link index.
  std::vector<std::vector<int>> fibersOfSlot(slotBundles.size());
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const auto it =
      std::lower_bound(slotBundles.begin(), slotBundles.end(), model.fibers[f].bundle);
    if (it == slotBundles.end() || *it != model.fibers[f].bundle)
      ++t.unknownBundleFibers;
    else
      fibersOfSlot[static_cast<std::size_t>(it - slotBundles.begin())].push_back(
        static_cast<int>(f));
  }
  const std::vector<std::int32_t> strand = fiberStrands(model);
  const double inv = 1.0 / lat.voxel;
  const Vec3 o{ lat.origin[0], lat.origin[1], lat.origin[2] };
  for (std::size_t slot = 0; slot < fibersOfSlot.size(); ++slot)
  {
    const double S = t.scale[slot];
    for (int f : fibersOfSlot[slot])
    {
      const Fiber& fib = model.fibers[static_cast<std::size_t>(f)];
      for (std::size_t k = 0; k + 1 < fib.points.size(); ++k)
      {
        SectionLink L;
        L.p = (fib.points[k] - o) * inv;
        L.q = (fib.points[k + 1] - o) * inv;
        L.rp = fib.radii[k] * inv;
        L.rq = fib.radii[k + 1] * inv;
        const bool sheath = fib.innerRadii.size() == fib.points.size();
        L.ip = sheath ? fib.innerRadii[k] * inv : L.rp;
        L.iq = sheath ? fib.innerRadii[k + 1] * inv : L.rq;
        L.slot = static_cast<std::int32_t>(slot);
        L.fiber = f;
        L.strand = strand[static_cast<std::size_t>(f)];
        if (norm2(L.q - L.p) == 0.0)
        {
          ++t.zeroLengthLinks; // no axis to own a voxel
          continue;
        }
        const double grow = S * std::max(L.rp, L.rq);
        double lo[3], hi[3];
        for (int a = 0; a < 3; ++a)
        {
          lo[a] = std::min(L.p[a], L.q[a]) - grow;
          hi[a] = std::max(L.p[a], L.q[a]) + grow;
        }
        // Voxel centres c = i + 1/2 inside [lo, hi].
        const double fi0 = std::ceil(lo[0] - 0.5), fi1 = std::floor(hi[0] - 0.5);
        const double fj0 = std::ceil(lo[1] - 0.5), fj1 = std::floor(hi[1] - 0.5);
        if (hi[2] < 0.5 || lo[2] > static_cast<double>(lat.n[2]) - 0.5)
          continue;
        if (fi1 < static_cast<double>(region.i0) || fi0 > static_cast<double>(region.i1 - 1) ||
          fj1 < static_cast<double>(region.j0) || fj0 > static_cast<double>(region.j1 - 1))
          continue;
        const std::uint32_t g = static_cast<std::uint32_t>(t.links.size());
        t.links.push_back(L);
        const std::int64_t i0 = std::max<std::int64_t>(region.i0, static_cast<std::int64_t>(fi0));
        const std::int64_t i1 =
          std::min<std::int64_t>(region.i1 - 1, static_cast<std::int64_t>(fi1));
        const std::int64_t j0 = std::max<std::int64_t>(region.j0, static_cast<std::int64_t>(fj0));
        const std::int64_t j1 =
          std::min<std::int64_t>(region.j1 - 1, static_cast<std::int64_t>(fj1));
        for (std::int64_t by = (j0 - t.by0) / t.binSize; by <= (j1 - t.by0) / t.binSize; ++by)
          for (std::int64_t bx = (i0 - t.bx0) / t.binSize; bx <= (i1 - t.bx0) / t.binSize; ++bx)
            t.bins[static_cast<std::size_t>(by * t.nbx + bx)].push_back(g);
      }
    }
  }
}

void candidateLinks(const LinkTable& t, const GridRange& fill, std::vector<std::uint32_t>& cand)
{
  cand.clear();
  if (fill.nx() <= 0 || fill.ny() <= 0 || t.links.empty())
    return;
  const std::int64_t bxa = std::max<std::int64_t>(0, (fill.i0 - t.bx0) / t.binSize);
  const std::int64_t bxb = std::min<std::int64_t>(t.nbx - 1, (fill.i1 - 1 - t.bx0) / t.binSize);
  const std::int64_t bya = std::max<std::int64_t>(0, (fill.j0 - t.by0) / t.binSize);
  const std::int64_t byb = std::min<std::int64_t>(t.nby - 1, (fill.j1 - 1 - t.by0) / t.binSize);
  for (std::int64_t by = bya; by <= byb; ++by)
    for (std::int64_t bx = bxa; bx <= bxb; ++bx)
    {
      const auto& bin = t.bins[static_cast<std::size_t>(by * t.nbx + bx)];
      cand.insert(cand.end(), bin.begin(), bin.end());
    }
  std::sort(cand.begin(), cand.end());
  cand.erase(std::unique(cand.begin(), cand.end()), cand.end());
}

} // namespace fiberpli
