#include "Tissue/BundleGenerator.h"

#include "Model/FiberPieces.h"
#include "Tissue/Beading.h"
#include "Tissue/BundleShapes.h"
#include "Tissue/Dispersion.h"
#include "Tissue/Undulation.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace fiberpli
{

namespace
{
constexpr double kDegree = M_PI / 180.0;
// The largest tilt of a dispersed bundle fiber (75°: a fiber at most 3.9 times its path's length).
constexpr double kMaxBundleTilt = 75.0 * kDegree;

struct Path
{
  ResampledTrajectory trajectory;
  TrajectoryFrames frames;
};

Path makePath(
  const std::vector<Vec3>& control, const std::vector<double>* scale, double segmentLength)
{
  Path p;
  p.trajectory = resampleTrajectory(control, scale, segmentLength);
  p.frames = transportFrames(p.trajectory.points);
  return p;
}

RanvierOptions ranvierOf(const BundleOptions& o)
{
  RanvierOptions r;
  r.spacing = effectiveRanvierSpacing(o);
  r.depth = o.ranvierDepth;
  r.length = o.ranvierLength;
  return r;
}

// The fibers of one bundle in output order: `members` (indices into cs) laid along path.
struct Bundle
{
  const Path* path;
  std::vector<CrossSectionFiber>* cs;
  std::vector<std::size_t> members;
  int bundle;
};

// Lays the fibers of the bundles (in order: global fiber index = position in that order) that
// fall into `range`; the others only take part in the cross-sections (seeds, radii, splits).
FiberModel layBundles(
  const std::vector<Bundle>& bundles, const FiberRange& range, const BundleOptions& o)
{
  const RanvierOptions ranvier = ranvierOf(o);
  FiberModel model;
  model.fibers.reserve(range.size());
  std::size_t next = 0;
  for (const Bundle& b : bundles)
  {
    for (std::size_t idx : b.members)
    {
      if (next >= range.begin && next < range.end)
      {
        Fiber f = layFiber(b.path->trajectory, b.path->frames, (*b.cs)[idx], ranvier,
          o.displacement, o.realism, o.segmentLength, o.seed);
        f.id = static_cast<std::int64_t>(next);
        f.bundle = b.bundle;
        model.fibers.push_back(std::move(f));
      }
      ++next;
    }
  }
  return model;
}

FiberModel layBundles(
  const std::vector<Bundle>& bundles, int piece, int pieces, const BundleOptions& o)
{
  std::size_t total = 0;
  for (const Bundle& b : bundles)
  {
    total += b.members.size();
  }
  return layBundles(bundles, pieceRange(total, piece, pieces), o);
}

std::vector<std::size_t> allOf(const std::vector<CrossSectionFiber>& cs)
{
  std::vector<std::size_t> idx(cs.size());
  std::iota(idx.begin(), idx.end(), std::size_t{ 0 });
  return idx;
}

void splitChiasmNerve(const std::vector<CrossSectionFiber>& cs, const Path& straight,
  const Vec3& lateral, double fraction, std::vector<std::size_t>& crossing,
  std::vector<std::size_t>& uncrossed)
{
  const Vec3& u0 = straight.frames.u.front();
  const Vec3& v0 = straight.frames.v.front();
  std::vector<std::size_t> order = allOf(cs);
  std::vector<double> key(cs.size());
  for (std::size_t j = 0; j < cs.size(); ++j)
  {
    key[j] = dot(cs[j].seed.x * u0 + cs[j].seed.y * v0, lateral);
  }
  std::stable_sort(
    order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] > key[b]; });
  // The 1e-9 keeps an exact product such as 0.25·76 = 19 from rounding up through a last-bit error.
  const std::size_t count = std::min(cs.size(),
    static_cast<std::size_t>(std::ceil(fraction * static_cast<double>(cs.size()) - 1e-9)));
  uncrossed.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count));
  crossing.assign(order.begin() + static_cast<std::ptrdiff_t>(count), order.end());
  std::sort(uncrossed.begin(), uncrossed.end());
  std::sort(crossing.begin(), crossing.end());
}

