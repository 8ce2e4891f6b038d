/// TubeMesher: one closed, consistently oriented (outward) triangle mesh around every fiber.
/// Rings of `sides` vertices sit at every fiber point, perpendicular to the bisector of the two
/// adjacent links, with the per-point radius. The ring frame is carried along the fiber by parallel
/// transport (rotation-minimising, Geometry/MinimalRotation.h, the rule of the bundle frames; at an
/// exact hairpin the ring turns by its half-turn rule), so rings never twist against each other;
/// repeated points are skipped for directions. Capping closes both ends with a triangle fan around
/// a centre vertex, so every edge is shared by exactly two triangles (watertight). Point normals
/// are the radial directions (the tube axis direction at the cap centres).
#pragma once

#include "Model/FiberModel.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

/// Ring sides beyond which a tube looks no rounder, only heavier. Plugin/FiberTubes.xml repeats it.
constexpr int kMaxTubeSides = 64;

struct TubeOptions
{
  int sides = 12;      ///< vertices per ring, 3 to kMaxTubeSides
  bool capping = true; ///< close the ends (watertight tubes)
  /// Also a tube at the inner radius of every fiber that has inner radii (Fiber::innerRadii, the
  /// axon inside the myelin), after all outer tubes; each tube is closed and outward on its own.
  bool innerTubes = false;
  int numberOfThreads = 0;
};

struct TubeMesh : Status
{
  std::vector<double> points; ///< x, y, z per vertex
  std::vector<float> normals; ///< unit normal per vertex
  std::vector<std::int64_t>
    triangles; ///< 3 vertex indices per triangle, counter-clockwise seen from outside
  std::vector<std::int64_t> triangleFiber; ///< index of the fiber (in model order) of each triangle
  /// With TubeOptions::innerTubes: 0 for a triangle of an outer tube, 1 of an inner tube; else
  /// empty.
  std::vector<std::uint8_t> triangleSurface;

  std::size_t numberOfPoints() const { return points.size() / 3; }
  std::size_t numberOfTriangles() const { return triangles.size() / 3; }
};

/// "" when the options are valid, else the message naming the property (NumberOfSides) and the
/// value.
std::string checkTubeOptions(const TubeOptions& options);

/// Meshes every fiber of the model (preconditions: validateModel(model) and
/// checkTubeOptions(options) are empty). Fibers are
/// meshed in parallel into precomputed slots, so the output does not depend on the thread count.
TubeMesh meshTubes(
  const FiberModel& model, const TubeOptions& options, const ProgressFn& progress = {});

} // namespace fiberpli
