#include "Tissue/CubeGenerator.h"

#include "Util/MemoryBudget.h"
#include "Util/Random.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fiberpli
{

namespace
{
int pointsPerFiber(const CubeOptions& o)
{
  return std::max(2, static_cast<int>(std::lround(o.edgeLength / o.segmentLength)) + 1);
}
} // namespace

std::string validateCubeOptions(const CubeOptions& o)
{
  std::ostringstream msg;
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
  else if (!std::isfinite(o.edgeLength) || o.edgeLength <= 2.0 * o.fiberRadius)
  {
    msg << "EdgeLength is " << o.edgeLength << ", must be > 2 * FiberRadius";
  }
  else if (!std::isfinite(o.segmentLength) || o.segmentLength <= 0.0)
  {
    msg << "SegmentLength is " << o.segmentLength << ", must be > 0";
  }
  else if (!std::isfinite(o.displacement) || o.displacement < 0.0)
  {
    msg << "Displacement is " << o.displacement << ", must be >= 0";
  }
  else
  {
    const double fibers = static_cast<double>(o.numberOfFibers);
    const double points = fibers * (o.edgeLength / o.segmentLength + 2.0);
    std::ostringstream what;
    what << "NumberOfFibers " << o.numberOfFibers << " with EdgeLength " << o.edgeLength
         << " and SegmentLength " << o.segmentLength << " (" << points << " points)";
    const std::string problem = checkMemoryBudget(fiberModelBytes(fibers, points), what.str());
    if (!problem.empty())
    {
      msg << problem << "; it would need too many points";
    }
  }
  return msg.str();
}

int cubePopulationSize(const CubeOptions& o, int k)
{
  return o.numberOfFibers / o.populations + (k < o.numberOfFibers % o.populations ? 1 : 0);
}

FiberModel generateCube(const CubeOptions& o)
{
  FiberModel model;
  model.fibers.reserve(static_cast<std::size_t>(o.numberOfFibers));
  const int n = pointsPerFiber(o);
  const double half = 0.5 * o.edgeLength;
  std::int64_t nextId = 0;
  for (int k = 0; k < o.populations; ++k)
  {
    const int axis = k;
    const int other1 = (axis + 1) % 3;
    const int other2 = (axis + 2) % 3;
    const int count = cubePopulationSize(o, k);
    for (int j = 0; j < count; ++j)
    {
      RandomStream rng(o.seed, static_cast<std::uint64_t>(k), static_cast<std::uint64_t>(j));
      Fiber f;
      f.id = nextId++;
      f.bundle = k;
      const double t1 = rng.uniform(-half, half);
      const double t2 = rng.uniform(-half, half);
      f.points.resize(static_cast<std::size_t>(n));
      f.radii.assign(static_cast<std::size_t>(n), o.fiberRadius);
      for (int i = 0; i < n; ++i)
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
      model.fibers.push_back(std::move(f));
    }
  }
  return model;
}

} // namespace fiberpli