double yTurnRadius(const BundleOptions& o)
{
  return std::max(2.0 * o.bundleRadius, 5.0 * o.fiberRadius);
}
// The uncrossed fibers are the lateral ones, on the inside of the side path's bend, up to
// BundleRadius from its centre line: the same max(2R, 5r) as the Y keeps them >= R from the centre
// of the turn.
double chiasmTurnRadius(const BundleOptions& o)
{
  return yTurnRadius(o);
}
// The fiber laid along the trajectory at its seed offset, dispersed: tilted about its middle by a
// Watson angle θ (|cos θ| at the cross-section's quantile sequence, the azimuth from stream
// Dispersion): a drift across the path growing linearly with arc length, so a straight bundle's
// fiber runs at θ to the axis. θ is capped at kMaxBundleTilt so that no fiber runs (nearly) across
// a bundle.
std::vector<Vec3> laidPoints(const ResampledTrajectory& t, const TrajectoryFrames& fr,
  const CrossSectionFiber& cf, const ShapeOptions& shape, std::uint64_t seed)
{
  const std::size_t n = t.points.size();
  std::vector<Vec3> points(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    points[k] = t.points[k] + t.scale[k] * (cf.seed.x * fr.u[k] + cf.seed.y * fr.v[k]);
  }
  if (shape.dispersed())
  {
    const double offset =
      shapeStream(seed, ShapeFeature::Dispersion, cf.crossSection, kGroupStream).uniform();
    const double u1 = dispersionQuantile(offset, cf.key);
    const double u2 =
      shapeStream(seed, ShapeFeature::Dispersion, cf.crossSection, cf.key).uniform();
    const double c = watsonTableForC2(shape.dispersionC2)->cosine(u1);
    const double slope =
      std::min(std::tan(kMaxBundleTilt), std::sqrt(std::max(0.0, 1.0 - c * c)) / c);
    const double phi = 2.0 * M_PI * u2;
    std::vector<double> arc(n, 0.0);
    for (std::size_t k = 1; k < n; ++k)
      arc[k] = arc[k - 1] + distance(t.points[k - 1], t.points[k]);
    for (std::size_t k = 0; k < n; ++k)
      points[k] +=
        (arc[k] - 0.5 * arc.back()) * slope * (std::cos(phi) * fr.u[k] + std::sin(phi) * fr.v[k]);
  }
  return points;
}
} // namespace

FiberShape bundleFiberShape(const ResampledTrajectory& t, const TrajectoryFrames& fr,
  const CrossSectionFiber& cf, double displacement, const ShapeOptions& shape, double segmentLength,
  std::uint64_t seed)
{
  FiberShape target;
  target.base.points = laidPoints(t, fr, cf, shape, seed);
  target.base.u = fr.u;
  target.base.v = fr.v;
  target.radius = cf.radius;
  const double length = polylineLength(target.base.points);
  target.pointCount = undulatedPointCount(length, shape.tortuosity, segmentLength, 2);
  RandomStream jr = shapeStream(seed, ShapeFeature::Jitter, cf.crossSection, cf.key);
  target.jitter = drawJitter(jr, target.pointCount, displacement, false);
  if (shape.undulating())
  {
    RandomStream ur = shapeStream(seed, ShapeFeature::Undulation, cf.crossSection, cf.key);
    target.undulation = drawUndulation(ur, length, shape.undulationWavelength, false);
    target.reached = calibrateUndulation(
      target.base, target.undulation, shape.tortuosity, target.pointCount, &target.jitter);
  }
  return target;
}

