/// CubeGenerator: the paper's cube benchmark (tissue-models.md §6.1). Straight fibers of 1, 2 or 3
/// mutually perpendicular populations (x; x+y; x+y+z) placed uniformly at random in a cube of edge
/// L centred at the origin, n = max(2, round(L/l) + 1) points per fiber, every point displaced by
/// U[-D, D] per axis, constant radius. bundle = population index (0, 1, 2).
#pragma once

#include "Model/FiberModel.h"

#include <cstdint>
#include <string>

namespace fiberpli
{

struct CubeOptions
{
  int populations = 1;             ///< 1..3
  int numberOfFibers = 1000;       ///< split as evenly as possible over the populations
  double edgeLength = 51.961524227066320; ///< √3·30 µm
  double fiberRadius = 0.8;        ///< µm
  double segmentLength = 2.0;      ///< µm, point spacing before displacement
  double displacement = 0.5;       ///< µm, D of U[-D, D]³
  std::uint64_t seed = 42;
};

/// Empty string when the options are usable, else a message naming the option and its value.
std::string validateCubeOptions(const CubeOptions& options);

/// Number of fibers of population k (0-based) when options.numberOfFibers are split.
int cubePopulationSize(const CubeOptions& options, int k);

/// Generates the cube. Fiber ids are 0..N-1 in population order. The draws of fiber j of population
/// k come from the stream (seed, k, j): transverse position (2), then displacements point by point.
/// Precondition: validateCubeOptions(options) is empty.
FiberModel generateCube(const CubeOptions& options);

} // namespace fiberpli
