#include "Mesh/SubstrateMesher.h"

#include "Geometry/MinimalRotation.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace fiberpli
{

namespace
{

using Offset = std::array<long long, 3>;
constexpr long long kNoPlane = std::numeric_limits<long long>::min();

/// A vertex of the unwrapped tube: a base position plus a lattice offset (integer multiples of the
/// cell edges). The seam of a loop uses its first ring's base vertices with the closure offset, so
/// that both copies wrap to bit-identical coordinates.
struct LocalVertex
{
  std::size_t base;
  Offset offset;
};

struct TubeBuild
{
  std::vector<Vec3> base;
  std::vector<Offset>
    onPlane; ///< per base vertex and axis: index of the lattice plane (base frame) it lies on
  std::vector<LocalVertex> verts;
  std::vector<std::array<std::size_t, 3>> tris;

  std::size_t addBase(const Vec3& p)
  {
    base.push_back(p);
    onPlane.push_back({ kNoPlane, kNoPlane, kNoPlane });
    return base.size() - 1;
  }
  std::size_t addVertex(std::size_t b, const Offset& o)
  {
    verts.push_back({ b, o });
    return verts.size() - 1;
  }
};

Vec3 perpendicularTo(const Vec3& t)
{
  const Vec3 a = std::abs(t.x) < 0.6 ? Vec3{ 1.0, 0.0, 0.0 } : Vec3{ 0.0, 1.0, 0.0 };
  return normalized(cross(t, a));
}

/// Unit directions of the links; zero-length links borrow a neighbour's direction.
std::vector<Vec3> unitDirections(std::vector<Vec3> dir)
{
  for (Vec3& d : dir)
  {
    d = normalized(d);
  }
  for (std::size_t k = 1; k < dir.size(); ++k)
  {
    if (norm2(dir[k]) == 0.0)
    {
      dir[k] = dir[k - 1];
    }
  }
  for (std::size_t k = dir.size() - 1; k-- > 0;)
  {
    if (norm2(dir[k]) == 0.0)
    {
      dir[k] = dir[k + 1];
    }
  }
  if (norm2(dir[0]) == 0.0)
  {
    std::fill(dir.begin(), dir.end(), Vec3{ 0.0, 0.0, 1.0 });
  }
  return dir;
}

Vec3 bisector(const Vec3& in, const Vec3& out)
{
  const Vec3 sum = in + out;
  return norm2(sum) > 1e-12 ? normalized(sum) : in; // a hairpin has no bisector
}

/// Builds the tube around pts (radii per point). loop: the tube continues from the last point to
/// pts[0] + closure (closureK: closure in edge multiples) and has no caps; else it is capped.
void buildTube(const std::vector<Vec3>& pts, const std::vector<double>& radii, bool loop,
  const Vec3& closure, const Offset& closureK, int sides, TubeBuild& b)
{
  const std::size_t m = pts.size();
  std::vector<Vec3> raw;
  for (std::size_t k = 0; k + 1 < m; ++k)
  {
    raw.push_back(pts[k + 1] - pts[k]);
  }
  if (loop)
  {
    raw.push_back(pts[0] + closure - pts[m - 1]);
  }
  const std::vector<Vec3> dir = unitDirections(raw);
  auto axisAt = [&](std::size_t i)
  {
    if (loop)
    {
      return bisector(dir[(i + dir.size() - 1) % dir.size()], dir[i]);
    }
    if (i == 0)
    {
      return dir.front();
    }
    if (i == m - 1)
    {
      return dir.back();
    }
    return bisector(dir[i - 1], dir[i]);
  };
  const auto n = static_cast<std::size_t>(sides);
  Vec3 axis = axisAt(0);
  Vec3 u = perpendicularTo(axis);
  for (std::size_t i = 0; i < m; ++i)
  {
    const Vec3 next = axisAt(i);
    u = normalized(rotateMinimal(axis, next, u));
    u = normalized(u - next * dot(u, next));
    if (norm2(u) == 0.0)
    {
      u = perpendicularTo(next);
    }
    axis = next;
    const Vec3 v = cross(axis, u);
    for (std::size_t s = 0; s < n; ++s)
    {
      const double phi = 2.0 * M_PI * static_cast<double>(s) / static_cast<double>(n);
      b.addVertex(
        b.addBase(pts[i] + (u * std::cos(phi) + v * std::sin(phi)) * radii[i]), Offset{ 0, 0, 0 });
    }
  }
  auto ring = [&](std::size_t i, std::size_t s) { return i * n + s % n; };
  auto quad = [&](std::size_t a0, std::size_t a1, std::size_t b0, std::size_t b1)
  {
    // (u, v, axis) right-handed: around the ring × along the axis points outward.
    b.tris.push_back({ a0, a1, b1 });
    b.tris.push_back({ a0, b1, b0 });
  };
  for (std::size_t i = 0; i + 1 < m; ++i)
  {
    for (std::size_t s = 0; s < n; ++s)
    {
      quad(ring(i, s), ring(i, s + 1), ring(i + 1, s), ring(i + 1, s + 1));
    }
  }
  if (loop)
  {
    // Seam: the last ring joins the first ring shifted by the closure; the first ring's vertex
    // nearest to the last ring's vertex 0 starts, so the seam does not twist.
    std::size_t best = 0;
    double bestD = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < n; ++j)
    {
      const double d = norm2(b.base[ring(0, j)] + closure - b.base[ring(m - 1, 0)]);
      if (d < bestD)
      {
        bestD = d;
        best = j;
      }
    }
    std::vector<std::size_t> seam(n);
    for (std::size_t j = 0; j < n; ++j)
    {
      seam[j] = b.addVertex(ring(0, (j + best) % n), closureK);
    }
    for (std::size_t s = 0; s < n; ++s)
    {
      quad(ring(m - 1, s), ring(m - 1, s + 1), seam[s], seam[(s + 1) % n]);
    }
    return;
  }
  const std::size_t c0 = b.addVertex(b.addBase(pts.front()), Offset{ 0, 0, 0 });
  const std::size_t c1 = b.addVertex(b.addBase(pts.back()), Offset{ 0, 0, 0 });
  for (std::size_t s = 0; s < n; ++s)
  {
    b.tris.push_back({ c0, ring(0, s + 1), ring(0, s) });
    b.tris.push_back({ c1, ring(m - 1, s), ring(m - 1, s + 1) });
  }
}

/// Splits every triangle that straddles the lattice plane k of axis a (conformingly: both
/// triangles of an edge get the same cut vertex).
void clipAtPlane(TubeBuild& b, const PeriodicCell& cell, int a, long long k)
{
  const double lo = cell.lo[a];
  const double e = cell.hi[a] - cell.lo[a];
  const double eps = 1e-9 * e;
  auto planeValue = [&](long long j) { return lo + static_cast<double>(j) * e; };
  std::vector<double> d(b.verts.size());
  for (std::size_t v = 0; v < b.verts.size(); ++v)
  {
    const LocalVertex& lv = b.verts[v];
    const long long j = k - lv.offset[a];
    const double pv = planeValue(j);
    double dv = b.base[lv.base][a] - pv;
    if (std::abs(dv) <= eps)
    {
      b.base[lv.base][a] = pv; // onto the plane: no sliver straddles it
      b.onPlane[lv.base][a] = j;
      dv = 0.0;
    }
    d[v] = dv;
  }
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> cuts;
  auto cut = [&](std::size_t p, std::size_t q)
  {
    const auto key = std::make_pair(std::min(p, q), std::max(p, q));
    const auto found = cuts.find(key);
    if (found != cuts.end())
    {
      return found->second;
    }
    // Compute from the endpoint with the smaller base id: the twin edge of a loop's seam (same
    // base vertices, other offset) then gives bit-identical coordinates.
    std::size_t u = p;
    std::size_t w = q;
    if (b.verts[w].base < b.verts[u].base)
    {
      std::swap(u, w);
    }
    const LocalVertex lu = b.verts[u];
    const LocalVertex lw = b.verts[w];
    Vec3 bw = b.base[lw.base];
    Offset planesW = b.onPlane[lw.base];
    for (int c = 0; c < 3; ++c)
    {
      const long long delta = lw.offset[c] - lu.offset[c];
      if (delta != 0)
      {
        bw[c] += static_cast<double>(delta) * (cell.hi[c] - cell.lo[c]);
        if (planesW[c] != kNoPlane)
        {
          planesW[c] += delta;
        }
      }
    }
    const Vec3 bu = b.base[lu.base];
    const double t = d[u] / (d[u] - d[w]);
    Vec3 pt = bu + (bw - bu) * t;
    const long long j = k - lu.offset[a];
    pt[a] = planeValue(j);
    const std::size_t nb = b.addBase(pt);
    b.onPlane[nb][a] = j;
    for (int c = 0; c < 3; ++c)
    {
      if (c != a && b.onPlane[lu.base][c] != kNoPlane && b.onPlane[lu.base][c] == planesW[c])
      {
        b.onPlane[nb][c] = planesW[c]; // the edge lies in that plane, so does its cut
      }
    }
    const std::size_t nv = b.addVertex(nb, lu.offset);
    cuts.emplace(key, nv);
    return nv;
  };
  auto sign = [&](std::size_t v) { return d[v] > 0.0 ? 1 : (d[v] < 0.0 ? -1 : 0); };
  std::vector<std::array<std::size_t, 3>> out;
  out.reserve(b.tris.size());
  for (const auto& t : b.tris)
  {
    const int s0 = sign(t[0]);
    const int s1 = sign(t[1]);
    const int s2 = sign(t[2]);
    const bool pos = s0 > 0 || s1 > 0 || s2 > 0;
    const bool neg = s0 < 0 || s1 < 0 || s2 < 0;
    if (!(pos && neg))
    {
      out.push_back(t);
      continue;
    }
    const int s[3] = { s0, s1, s2 };
    int zero = -1;
    for (int i = 0; i < 3; ++i)
    {
      if (s[i] == 0)
      {
        zero = i;
      }
    }
    if (zero >= 0)
    {
      const std::size_t v0 = t[zero];
      const std::size_t v1 = t[(zero + 1) % 3];
      const std::size_t v2 = t[(zero + 2) % 3];
      const std::size_t c = cut(v1, v2);
      out.push_back({ v0, v1, c });
      out.push_back({ v0, c, v2 });
      continue;
    }
    int lone = 0;
    for (int i = 0; i < 3; ++i)
    {
      if (s[i] != s[(i + 1) % 3] && s[i] != s[(i + 2) % 3])
      {
        lone = i;
      }
    }
    const std::size_t v0 = t[lone];
    const std::size_t v1 = t[(lone + 1) % 3];
    const std::size_t v2 = t[(lone + 2) % 3];
    const std::size_t c1 = cut(v0, v1);
    const std::size_t c2 = cut(v0, v2);
    out.push_back({ v0, c1, c2 });
    out.push_back({ c1, v1, v2 });
    out.push_back({ c1, v2, c2 });
  }
  b.tris.swap(out);
}

/// Cuts the tube at every lattice plane it crosses and moves every piece into the cell.
void wrapIntoCell(TubeBuild& b, const PeriodicCell& cell, SubstrateSurface& surface)
{
  for (int a = 0; a < 3; ++a)
  {
    const double lo = cell.lo[a];
    const double e = cell.hi[a] - cell.lo[a];
    double mn = std::numeric_limits<double>::infinity();
    double mx = -mn;
    for (const LocalVertex& v : b.verts)
    {
      const double x = b.base[v.base][a] + static_cast<double>(v.offset[a]) * e;
      mn = std::min(mn, x);
      mx = std::max(mx, x);
    }
    const auto k0 = static_cast<long long>(std::ceil((mn - 2e-9 * e - lo) / e));
    const auto k1 = static_cast<long long>(std::floor((mx + 2e-9 * e - lo) / e));
    for (long long k = k0; k <= k1; ++k)
    {
      clipAtPlane(b, cell, a, k);
    }
  }
  std::map<std::pair<std::size_t, Offset>, std::int64_t> index;
  for (const auto& t : b.tris)
  {
    Offset slab{ 0, 0, 0 };
    for (int a = 0; a < 3; ++a)
    {
      const double lo = cell.lo[a];
      const double e = cell.hi[a] - cell.lo[a];
      bool found = false;
      long long lowest = std::numeric_limits<long long>::max();
      for (std::size_t v : t)
      {
        const LocalVertex& lv = b.verts[v];
        const long long j = b.onPlane[lv.base][a];
        if (j == kNoPlane)
        {
          slab[a] =
            static_cast<long long>(std::floor((b.base[lv.base][a] - lo) / e)) + lv.offset[a];
          found = true;
          break;
        }
        lowest = std::min(lowest, j + lv.offset[a]);
      }
      if (!found)
      {
        slab[a] = lowest; // a triangle lying in a face (degenerate): keep it at the low face
      }
    }
    std::array<std::int64_t, 3> tri{};
    for (int i = 0; i < 3; ++i)
    {
      const LocalVertex& lv = b.verts[t[i]];
      Offset rel;
      for (int a = 0; a < 3; ++a)
      {
        rel[a] = lv.offset[a] - slab[a];
      }
      const auto key = std::make_pair(lv.base, rel);
      const auto it = index.find(key);
      if (it != index.end())
      {
        tri[i] = it->second;
        continue;
      }
      Vec3 p;
      for (int a = 0; a < 3; ++a)
      {
        const double e = cell.hi[a] - cell.lo[a];
        const long long j = b.onPlane[lv.base][a];
        if (j != kNoPlane)
        {
          const long long face = j + rel[a];
          p[a] = face == 0 ? cell.lo[a]
                           : (face == 1 ? cell.hi[a] : cell.lo[a] + static_cast<double>(face) * e);
        }
        else
        {
          p[a] =
            rel[a] == 0 ? b.base[lv.base][a] : b.base[lv.base][a] + static_cast<double>(rel[a]) * e;
        }
      }
      surface.vertices.push_back(p);
      tri[i] = static_cast<std::int64_t>(surface.vertices.size() - 1);
      index.emplace(key, tri[i]);
    }
    surface.triangles.push_back(tri);
  }
}

/// The fiber's points and radii with extra points so that no link is longer than spacing; for a
/// loop the closing link (to the first point + closure) is filled too (without repeating it).
void refine(const std::vector<Vec3>& pts, const std::vector<double>& radii, bool loop,
  const Vec3& closure, double spacing, std::vector<Vec3>& outPts, std::vector<double>& outRadii)
{
  outPts.clear();
  outRadii.clear();
  const std::size_t m = pts.size();
  const std::size_t links = loop ? m : m - 1;
  for (std::size_t k = 0; k < links; ++k)
  {
    const Vec3 a = pts[k];
    const Vec3 bpt = k + 1 < m ? pts[k + 1] : pts[0] + closure;
    const double ra = radii[k];
    const double rb = radii[(k + 1) % m];
    const double length = norm(bpt - a);
    const std::size_t n = spacing > 0.0
      ? std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(length / spacing)))
      : 1;
    for (std::size_t j = 0; j < n; ++j)
    {
      const double t = static_cast<double>(j) / static_cast<double>(n);
      outPts.push_back(j == 0 ? a : a + (bpt - a) * t);
      outRadii.push_back(ra + (rb - ra) * t);
    }
  }
  if (!loop)
  {
    outPts.push_back(pts.back());
    outRadii.push_back(radii.back());
  }
}

} // namespace