Fiber layFiber(const ResampledTrajectory& t, const TrajectoryFrames& fr, CrossSectionFiber& cf,
  const RanvierOptions& ranvier, double displacement, const ShapeOptions& shape,
  double segmentLength, std::uint64_t seed, bool* reached)
{
  Fiber f;
  if (shape.undulating())
  {
    // The undulated fiber replaces the laid polyline, its displacements drawn from the Jitter
    // stream (its point count differs from the straight one's) and counted in the calibration;
    // Ranvier's points then go onto the finished polyline, which they do not bend.
    const FiberShape target = bundleFiberShape(t, fr, cf, displacement, shape, segmentLength, seed);
    if (reached)
      *reached = target.reached;
    f.points = target.points();
    applyRanvier(f, cf.radius, cf.phase, ranvier);
  }
  else
  {
    f.points = laidPoints(t, fr, cf, shape, seed);
    applyRanvier(f, cf.radius, cf.phase, ranvier);
    for (Vec3& p : f.points)
    {
      p.x += cf.rng.uniform(-displacement, displacement);
      p.y += cf.rng.uniform(-displacement, displacement);
      p.z += cf.rng.uniform(-displacement, displacement);
    }
  }
  if (shape.beaded())
  {
    std::vector<double> arc(f.points.size(), 0.0);
    for (std::size_t i = 1; i < arc.size(); ++i)
      arc[i] = arc[i - 1] + distance(f.points[i - 1], f.points[i]);
    RandomStream br = shapeStream(seed, ShapeFeature::Beading, cf.crossSection, cf.key);
    const std::vector<double> factor =
      beadingFactors(drawBeading(br, arc, shape.beadingLength, shape.beadingCV, false));
    for (std::size_t i = 0; i < f.radii.size(); ++i)
      f.radii[i] *= factor[i];
  }
  return f;
}

FiberModel generateBundle(const BundleOptions& o, const std::vector<Vec3>* trajectory,
  const std::vector<double>* trajectoryScale, int piece, int pieces)
{
  if (!validateBundleOptions(o, trajectory, trajectoryScale, pieces).empty())
  {
    return FiberModel{};
  }
  const double H = 0.5 * o.length;
  const double omega = o.crossingAngle * kDegree;
  switch (o.shape)
  {
    case BundleShape::Cylinder:
    case BundleShape::Trajectory:
    {
      const Path path = o.shape == BundleShape::Cylinder
        ? makePath(straightPath(H, 0.0), nullptr, o.segmentLength)
        : makePath(*trajectory, trajectoryScale, o.segmentLength);
      std::vector<CrossSectionFiber> cs = makeCrossSection(o, 0);
      return layBundles({ { &path, &cs, allOf(cs), 0 } }, piece, pieces, o);
    }
    case BundleShape::Crossing:
    {
      Path path[2];
      std::vector<CrossSectionFiber> cs[2];
      for (int b = 0; b < 2; ++b)
      {
        path[b] = makePath(straightPath(H, b * omega), nullptr, o.segmentLength);
        cs[b] = makeCrossSection(o, static_cast<std::uint64_t>(b));
      }
      return layBundles(
        { { &path[0], &cs[0], allOf(cs[0]), 0 }, { &path[1], &cs[1], allOf(cs[1]), 1 } }, piece,
        pieces, o);
    }
    case BundleShape::YShape:
    {
      std::vector<CrossSectionFiber> cs = makeCrossSection(o, 0);
      std::vector<std::size_t> left;
      std::vector<std::size_t> right;
      for (std::size_t j = 0; j < cs.size(); ++j)
      {
        // The trunk runs along +y; the minimal rotation e_z → e_y keeps e_x, so seed x is world x.
        (cs[j].seed.x < 0.0 ? left : right).push_back(j);
      }
      const double step = 0.25 * o.segmentLength;
      const Path leftPath =
        makePath(yBranchPath(H, omega, yTurnRadius(o), true, step), nullptr, o.segmentLength);
      const Path rightPath =
        makePath(yBranchPath(H, omega, yTurnRadius(o), false, step), nullptr, o.segmentLength);
      return layBundles(
        { { &leftPath, &cs, left, 0 }, { &rightPath, &cs, right, 1 } }, piece, pieces, o);
    }
    case BundleShape::Chiasm:
    {
      std::vector<CrossSectionFiber> cs[2];
      std::vector<std::size_t> crossing[2];
      std::vector<std::size_t> uncrossed[2];
      Path straight[2];
      Path side[2];
      for (int s = 0; s < 2; ++s)
      {
        const Vec3 d = chiasmDirection(omega, s == 1);
        straight[s] = makePath({ -H * d, H * d }, nullptr, o.segmentLength);
        cs[s] = makeCrossSection(o, static_cast<std::uint64_t>(s));
        splitChiasmNerve(cs[s], straight[s], chiasmLateralNormal(omega, s == 1),
          o.uncrossedFraction, crossing[s], uncrossed[s]);
        side[s] =
          makePath(chiasmSidePath(H, omega, chiasmTurnRadius(o), s == 1, 0.25 * o.segmentLength),
            nullptr, o.segmentLength);
      }
      return layBundles(
        { { &straight[0], &cs[0], crossing[0], 0 }, { &straight[1], &cs[1], crossing[1], 1 },
          { &side[0], &cs[0], uncrossed[0], 2 }, { &side[1], &cs[1], uncrossed[1], 3 } },
        piece, pieces, o);
    }
  }
  return FiberModel{};
}

