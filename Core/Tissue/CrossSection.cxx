#include "Tissue/CrossSection.h"

namespace fiberpli
{

std::vector<CrossSectionFiber> makeCrossSection(const BundleOptions& o, std::uint64_t crossSection)
{
  const double lambda = effectiveRanvierSpacing(o);
  const double R = o.bundleRadius;
  std::vector<CrossSectionFiber> fibers;
  auto drawFiber = [&](std::size_t key, const Seed2D* gridSeed)
  {
    CrossSectionFiber f{ {}, 0.0, 0.0, key, RandomStream(o.seed, crossSection, key), crossSection };
    const double u1 = f.rng.uniform();
    const double u2 = f.rng.uniform();
    f.radius = drawFiberRadius(f.rng, o.fiberRadius, o.radiusSpread, o.radiusDistribution, R);
    // Drawn even with Ranvier off, so switching it on does not change the displacements.
    const double phaseDraw = f.rng.uniform();
    f.phase = lambda > 0.0 ? phaseDraw * lambda : 0.0;
    f.seed = gridSeed ? *gridSeed : randomSeedInDisc(u1, u2, R - f.radius);
    if (!gridSeed || seedInsideCircle(f.seed, f.radius, R))
    {
      fibers.push_back(f);
    }
  };
  if (o.numberOfFibers > 0)
  {
    fibers.reserve(static_cast<std::size_t>(o.numberOfFibers));
    for (int j = 0; j < o.numberOfFibers; ++j)
    {
      drawFiber(static_cast<std::size_t>(j), nullptr);
    }
  }
  else
  {
    const std::vector<Seed2D> grid =
      triangularGrid(R + o.fiberSpacing, R + o.fiberSpacing, o.fiberSpacing);
    for (std::size_t g = 0; g < grid.size(); ++g)
    {
      drawFiber(g, &grid[g]);
    }
  }
  return fibers;
}

} // namespace fiberpli