std::string checkSubstrateMeshOptions(const SubstrateMeshOptions& o)
{
  return ValueChecks()
    .within("NumberOfSides", o.sides, 3, kMaxSubstrateSides)
    .then(std::isfinite(o.ringSpacing) && o.ringSpacing >= 0.0
        ? std::string()
        : "RingSpacing is " + formatNumber(o.ringSpacing) +
          " µm, must be finite and >= 0 (0: rings at the fiber points only)")
    .error();
}

int substrateSidesForTolerance(double radius, double tolerance)
{
  for (int n = 3; n < kMaxSubstrateSides; ++n)
  {
    if (radius * (1.0 - std::cos(M_PI / n)) <= tolerance)
    {
      return n;
    }
  }
  return kMaxSubstrateSides;
}

Status meshSubstrate(const FiberModel& model, const std::vector<std::vector<double>>* innerRadii,
  const PeriodicCell& cell, const SubstrateMeshOptions& options, const SubstrateSink& sink,
  const ProgressFn& progress)
{
  const std::string bad = checkSubstrateMeshOptions(options);
  if (!bad.empty())
  {
    return bad;
  }
  const std::string invalid = validateModel(model);
  if (!invalid.empty())
  {
    return invalid;
  }
  const bool hasInner = innerRadii != nullptr && !innerRadii->empty();
  if (hasInner && innerRadii->size() != model.fibers.size())
  {
    return "inner_radius: " + std::to_string(innerRadii->size()) + " fibers, the model has " +
      std::to_string(model.fibers.size());
  }
  // Ring counts are checked before anything is built: a tiny spacing must not exhaust memory.
  if (options.ringSpacing > 0.0)
  {
    double rings = 0.0;
    for (const Fiber& f : model.fibers)
    {
      for (std::size_t k = 0; k + 1 < f.size(); ++k)
      {
        rings += std::ceil(norm(f.points[k + 1] - f.points[k]) / options.ringSpacing);
      }
    }
    if (rings * options.sides > 4e9)
    {
      std::ostringstream m;
      m << "RingSpacing " << options.ringSpacing << " µm gives " << rings << " rings of "
        << options.sides << " vertices (more than 4e9 vertices); raise it";
      return m.str();
    }
  }
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fiber = model.fibers[f];
    Vec3 closure;
    const bool loop = cell.enabled() && isClosedFiber(fiber, cell, closure);
    Offset closureK{ 0, 0, 0 };
    std::vector<Vec3> pts = fiber.points;
    if (loop)
    {
      pts.pop_back(); // the last point is the first one shifted by the closure
      for (int a = 0; a < 3; ++a)
      {
        closureK[a] =
          static_cast<long long>(std::nearbyint(closure[a] / (cell.hi[a] - cell.lo[a])));
      }
    }
    for (int pass = 0; pass < (hasInner ? 2 : 1); ++pass)
    {
      std::vector<double> radii = pass == 0 ? fiber.radii : (*innerRadii)[f];
      if (radii.size() != fiber.size())
      {
        return "inner_radius of fiber " + std::to_string(f) + " (id " + std::to_string(fiber.id) +
          ") has " + std::to_string(radii.size()) + " values for " + std::to_string(fiber.size()) +
          " points";
      }
      for (std::size_t i = 0; i < radii.size(); ++i)
      {
        if (!std::isfinite(radii[i]) || !(radii[i] > 0.0) || radii[i] > fiber.radii[i])
        {
          std::ostringstream m;
          m << "inner_radius " << radii[i] << " of fiber " << f << " (id " << fiber.id << ") point "
            << i << " must be > 0 and <= its radius " << fiber.radii[i];
          return m.str();
        }
      }
      if (loop)
      {
        radii.pop_back();
      }
      std::vector<Vec3> ringPts;
      std::vector<double> ringRadii;
      refine(pts, radii, loop, closure, options.ringSpacing, ringPts, ringRadii);
      TubeBuild build;
      buildTube(ringPts, ringRadii, loop, closure, closureK, options.sides, build);
      SubstrateSurface surface;
      surface.fiber = f;
      surface.inner = pass == 1;
      if (cell.enabled())
      {
        wrapIntoCell(build, cell, surface);
      }
      else
      {
        surface.vertices = build.base;
        for (const auto& t : build.tris)
        {
          surface.triangles.push_back({ static_cast<std::int64_t>(build.verts[t[0]].base),
            static_cast<std::int64_t>(build.verts[t[1]].base),
            static_cast<std::int64_t>(build.verts[t[2]].base) });
        }
      }
      if (!sink(surface))
      {
        return Status::stopped();
      }
    }
    if (!reportProgress(
          progress, static_cast<double>(f + 1) / static_cast<double>(model.fibers.size())))
    {
      return Status::stopped();
    }
  }
  return {};
}

