#include "Mesh/TubeMesher.h"

#include "Geometry/MinimalRotation.h"
#include "Util/Threads.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fiberpli
{

namespace
{

/// Unit link directions of a fiber; a zero-length link takes the direction of its neighbour so
/// that repeated points never produce a NaN frame.
std::vector<Vec3> linkDirections(const Fiber& f)
{
  const std::size_t n = f.points.size();
  std::vector<Vec3> dir(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k)
  {
    dir[k] = normalized(f.points[k + 1] - f.points[k]);
  }
  for (std::size_t k = 1; k < dir.size(); ++k) // forward fill
  {
    if (norm2(dir[k]) == 0.0)
    {
      dir[k] = dir[k - 1];
    }
  }
  for (std::size_t k = dir.size() - 1; k-- > 0;) // backward fill for leading zeros
  {
    if (norm2(dir[k]) == 0.0)
    {
      dir[k] = dir[k + 1];
    }
  }
  if (norm2(dir[0]) == 0.0) // all points coincide: any axis will do
  {
    std::fill(dir.begin(), dir.end(), Vec3{ 0.0, 0.0, 1.0 });
  }
  return dir;
}

/// Any unit vector perpendicular to t.
Vec3 perpendicular(const Vec3& t)
{
  const Vec3 a = std::abs(t.x) < 0.6 ? Vec3{ 1.0, 0.0, 0.0 } : Vec3{ 0.0, 1.0, 0.0 };
  return normalized(cross(t, a));
}

/// Ring plane normal at point i: bisector of the adjacent link directions.
Vec3 ringAxis(const std::vector<Vec3>& dir, std::size_t i)
{
  if (i == 0)
  {
    return dir.front();
  }
  if (i == dir.size())
  {
    return dir.back();
  }
  const Vec3 sum = dir[i - 1] + dir[i];
  // A hairpin (antiparallel links) has no bisector: use the incoming direction.
  return norm2(sum) > 1e-12 ? normalized(sum) : dir[i - 1];
}

struct FiberSlot
{
  std::size_t firstPoint = 0;
  std::size_t firstTriangle = 0;
};

void meshFiber(const Fiber& f, std::int64_t fiberIndex, const TubeOptions& o, const FiberSlot& slot,
  TubeMesh& mesh)
{
  const std::size_t n = f.points.size();
  const int sides = o.sides;
  const std::vector<Vec3> dir = linkDirections(f);

  double* pts = mesh.points.data() + 3 * slot.firstPoint;
  float* nrm = mesh.normals.data() + 3 * slot.firstPoint;
  Vec3 axis = ringAxis(dir, 0);
  Vec3 u = perpendicular(axis);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec3 next = ringAxis(dir, i);
    u = normalized(
      rotateMinimal(axis, next, u)); // parallel transport, same rule as the bundle frames
    // Re-orthogonalise against round-off drift so the ring stays planar.
    u = normalized(u - next * dot(u, next));
    if (norm2(u) == 0.0)
    {
      u = perpendicular(next);
    }
    axis = next;
    const Vec3 v = cross(axis, u);
    for (int s = 0; s < sides; ++s)
    {
      const double phi = 2.0 * M_PI * s / sides;
      const Vec3 radial = u * std::cos(phi) + v * std::sin(phi);
      const Vec3 p = f.points[i] + radial * f.radii[i];
      const std::size_t idx =
        3 * (i * static_cast<std::size_t>(sides) + static_cast<std::size_t>(s));
      pts[idx] = p.x;
      pts[idx + 1] = p.y;
      pts[idx + 2] = p.z;
      nrm[idx] = static_cast<float>(radial.x);
      nrm[idx + 1] = static_cast<float>(radial.y);
      nrm[idx + 2] = static_cast<float>(radial.z);
    }
  }

  std::int64_t* tri = mesh.triangles.data() + 3 * slot.firstTriangle;
  std::int64_t* triFiber = mesh.triangleFiber.data() + slot.firstTriangle;
  std::size_t t = 0;
  const auto emit = [&](std::int64_t a, std::int64_t b, std::int64_t c)
  {
    tri[3 * t] = a;
    tri[3 * t + 1] = b;
    tri[3 * t + 2] = c;
    triFiber[t] = fiberIndex;
    ++t;
  };
  const auto ringVertex = [&](std::size_t i, int s)
  {
    return static_cast<std::int64_t>(
      slot.firstPoint + i * static_cast<std::size_t>(sides) + static_cast<std::size_t>(s % sides));
  };
  // (u, v, axis) is right-handed: (around the ring) × (along the axis) points outward.
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    for (int s = 0; s < sides; ++s)
    {
      emit(ringVertex(i, s), ringVertex(i, s + 1), ringVertex(i + 1, s + 1));
      emit(ringVertex(i, s), ringVertex(i + 1, s + 1), ringVertex(i + 1, s));
    }
  }
  if (o.capping)
  {
    const std::size_t c0 = n * static_cast<std::size_t>(sides);
    const std::size_t c1 = c0 + 1;
    const Vec3 a0 = -ringAxis(dir, 0);
    const Vec3 a1 = ringAxis(dir, n - 1);
    const Vec3* centres[2] = { &f.points.front(), &f.points.back() };
    const Vec3* axes[2] = { &a0, &a1 };
    const std::size_t slots[2] = { c0, c1 };
    for (int e = 0; e < 2; ++e)
    {
      pts[3 * slots[e]] = centres[e]->x;
      pts[3 * slots[e] + 1] = centres[e]->y;
      pts[3 * slots[e] + 2] = centres[e]->z;
      nrm[3 * slots[e]] = static_cast<float>(axes[e]->x);
      nrm[3 * slots[e] + 1] = static_cast<float>(axes[e]->y);
      nrm[3 * slots[e] + 2] = static_cast<float>(axes[e]->z);
    }
    const auto centre0 = static_cast<std::int64_t>(slot.firstPoint + c0);
    const auto centre1 = static_cast<std::int64_t>(slot.firstPoint + c1);
    for (int s = 0; s < sides; ++s)
    {
      emit(centre0, ringVertex(0, s + 1), ringVertex(0, s)); // faces -axis at the start
      emit(centre1, ringVertex(n - 1, s), ringVertex(n - 1, s + 1));
    }
  }
}

