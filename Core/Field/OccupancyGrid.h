/// OccupancyGrid: a coarse voxel count of the fibers placed so far, so that a source can pick,
/// among a few candidate lines, the one that overlaps them least (docs/field-source.md §4.1). A
/// line's stamp is the set of voxels whose centre lies within its radius of sample points taken
/// every voxel edge along it (and the voxel holding each sample); counts are per sample, not per
/// voxel, so a voxel near a line is counted about 2·radius/edge times: a consistent measure of the
/// overlapped volume for ranking candidates, not a volume.
#pragma once

#include "Geometry/Vec3.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace fiberpli
{

class OccupancyGrid
{
public:
  /// The box [lower, upper] in voxels of edge `edge` (> 0), grown until there are at most
  /// maxVoxels (one byte each).
  OccupancyGrid(const Vec3& lower, const Vec3& upper, double edge, std::size_t maxVoxels);

  /// Σ over the stamp of a line of constant radius of the counts of the lines added so far.
  std::uint64_t overlap(const std::vector<Vec3>& line, double radius) const;

  /// Adds a line's stamp (radius per point; a link samples the larger of its two), counts
  /// saturating at 255.
  void add(const std::vector<Vec3>& line, const std::vector<double>& radii);

  double edge() const { return edge_; }

private:
  template <class Visit>
  void stamp(const std::vector<Vec3>& line, const std::vector<double>* radii, double radius,
    Visit&& visit) const;

  Vec3 lower_;
  double edge_ = 1.0;
  int n_[3] = { 1, 1, 1 };
  std::vector<std::uint8_t> counts_;
};

} // namespace fiberpli
