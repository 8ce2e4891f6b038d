#include "Tissue/Ranvier.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{

double ranvierFactor(double s, double phase, const RanvierOptions& o)
{
  if (!(o.spacing > 0.0))
  {
    return 1.0;
  }
  double m = std::fmod(s - phase, o.spacing);
  if (m < 0.0)
  {
    m += o.spacing;
  }
  const double x = std::fabs(m - 0.5 * o.spacing);
  const double half = 0.5 * o.length;
  double g = 0.0;
  if (x <= half)
  {
    g = 1.0;
  }
  else if (x <= o.length)
  {
    g = 0.5 * (1.0 + std::cos(M_PI * (x - half) / half));
  }
  return 1.0 - o.depth * g;
}

void applyRanvier(Fiber& f, double baseRadius, double phase, const RanvierOptions& o)
{
  const std::size_t n = f.points.size();
  std::vector<double> arc(n, 0.0);
  for (std::size_t i = 1; i < n; ++i)
  {
    arc[i] = arc[i - 1] + distance(f.points[i], f.points[i - 1]);
  }
  if (o.spacing > 0.0 && n >= 2)
  {
    const double total = arc.back();
    const double w = o.length;
    double minLink = total;
    for (std::size_t i = 1; i < n; ++i)
    {
      minLink = std::min(minLink, arc[i] - arc[i - 1]);
    }
    const double tol = 0.25 * std::min(0.5 * w, minLink);

    // New arc-length positions: existing points (possibly moved) plus inserted profile points.
    std::vector<double> target(arc);
    std::vector<bool> moved(n, false);
    std::vector<double> inserted;
    const double firstCentre = phase + 0.5 * o.spacing;
    const long mLo = static_cast<long>(std::floor((-w - firstCentre) / o.spacing));
    const long mHi = static_cast<long>(std::ceil((total + w - firstCentre) / o.spacing));
    const double offsets[5] = { -w, -0.5 * w, 0.0, 0.5 * w, w };
    for (long m = mLo; m <= mHi; ++m)
    {
      const double centre = firstCentre + static_cast<double>(m) * o.spacing;
      for (double d : offsets)
      {
        const double s = centre + d;
        if (s <= tol || s >= total - tol)
        {
          continue;
        }
        const std::size_t hi =
          static_cast<std::size_t>(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin());
        const std::size_t near = (hi < n && arc[hi] - s < s - arc[hi - 1]) ? hi : hi - 1;
        if (std::fabs(arc[near] - s) < tol)
        {
          if (near > 0 && near + 1 < n && !moved[near])
          {
            target[near] = s;
            moved[near] = true;
          }
          continue;
        }
        inserted.push_back(s);
      }
    }
    target.insert(target.end(), inserted.begin(), inserted.end());
    std::sort(target.begin(), target.end());

    // Positions on the original polyline at the target arc lengths.
    std::vector<Vec3> points(target.size());
    std::size_t seg = 0;
    for (std::size_t i = 0; i < target.size(); ++i)
    {
      const double s = target[i];
      while (seg + 2 < n && arc[seg + 1] < s)
      {
        ++seg;
      }
      const double len = arc[seg + 1] - arc[seg];
      const double t = len > 0.0 ? std::min(1.0, std::max(0.0, (s - arc[seg]) / len)) : 0.0;
      points[i] = t == 0.0
        ? f.points[seg]
        : (t == 1.0 ? f.points[seg + 1] : (1.0 - t) * f.points[seg] + t * f.points[seg + 1]);
    }
    f.points.swap(points);
    arc.swap(target);
  }
  f.radii.resize(f.points.size());
  for (std::size_t i = 0; i < f.points.size(); ++i)
  {
    f.radii[i] = baseRadius * ranvierFactor(arc[i], phase, o);
  }
}

} // namespace fiberpli