std::string bundleWarnings(const BundleOptions& o, const std::vector<Vec3>* trajectory,
  const std::vector<double>* trajectoryScale)
{
  if (!validateBundleOptions(o, trajectory, trajectoryScale).empty())
  {
    return std::string();
  }
  if (!shapeWarnings(o.realism, o.segmentLength).empty())
  {
    return shapeWarnings(o.realism, o.segmentLength);
  }
  if (o.realism.undulating())
  {
    // Each axis of U[−D, D]³ adds D²/3 per point: a link of length l becomes about √(l² + 2D²)
    // (docs/tissue-models.md §5.2); a fiber whose jitter alone is that tortuous gets no undulation.
    const double jitterAlone =
      std::sqrt(1.0 + 2.0 * o.displacement * o.displacement / (o.segmentLength * o.segmentLength));
    if (jitterAlone >= o.realism.tortuosity)
    {
      std::ostringstream msg;
      msg << "Tortuosity " << o.realism.tortuosity << ": the Displacement " << o.displacement
          << " alone makes the fibers about " << jitterAlone
          << " times longer than their path, so they stay without undulation (lower Displacement)";
      return msg.str();
    }
  }
  ResampledTrajectory t;
  if (o.shape == BundleShape::Trajectory)
  {
    t = resampleTrajectory(*trajectory, trajectoryScale, o.segmentLength);
  }
  else if (o.shape == BundleShape::Chiasm)
  {
    t = resampleTrajectory(chiasmSidePath(0.5 * o.length, o.crossingAngle * kDegree,
                             chiasmTurnRadius(o), false, 0.25 * o.segmentLength),
      nullptr, o.segmentLength);
  }
  else
  {
    return std::string();
  }
  std::size_t where = 0;
  const double rc = minimumCircumradius(t.points, &where);
  const double reach = o.bundleRadius * *std::max_element(t.scale.begin(), t.scale.end());
  if (rc >= reach)
  {
    return std::string();
  }
  std::ostringstream msg;
  msg << (o.shape == BundleShape::Chiasm ? "Chiasm side path" : "Trajectory")
      << " radius of curvature " << rc << " um near resampled point " << where << " ("
      << t.points[where].x << ", " << t.points[where].y << ", " << t.points[where].z
      << ") is smaller than BundleRadius x scale " << reach
      << " um: fibers on the inside of the bend fold over; smooth the trajectory or reduce "
         "BundleRadius";
  return msg.str();
}

} // namespace fiberpli
