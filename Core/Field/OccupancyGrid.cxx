#include "Field/OccupancyGrid.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

OccupancyGrid::OccupancyGrid(
  const Vec3& lower, const Vec3& upper, double edge, std::size_t maxVoxels)
  : lower_(lower)
  , edge_(edge)
{
  const Vec3 e = upper - lower;
  const double extent[3] = { e.x, e.y, e.z };
  while (true)
  {
    double voxels = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      n_[a] = std::max(1, static_cast<int>(std::ceil(extent[a] / edge_)));
      voxels *= n_[a];
    }
    if (voxels <= static_cast<double>(maxVoxels))
    {
      break;
    }
    edge_ *= 1.25;
  }
  counts_.assign(static_cast<std::size_t>(n_[0]) * n_[1] * n_[2], 0);
}

// Samples every voxel edge along each link (both ends included once), and for each sample the
// voxels whose centres lie within the radius, plus the sample's own voxel (a radius below half an
// edge may reach no centre). Voxels outside the box are skipped.
template <class Visit>
void OccupancyGrid::stamp(const std::vector<Vec3>& line, const std::vector<double>* radii,
  double radius, Visit&& visit) const
{
  const auto voxelOf = [this](const Vec3& p, int a)
  { return static_cast<int>(std::floor((p[a] - lower_[a]) / edge_)); };
  const auto sample = [&](const Vec3& p, double r)
  {
    const Vec3 reach{ r, r, r };
    const Vec3 low = p - reach;
    const Vec3 high = p + reach;
    int from[3];
    int to[3];
    int own[3];
    for (int a = 0; a < 3; ++a)
    {
      own[a] = voxelOf(p, a);
      from[a] = std::max(0, voxelOf(low, a));
      to[a] = std::min(n_[a] - 1, voxelOf(high, a));
    }
    for (int k = from[2]; k <= to[2]; ++k)
    {
      const double dz = lower_.z + (k + 0.5) * edge_ - p.z;
      for (int j = from[1]; j <= to[1]; ++j)
      {
        const double dy = lower_.y + (j + 0.5) * edge_ - p.y;
        for (int i = from[0]; i <= to[0]; ++i)
        {
          const double dx = lower_.x + (i + 0.5) * edge_ - p.x;
          const bool inside = dx * dx + dy * dy + dz * dz <= r * r;
          if (inside || (i == own[0] && j == own[1] && k == own[2]))
          {
            visit((static_cast<std::size_t>(k) * n_[1] + j) * n_[0] + i);
          }
        }
      }
    }
  };
  for (std::size_t p = 0; p < line.size(); ++p)
  {
    const double rp = radii ? (*radii)[p] : radius;
    if (p + 1 == line.size())
    {
      sample(line[p], rp);
      break;
    }
    const double r = radii ? std::max(rp, (*radii)[p + 1]) : radius;
    const Vec3 d = line[p + 1] - line[p];
    const int steps = std::max(1, static_cast<int>(std::ceil(norm(d) / edge_)));
    for (int s = 0; s < steps; ++s)
    {
      sample(line[p] + (static_cast<double>(s) / steps) * d, r);
    }
  }
}

std::uint64_t OccupancyGrid::overlap(const std::vector<Vec3>& line, double radius) const
{
  std::uint64_t sum = 0;
  stamp(line, nullptr, radius, [&](std::size_t v) { sum += counts_[v]; });
  return sum;
}

void OccupancyGrid::add(const std::vector<Vec3>& line, const std::vector<double>& radii)
{
  stamp(line, &radii, 0.0,
    [&](std::size_t v)
    {
      if (counts_[v] < 255)
      {
        ++counts_[v];
      }
    });
}

} // namespace fiberpli
