// Independent references for periodic cells (share no code with the solver; distances come from
// BruteForceOverlap.h): the overlap count over all 27 images and the volume fraction by Monte
// Carlo.
#pragma once

#include "BruteForceOverlap.h"
#include "Tissue/CubeGenerator.h"
#include "Util/Random.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace fiberpli_test
{
using fiberpli::Fiber;
using fiberpli::FiberModel;
using fiberpli::RandomStream;

// The periodic cube of the periodic tests: r 0.8 µm, points 2 µm apart, displacement ±0.3 µm.
inline fiberpli::CubeOptions periodicCube(
  int populations, double edge, double phi, std::uint64_t seed = 3)
{
  fiberpli::CubeOptions o;
  o.populations = populations;
  o.edgeLength = edge;
  o.periodic = true;
  o.volumeFraction = phi;
  o.fiberRadius = 0.8;
  o.segmentLength = 2.0;
  o.displacement = 0.3;
  o.seed = seed;
  return o;
}

// Reference pair list by minimum image over all 27 lattice translates, with the same-fiber rule
// written out for closed fibers (the shorter arc way round; adjacent through the closure).
inline std::size_t refPeriodicCount(const FiberModel& m, double L)
{
  const std::vector<RefLink> l = refLinks(m);
  std::vector<double> total(m.fibers.size(), 0.0);
  std::vector<std::size_t> links(m.fibers.size(), 0);
  for (const auto& x : l)
  {
    total[x.fiber] = x.arc1;
    links[x.fiber] = x.k + 1;
  }
  std::size_t count = 0;
  for (std::size_t a = 0; a < l.size(); ++a)
  {
    for (std::size_t b = a + 1; b < l.size(); ++b)
    {
      if (l[a].fiber == l[b].fiber)
      {
        const std::size_t dk = l[b].k - l[a].k;
        if (dk <= 1 || dk + 1 == links[l[a].fiber])
          continue;
        const double inside = l[b].arc0 - l[a].arc1;
        const double around = total[l[a].fiber] - l[b].arc1 + l[a].arc0;
        if (std::min(inside, around) < 2.0 * (l[a].rho + l[b].rho))
          continue;
      }
      double best = HUGE_VAL;
      for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
          for (int k = -1; k <= 1; ++k)
          {
            // Both links wrapped near the origin first, then every image of b.
            const Vec3 ca = 0.5 * (l[a].p0 + l[a].p1);
            const Vec3 cb = 0.5 * (l[b].p0 + l[b].p1);
            Vec3 t;
            for (int d = 0; d < 3; ++d)
              t[d] = -L * std::round((cb[d] - ca[d]) / L);
            t += Vec3{ i * L, j * L, k * L };
            best = std::min(best, refSegmentDistance(l[a].p0, l[a].p1, l[b].p0 + t, l[b].p1 + t));
          }
      if (best < l[a].rho + l[b].rho)
        ++count;
    }
  }
  return count;
}

// Fraction of [-L/2, L/2]³ inside any capsule image, by uniform samples (no cell list: small
// cells).
inline double monteCarloFraction(const FiberModel& m, double L, int samples)
{
  RandomStream rng(99);
  int hits = 0;
  for (int s = 0; s < samples; ++s)
  {
    const Vec3 p{ rng.uniform(-L / 2, L / 2), rng.uniform(-L / 2, L / 2),
      rng.uniform(-L / 2, L / 2) };
    bool inside = false;
    for (const Fiber& f : m.fibers)
    {
      for (std::size_t k = 0; k + 1 < f.size() && !inside; ++k)
      {
        const Vec3 c = 0.5 * (f.points[k] + f.points[k + 1]);
        Vec3 t; // the image of the link nearest to p
        for (int d = 0; d < 3; ++d)
          t[d] = -L * std::round((c[d] - p[d]) / L);
        const double r = std::max(f.radii[k], f.radii[k + 1]);
        inside = refPointSegment(p, f.points[k] + t, f.points[k + 1] + t) < r;
      }
      if (inside)
        break;
    }
    hits += inside ? 1 : 0;
  }
  return double(hits) / samples;
}

} // namespace fiberpli_test