Status writeSubstratePly(std::ostream& out, const FiberModel& model,
  const std::vector<std::vector<double>>* innerRadii, const PeriodicCell& cell,
  const SubstrateMeshOptions& options, SubstrateMeshCounts& counts, const ProgressFn& progress)
{
  counts = SubstrateMeshCounts{};
  // Progress: the three passes take a third each.
  auto part = [&](int p)
  { return ProgressFn([&, p](double x) { return reportProgress(progress, (p + x) / 3.0); }); };
  Status status = meshSubstrate(
    model, innerRadii, cell, options,
    [&](const SubstrateSurface& s)
    {
      counts.vertices += s.vertices.size();
      counts.triangles += s.triangles.size();
      ++counts.surfaces;
      return true;
    },
    progress ? part(0) : ProgressFn{});
  if (!status.ok())
  {
    return status;
  }
  out << "ply\nformat ascii 1.0\ncomment FiberPLI substrate, micrometres\n"
      << "element vertex " << counts.vertices
      << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "element face " << counts.triangles
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  std::string text;
  auto flushText = [&]()
  {
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    text.clear();
    return static_cast<bool>(out);
  };
  auto number = [&](double x)
  {
    char buffer[32];
    const std::to_chars_result r = std::to_chars(buffer, buffer + sizeof(buffer), x);
    text.append(buffer, static_cast<std::size_t>(r.ptr - buffer));
  };
  std::uint64_t written = 0;
  status = meshSubstrate(
    model, innerRadii, cell, options,
    [&](const SubstrateSurface& s)
    {
      for (const Vec3& p : s.vertices)
      {
        number(p.x);
        text += ' ';
        number(p.y);
        text += ' ';
        number(p.z);
        text += '\n';
      }
      written += s.vertices.size();
      return flushText();
    },
    progress ? part(1) : ProgressFn{});
  if (!status.ok())
  {
    return status;
  }
  if (written != counts.vertices)
  {
    return "the mesh changed between its passes (vertex count)"; // cannot happen: the passes are
                                                                 // deterministic
  }
  std::uint64_t first = 0;
  status = meshSubstrate(
    model, innerRadii, cell, options,
    [&](const SubstrateSurface& s)
    {
      for (const auto& t : s.triangles)
      {
        text += "3 ";
        text += std::to_string(first + static_cast<std::uint64_t>(t[0]));
        text += ' ';
        text += std::to_string(first + static_cast<std::uint64_t>(t[1]));
        text += ' ';
        text += std::to_string(first + static_cast<std::uint64_t>(t[2]));
        text += '\n';
      }
      first += s.vertices.size();
      return flushText();
    },
    progress ? part(2) : ProgressFn{});
  if (!status.ok())
  {
    return status;
  }
  out.flush();
  if (!out)
  {
    return "the output stream failed";
  }
  return {};
}

std::string mcdcConfigSnippet(const std::string& plyPath, const Vec3& lo, const Vec3& hi)
{
  std::ostringstream s;
  s.precision(15);
  s << "<obstacle>\nply " << plyPath << "\nply_scale 0.001\n</obstacle>\n\n<voxels>\n"
    << lo.x * 1e-3 << ' ' << lo.y * 1e-3 << ' ' << lo.z * 1e-3 << '\n'
    << hi.x * 1e-3 << ' ' << hi.y * 1e-3 << ' ' << hi.z * 1e-3 << "\n</voxels>\n";
  return s.str();
}

} // namespace fiberpli
