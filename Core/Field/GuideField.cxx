#include "Field/GuideField.h"

#include "Field/FieldAgreement.h"
#include "Util/MemoryBudget.h"
#include "Util/NumberFormat.h"
#include "Util/Threads.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace fiberpli
{

namespace
{
constexpr int kMaxPopulations = 2;
constexpr int kPlanesPerReport = 8; // grid planes between progress reports

/// One guide segment of positive length.
struct Segment
{
  Vec3 a, b;
  int population = 0;
};

std::string guidePointProblem(const std::vector<GuideLine>& guides)
{
  for (std::size_t g = 0; g < guides.size(); ++g)
  {
    for (std::size_t i = 0; i < guides[g].points.size(); ++i)
    {
      if (!isFinite(guides[g].points[i]))
      {
        return "Input: point " + std::to_string(i) + " of guide line " + std::to_string(g) +
          " is not finite (NaN or infinite); every guide point must be a finite position in µm";
      }
    }
  }
  return {};
}

/// The grid points i with |origin + i·spacing - x| < reach along one axis, clamped to the grid.
void pointRange(double lo, double hi, double origin, double spacing, int n, int& first, int& last)
{
  first = std::max(0, static_cast<int>(std::floor((lo - origin) / spacing)));
  last = std::min(n - 1, static_cast<int>(std::ceil((hi - origin) / spacing)));
}
} // namespace

std::string validateGuideFieldOptions(const GuideFieldOptions& o)
{
  if (!(std::isfinite(o.radius) && o.radius > 0.0))
  {
    return "GuideRadius is " + formatNumber(o.radius) + ", must be > 0 (µm)";
  }
  if (!(std::isfinite(o.spacing) && o.spacing > 0.0))
  {
    return "GuideSpacing is " + formatNumber(o.spacing) + ", must be > 0 (µm)";
  }
  if (o.spacing > o.radius)
  {
    return "GuideSpacing is " + formatNumber(o.spacing) + " µm, must be at most GuideRadius (" +
      formatNumber(o.radius) + " µm): a coarser grid can miss the guides";
  }
  if (o.populations != GuidePopulations::One && o.populations != GuidePopulations::ByBundle)
  {
    return "GuidePopulations is " + std::to_string(static_cast<int>(o.populations)) +
      ", must be 0 (One) or 1 (ByBundle)";
  }
  return validateThreadCount(o.threads);
}

double segmentLengthInBall(const Vec3& a, const Vec3& b, const Vec3& centre, double radius)
{
  const Vec3 d = b - a;
  const double length = norm(d);
  if (!(length > 0.0))
  {
    return 0.0;
  }
  const Vec3 u = d / length;
  const Vec3 ac = centre - a;
  const double along = dot(ac, u);                  // the centre's projection onto the line
  const double across2 = norm2(ac) - along * along; // squared distance from the line
  const double half2 = radius * radius - across2;   // squared half chord
  if (!(half2 > 0.0))
  {
    return 0.0;
  }
  const double half = std::sqrt(half2);
  return std::max(0.0, std::min(length, along + half) - std::max(0.0, along - half));
}

GuideFieldResult guideOrientationFields(
  const std::vector<GuideLine>& guides, const GuideFieldOptions& o, const ProgressFn& progress)
{
  GuideFieldResult result;
  result.error = validateGuideFieldOptions(o);
  if (result.error.empty())
  {
    result.error = guidePointProblem(guides);
  }
  if (!result.error.empty())
  {
    return result;
  }

  // The populations: one, or the sorted bundle ids of the guides that have a segment.
  std::vector<std::int64_t> bundles;
  std::vector<Segment> segments;
  Vec3 lo{ std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
    std::numeric_limits<double>::infinity() };
  Vec3 hi = -lo;
  for (const GuideLine& g : guides)
  {
    for (std::size_t i = 1; i < g.points.size(); ++i)
    {
      if (norm2(g.points[i] - g.points[i - 1]) > 0.0)
      {
        bundles.push_back(g.bundle);
        break;
      }
    }
  }
  if (bundles.empty())
  {
    result.error = "Input: the guides have no line with two distinct points (a vtkPolyData with "
                   "polylines is needed, e.g. streamlines read from a .tck file)";
    return result;
  }
  std::sort(bundles.begin(), bundles.end());
  bundles.erase(std::unique(bundles.begin(), bundles.end()), bundles.end());
  const bool byBundle = o.populations == GuidePopulations::ByBundle;
  if (byBundle && bundles.size() > static_cast<std::size_t>(kMaxPopulations))
  {
    std::string list;
    for (std::size_t k = 0; k < bundles.size() && k < 4; ++k)
    {
      list += (k ? ", " : "") + std::to_string(bundles[k]);
    }
    result.error = "GuidePopulations is 1 (ByBundle), but the guides have " +
      std::to_string(bundles.size()) + " bundle_id values (" + list +
      (bundles.size() > 4 ? ", ..." : "") + "); at most 2 populations: use 0 (One)";
    return result;
  }
  const int populations = byBundle ? static_cast<int>(bundles.size()) : 1;
  for (const GuideLine& g : guides)
  {
    const int p = byBundle
      ? static_cast<int>(
          std::lower_bound(bundles.begin(), bundles.end(), g.bundle) - bundles.begin())
      : 0;
    for (std::size_t i = 1; i < g.points.size(); ++i)
    {
      if (norm2(g.points[i] - g.points[i - 1]) > 0.0)
      {
        segments.push_back({ g.points[i - 1], g.points[i], p });
        for (const Vec3& q : { g.points[i - 1], g.points[i] })
        {
          for (int a = 0; a < 3; ++a)
          {
            lo[a] = std::min(lo[a], q[a]);
            hi[a] = std::max(hi[a], q[a]);
          }
        }
      }
    }
  }
  result.segments = segments.size();

  // The grid: the bounds padded by the radius, rounded up to whole spacings and centred on them.
  const double r = o.radius;
  const double s = o.spacing;
  OrientationField grid;
  grid.spacing = { s, s, s };
  double points = 1.0;
  for (int a = 0; a < 3; ++a)
  {
    const double extent = hi[a] - lo[a] + 2.0 * r;
    const double cells = std::ceil(extent / s * (1.0 - 1e-12));
    points *= cells + 1.0;
    if (cells + 1.0 > 1e9)
    {
      points = std::numeric_limits<double>::infinity();
      break;
    }
    grid.dimensions[static_cast<std::size_t>(a)] = static_cast<int>(cells) + 1;
    grid.origin[a] = lo[a] - r - 0.5 * (cells * s - extent);
  }
  const Vec3 e = hi - lo;
  const std::string what = "the guide field (GuideSpacing " + formatNumber(s) +
    " µm over the guides' bounds " + formatNumber(e.x) + " × " + formatNumber(e.y) + " × " +
    formatNumber(e.z) + " µm padded by GuideRadius " + formatNumber(r) +
    " µm: " + formatNumber(points) + " grid points)";
  // Bins of m × m × m grid points, each listing the segments that can reach one of its points.
  const int m = std::max(1, static_cast<int>(std::ceil(r / s)));
  std::array<int, 3> bins{ 1, 1, 1 };
  for (int a = 0; a < 3; ++a)
  {
    bins[static_cast<std::size_t>(a)] = (grid.dimensions[static_cast<std::size_t>(a)] + m - 1) / m;
  }
  const double binCount = static_cast<double>(bins[0]) * bins[1] * bins[2];
  result.error =
    checkMemoryBudget(points * populations * sizeof(Vec3) + binCount * sizeof(std::size_t), what);
  if (!result.error.empty())
  {
    return result;
  }
  const auto binRange = [&](const Segment& seg, std::array<int, 3>& first, std::array<int, 3>& last)
  {
    for (int a = 0; a < 3; ++a)
    {
      int i0 = 0, i1 = 0;
      pointRange(std::min(seg.a[a], seg.b[a]) - r, std::max(seg.a[a], seg.b[a]) + r, grid.origin[a],
        s, grid.dimensions[static_cast<std::size_t>(a)], i0, i1);
      first[static_cast<std::size_t>(a)] = i0 / m;
      last[static_cast<std::size_t>(a)] = i1 / m;
    }
  };
  const auto binIndex = [&](int bi, int bj, int bk)
  { return (static_cast<std::size_t>(bk) * bins[1] + bj) * bins[0] + bi; };
  // Counting pass, then the lists (CSR, segments in guide order within every bin).
  std::vector<std::size_t> start(static_cast<std::size_t>(binCount) + 1, 0);
  double entries = 0.0;
  for (const Segment& seg : segments)
  {
    std::array<int, 3> f{}, l{};
    binRange(seg, f, l);
    entries += static_cast<double>(l[0] - f[0] + 1) * (l[1] - f[1] + 1) * (l[2] - f[2] + 1);
  }
  result.error = checkMemoryBudget(points * populations * sizeof(Vec3) +
      binCount * sizeof(std::size_t) + entries * sizeof(std::uint32_t),
    what);
  if (!result.error.empty())
  {
    return result;
  }
  if (segments.size() > std::numeric_limits<std::uint32_t>::max())
  {
    result.error = "Input: more than 2^32 guide segments";
    return result;
  }
  for (const Segment& seg : segments)
  {
    std::array<int, 3> f{}, l{};
    binRange(seg, f, l);
    for (int bk = f[2]; bk <= l[2]; ++bk)
      for (int bj = f[1]; bj <= l[1]; ++bj)
        for (int bi = f[0]; bi <= l[0]; ++bi)
          ++start[binIndex(bi, bj, bk) + 1];
  }
  for (std::size_t b = 1; b < start.size(); ++b)
  {
    start[b] += start[b - 1];
  }
  std::vector<std::uint32_t> list(start.back());
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t k = 0; k < segments.size(); ++k)
    {
      std::array<int, 3> f{}, l{};
      binRange(segments[k], f, l);
      for (int bk = f[2]; bk <= l[2]; ++bk)
        for (int bj = f[1]; bj <= l[1]; ++bj)
          for (int bi = f[0]; bi <= l[0]; ++bi)
            list[fill[binIndex(bi, bj, bk)]++] = static_cast<std::uint32_t>(k);
    }
  }

  result.fields.assign(static_cast<std::size_t>(populations), grid);
  for (OrientationField& f : result.fields)
  {
    f.vectors.assign(f.size(), Vec3{});
  }
  const int threads = resolveThreadCount(o.threads);
  const int nz = grid.dimensions[2];
  for (int k0 = 0; k0 < nz; k0 += kPlanesPerReport)
  {
    const int k1 = std::min(nz, k0 + kPlanesPerReport);
    const int rows = (k1 - k0) * grid.dimensions[1];
#pragma omp parallel for schedule(dynamic) num_threads(threads)
    for (int row = 0; row < rows; ++row)
    {
      const int k = k0 + row / grid.dimensions[1];
      const int j = row % grid.dimensions[1];
      for (int i = 0; i < grid.dimensions[0]; ++i)
      {
        const Vec3 c{ grid.origin.x + i * s, grid.origin.y + j * s, grid.origin.z + k * s };
        const std::size_t b = binIndex(i / m, j / m, k / m);
        double t[kMaxPopulations][9] = {};
        bool any[kMaxPopulations] = { false, false };
        for (std::size_t q = start[b]; q < start[b + 1]; ++q)
        {
          const Segment& seg = segments[list[q]];
          const double l = segmentLengthInBall(seg.a, seg.b, c, r);
          if (!(l > 0.0))
          {
            continue;
          }
          const Vec3 u = normalized(seg.b - seg.a);
          double* m9 = t[seg.population];
          for (int x = 0; x < 3; ++x)
          {
            for (int y = 0; y < 3; ++y)
            {
              m9[3 * x + y] += l * u[x] * u[y];
            }
          }
          any[seg.population] = true;
        }
        for (int p = 0; p < populations; ++p)
        {
          if (any[p])
          {
            result.fields[static_cast<std::size_t>(p)].vectors[grid.index(i, j, k)] =
              principalAxis(t[p]);
          }
        }
      }
    }
    if (!reportProgress(progress, static_cast<double>(k1) / nz))
    {
      GuideFieldResult stopped;
      stopped.aborted = true;
      return stopped;
    }
  }
  if (byBundle)
  {
    result.bundles = bundles;
  }
  return result;
}

} // namespace fiberpli
