#include "Section/SectionReach.h"

namespace fiberpli
{

TileReach columnsReach(const SectionLattice& lat, const GridRange& c, double radiusScale)
{
  TileReach r;
  if (c.nx() < 1 || c.ny() < 1 || lat.n[2] < 1)
  {
    return r;
  }
  const std::int64_t lo[3] = { c.i0, c.j0, 0 }, hi[3] = { c.i1, c.j1, lat.n[2] };
  for (int a = 0; a < 3; ++a)
  {
    r.box[2 * a] = lat.origin[a] + (static_cast<double>(lo[a]) - 0.5) * lat.voxel;
    r.box[2 * a + 1] = lat.origin[a] + (static_cast<double>(hi[a]) + 0.5) * lat.voxel;
  }
  r.radiusScale = radiusScale;
  return r;
}

} // namespace fiberpli
