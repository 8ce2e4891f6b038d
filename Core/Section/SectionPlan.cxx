#include "Section/SectionPlan.h"

#include "Model/VolumeOfInterest.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fiberpli
{

std::string checkSectionSizes(double voxelSize, double pixelSize)
{
  return ValueChecks()
    .positive("VoxelSize", voxelSize)
    .require(pixelSize >= voxelSize && std::isfinite(pixelSize), "PixelSize", pixelSize,
      ">= VoxelSize (" + formatNumber(voxelSize) + ")")
    .error();
}

std::string planSection(const FiberModel& model, const double voiIn[6], double voxelSize,
  double pixelSize, SectionPlan& plan)
{
  plan = SectionPlan();
  std::string err = checkSectionSizes(voxelSize, pixelSize);
  if (!err.empty())
    return err;
  double voi[6];
  err = resolveVolumeOfInterest(voiIn, model, voxelSize, voi, plan.lattice.n);
  if (!err.empty())
    return err;
  for (int a = 0; a < 3; ++a)
    plan.lattice.origin[a] = voi[2 * a];
  plan.lattice.voxel = voxelSize;
  plan.pixelSize = pixelSize;
  plan.pixels[0] = pixelCount(plan.lattice.n[0], plan.scale());
  plan.pixels[1] = pixelCount(plan.lattice.n[1], plan.scale());
  if (plan.pixels[0] < 1 || plan.pixels[1] < 1)
  {
    std::ostringstream m;
    m << "PixelSize " << pixelSize << " is larger than the VolumeOfInterest: no pixel";
    return m.str();
  }
  plan.thickness = static_cast<double>(plan.lattice.n[2]) * voxelSize;
  plan.imageOrigin[0] = voi[0] + 0.5 * pixelSize;
  plan.imageOrigin[1] = voi[2] + 0.5 * pixelSize;
  plan.imageOrigin[2] = voi[4] + 0.5 * plan.thickness;
  return {};
}

PixelGrid latticeForPixelGrid(const Vec3& corner, double pixelSize, std::int64_t nx,
  std::int64_t ny, double zMin, double zMax, int samplesPerPixel)
{
  PixelGrid g;
  const int s = samplesPerPixel < 1 ? 1 : samplesPerPixel;
  g.lattice.origin[0] = corner.x;
  g.lattice.origin[1] = corner.y;
  g.lattice.origin[2] = zMin;
  g.pixelSize = pixelSize;
  g.lattice.voxel = pixelSize / s;
  g.lattice.n[0] = nx * s;
  g.lattice.n[1] = ny * s;
  g.lattice.n[2] = std::max<std::int64_t>(1, std::llround((zMax - zMin) / g.lattice.voxel));
  return g;
}

} // namespace fiberpli