/// The tubes of `model` at its radii (fiber indices as in the model).
TubeMesh meshTubesAtRadii(const FiberModel& model, const TubeOptions& o, const ProgressFn& progress)
{
  TubeMesh mesh;
  const std::size_t nf = model.fibers.size();
  const auto sides = static_cast<std::size_t>(o.sides);
  std::vector<FiberSlot> slots(nf + 1);
  for (std::size_t f = 0; f < nf; ++f)
  {
    const std::size_t n = model.fibers[f].points.size();
    slots[f + 1].firstPoint = slots[f].firstPoint + n * sides + (o.capping ? 2 : 0);
    slots[f + 1].firstTriangle =
      slots[f].firstTriangle + 2 * sides * (n - 1) + (o.capping ? 2 * sides : 0);
  }
  mesh.points.resize(3 * slots[nf].firstPoint);
  mesh.normals.resize(3 * slots[nf].firstPoint);
  mesh.triangles.resize(3 * slots[nf].firstTriangle);
  mesh.triangleFiber.resize(slots[nf].firstTriangle);

  // Chunks keep progress reports and abort checks on the calling thread, outside parallel regions.
  const std::size_t chunk = std::max<std::size_t>(256, nf / 50);
  const int threads = resolveThreadCount(o.numberOfThreads);
  for (std::size_t begin = 0; begin < nf; begin += chunk)
  {
    const auto end = static_cast<std::int64_t>(std::min(nf, begin + chunk));
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t f = static_cast<std::int64_t>(begin); f < end; ++f)
    {
      meshFiber(
        model.fibers[static_cast<std::size_t>(f)], f, o, slots[static_cast<std::size_t>(f)], mesh);
    }
    if (!reportProgress(progress, static_cast<double>(end) / static_cast<double>(nf)))
    {
      mesh = TubeMesh{};
      mesh.aborted = true;
      return mesh;
    }
  }
  return mesh;
}

} // namespace

std::string checkTubeOptions(const TubeOptions& options)
{
  return ValueChecks().within("NumberOfSides", options.sides, 3, kMaxTubeSides).error();
}

TubeMesh meshTubes(const FiberModel& model, const TubeOptions& o, const ProgressFn& progress)
{
  if (!o.innerTubes)
  {
    return meshTubesAtRadii(model, o, progress);
  }
  // The axons: the fibers that have inner radii, with them as radii; meshed after the outer tubes
  // (the same rings and frames, since the points are the same) and appended behind them.
  FiberModel axons;
  std::vector<std::int64_t> axonFiber;
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fiber = model.fibers[f];
    if (fiber.innerRadii.size() == fiber.size())
    {
      axons.fibers.push_back(fiber);
      axons.fibers.back().radii = fiber.innerRadii;
      axonFiber.push_back(static_cast<std::int64_t>(f));
    }
  }
  const double outerShare = static_cast<double>(model.fibers.size()) /
    static_cast<double>(std::max<std::size_t>(1, model.fibers.size() + axons.fibers.size()));
  TubeMesh mesh =
    meshTubesAtRadii(model, o, [&](double f) { return reportProgress(progress, outerShare * f); });
  if (mesh.aborted)
  {
    return mesh;
  }
  TubeMesh inner = meshTubesAtRadii(axons, o,
    [&](double f) { return reportProgress(progress, outerShare + (1.0 - outerShare) * f); });
  if (inner.aborted)
  {
    return inner;
  }
  const auto offset = static_cast<std::int64_t>(mesh.numberOfPoints());
  mesh.triangleSurface.assign(mesh.numberOfTriangles(), 0);
  mesh.points.insert(mesh.points.end(), inner.points.begin(), inner.points.end());
  mesh.normals.insert(mesh.normals.end(), inner.normals.begin(), inner.normals.end());
  for (std::int64_t v : inner.triangles)
  {
    mesh.triangles.push_back(v + offset);
  }
  for (std::int64_t f : inner.triangleFiber)
  {
    mesh.triangleFiber.push_back(axonFiber[static_cast<std::size_t>(f)]);
  }
  mesh.triangleSurface.resize(mesh.numberOfTriangles(), 1);
  return mesh;
}

} // namespace fiberpli
