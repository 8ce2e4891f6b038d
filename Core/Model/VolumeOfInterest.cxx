#include "Model/VolumeOfInterest.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fiberpli
{

bool isBoundsSentinel(const double voi[6])
{
  return voi[0] > voi[1] && voi[2] > voi[3] && voi[4] > voi[5];
}

std::string resolveVolumeOfInterest(const double voi[6], const FiberModel& model, double voxelSize,
  double resolved[6], std::int64_t n[3])
{
  std::copy(voi, voi + 6, resolved);
  if (isBoundsSentinel(voi))
  {
    Vec3 lo, hi;
    if (!modelBounds(model, true, lo, hi))
    {
      return "VolumeOfInterest is the input-bounds sentinel but the input has no fibers";
    }
    const double bounds[6] = { lo.x, hi.x, lo.y, hi.y, lo.z, hi.z };
    std::copy(bounds, bounds + 6, resolved);
  }
  const char* axisName[3] = { "x", "y", "z" };
  std::ostringstream m;
  for (int a = 0; a < 3; ++a)
  {
    const double lo = resolved[2 * a], hi = resolved[2 * a + 1];
    if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi))
    {
      m << "VolumeOfInterest " << axisName[a] << " range [" << lo << ", " << hi
        << "] must have min < max (or min > max on every axis for the input bounds)";
      return m.str();
    }
    const double count = std::round((hi - lo) / voxelSize);
    if (!(count >= 1.0 && count <= 1e9))
    {
      m << "VolumeOfInterest " << axisName[a] << " extent " << hi - lo << " at VoxelSize "
        << voxelSize << " gives " << count << " voxels, needs 1 .. 1e9";
      return m.str();
    }
    n[a] = static_cast<std::int64_t>(count);
  }
  return {};
}

} // namespace fiberpli
