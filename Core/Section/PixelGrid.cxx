#include "Section/PixelGrid.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fiberpli
{

std::string validatePixelRange(std::int64_t nx, std::int64_t ny, const GridRange& r)
{
  std::ostringstream msg;
  if (nx < 0 || ny < 0)
  {
    msg << "image size " << nx << " x " << ny << " is negative";
  }
  else if (r.i0 < 0 || r.i1 > nx || r.i0 > r.i1)
  {
    msg << "pixel range i [" << r.i0 << ", " << r.i1 << ") is not inside [0, " << nx << ")";
  }
  else if (r.j0 < 0 || r.j1 > ny || r.j0 > r.j1)
  {
    msg << "pixel range j [" << r.j0 << ", " << r.j1 << ") is not inside [0, " << ny << ")";
  }
  return msg.str();
}

std::int64_t pixelOfVoxel(std::int64_t i, double scale)
{
  return static_cast<std::int64_t>(std::floor((static_cast<double>(i) + 0.5) * scale));
}

std::int64_t pixelCount(std::int64_t nVoxels, double scale)
{
  return static_cast<std::int64_t>(std::llround(static_cast<double>(nVoxels) * scale));
}

void voxelsOfPixel(
  std::int64_t p, double scale, std::int64_t nVox, std::int64_t& first, std::int64_t& last)
{
  const std::int64_t npx = pixelCount(nVox, scale);
  first = last = 0;
  if (p < 0 || p >= npx)
    return;
  // Start a little before the analytic bound and walk: the integer function decides.
  std::int64_t i = std::max<std::int64_t>(
    0, static_cast<std::int64_t>(std::floor(static_cast<double>(p) / scale)) - 2);
  while (i > 0 && pixelOfVoxel(i - 1, scale) >= p)
    --i;
  while (i < nVox && pixelOfVoxel(i, scale) < p)
    ++i;
  first = i;
  while (i < nVox && pixelOfVoxel(i, scale) == p)
    ++i;
  last = i;
  // Voxels mapped past the last pixel are dropped.
  if (p == npx - 1)
    while (last > first && pixelOfVoxel(last - 1, scale) >= npx)
      --last;
}

std::string checkPixelGrid(const PixelGrid& g, std::int64_t& nx, std::int64_t& ny)
{
  const SectionLattice& l = g.lattice;
  std::ostringstream msg;
  const std::string sizes = ValueChecks()
                              .positive("VoxelSize", l.voxel)
                              .require(std::isfinite(g.pixelSize) && g.pixelSize >= l.voxel,
                                "PixelSize", g.pixelSize, ">= VoxelSize " + formatNumber(l.voxel))
                              .error();
  if (!sizes.empty())
  {
    msg << sizes;
  }
  else if (l.n[0] < 0 || l.n[1] < 0 || l.n[2] < 0)
  {
    msg << "voxel counts " << l.n[0] << " x " << l.n[1] << " x " << l.n[2] << " must be >= 0";
  }
  else if (!std::isfinite(l.origin[0]) || !std::isfinite(l.origin[1]) ||
    !std::isfinite(l.origin[2]))
  {
    msg << "lattice origin is not finite";
  }
  if (!msg.str().empty())
  {
    return msg.str();
  }
  nx = pixelCount(l.n[0], g.scale());
  ny = pixelCount(l.n[1], g.scale());
  return {};
}

GridRange voxelColumnsOf(const PixelGrid& g, const GridRange& px)
{
  const double scale = g.scale();
  std::int64_t a, b, c, d, tmp;
  voxelsOfPixel(px.i0, scale, g.lattice.n[0], a, tmp);
  voxelsOfPixel(px.i1 - 1, scale, g.lattice.n[0], tmp, b);
  voxelsOfPixel(px.j0, scale, g.lattice.n[1], c, tmp);
  voxelsOfPixel(px.j1 - 1, scale, g.lattice.n[1], tmp, d);
  return GridRange{ a, b, c, d };
}

} // namespace fiberpli
