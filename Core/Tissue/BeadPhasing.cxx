#include "Tissue/BeadPhasing.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

std::vector<std::size_t> beadPhases(
  const std::vector<std::vector<double>>& radii, const std::vector<Seed2D>& centres, double period)
{
  const std::size_t n = std::min(radii.size(), centres.size());
  std::vector<std::size_t> shift(n, 0);
  std::vector<double> largest(n, 0.0);
  for (std::size_t j = 0; j < n; ++j)
    for (double r : radii[j])
      largest[j] = std::max(largest[j], r);
  // A grid of cells at least the largest reach wide: the candidates of fiber j are in its cell and
  // the 8 around it.
  double reach = 0.0;
  for (double r : largest)
    reach = std::max(reach, 2.0 * r);
  int cells = std::max(1, std::min(1024, static_cast<int>(std::floor(period / reach))));
  if (cells < 3)
    cells = 1; // one cell holds every fiber (the 3 x 3 block would visit a cell twice)
  const double width = period / cells;
  const auto cellOf = [&](double t)
  {
    double w = std::fmod(t, period);
    if (w < 0.0)
      w += period;
    return std::min(cells - 1, static_cast<int>(w / width));
  };
  std::vector<std::vector<std::size_t>> grid(static_cast<std::size_t>(cells) * cells);
  std::vector<std::size_t> near;
  std::vector<double> gap;
  for (std::size_t j = 0; j < n; ++j)
  {
    const std::size_t m = radii[j].size();
    const int cx = cellOf(centres[j].x), cy = cellOf(centres[j].y);
    near.clear();
    gap.clear();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
      {
        if (cells == 1 && (dx != 0 || dy != 0))
          continue;
        const int gx = (cx + dx + cells) % cells, gy = (cy + dy + cells) % cells;
        for (std::size_t i : grid[static_cast<std::size_t>(gx) * cells + gy])
        {
          if (radii[i].size() != m)
            continue;
          double ex = centres[j].x - centres[i].x, ey = centres[j].y - centres[i].y;
          ex -= period * std::round(ex / period);
          ey -= period * std::round(ey / period);
          const double d = std::sqrt(ex * ex + ey * ey);
          if (d < largest[j] + largest[i])
          {
            near.push_back(i);
            gap.push_back(d);
          }
        }
      }
    if (m > 0 && !near.empty())
    {
      double best = HUGE_VAL;
      for (std::size_t s = 0; s < m; ++s)
      {
        double cost = 0.0;
        for (std::size_t q = 0; q < near.size(); ++q)
        {
          const std::vector<double>& ri = radii[near[q]];
          const std::size_t si = shift[near[q]];
          for (std::size_t p = 0; p < m; ++p)
          {
            const double o = radii[j][(p + s) % m] + ri[(p + si) % m] - gap[q];
            cost += o > 0.0 ? o * o : 0.0;
          }
        }
        if (cost < best)
        {
          best = cost;
          shift[j] = s;
        }
      }
    }
    grid[static_cast<std::size_t>(cx) * cells + cy].push_back(j);
  }
  return shift;
}

} // namespace fiberpli
