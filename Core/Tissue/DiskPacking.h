/// DiskPacking: overlap-free 2-D arrangements of disks of given (unequal) radii, the cross-section
/// of a periodic cube with polydisperse fibers (docs/periodic-cells.md, "Polydisperse seeding").
/// A lattice is spaced for one radius; the large fibers of a broad radius distribution do not fit
/// on its sites. Here the disks are placed at random, compressed past jamming as soft disks
/// (harmonic overlap energy, minimised with FIRE), disks of different sizes exchange places where
/// that lowers the energy (swap moves let large disks find large holes, which is what makes
/// polydisperse packings dense), and the packing is then relaxed at the largest scale of the
/// radii at which it separates, which leaves every pair a gap proportional to its radii.
#pragma once

#include "Tissue/Seeds.h"
#include "Util/Progress.h"

#include <cstdint>
#include <vector>

namespace fiberpli
{

/// The region [0, width) × [0, height]: periodic along the width; along the height periodic too,
/// or bounded by two walls (a disk must lie inside, y − r >= 0 and y + r <= height).
struct DiskDomain
{
  double width = 0.0;
  double height = 0.0;
  bool periodicHeight = true;
};

struct DiskPacking
{
  /// centres[i]: the centre of disk i (radius radii[i]) in the domain.
  std::vector<Seed2D> centres;
  /// The largest s for which disks of radii s · radii[i] at these centres neither overlap
  /// (minimum image) nor cross a wall, up to 1.1 (larger values are reported as 1.1); >= 1 means
  /// the requested disks are overlap-free.
  double scale = 0.0;
  /// The progress callback asked to stop: no centres, scale 0.
  bool aborted = false;
};

/// Packs the disks, deterministic for (seed, key) (the random start and the distant swap partners
/// are the stream (seed, key, 0)), at as large a scale as it finds: of the arrangements it reaches
/// (one per compress–swap–decompress cycle) it returns the one with the largest scale, i.e. the
/// smallest overlap relative to the radii. Below 1 the disks could not be separated and overlap
/// (the caller should say so). An empty list, an empty or infinite domain, or any radius that is
/// not finite and > 0 gives an empty packing (no centres, scale 0). The cost grows with the disk
/// count (docs/periodic-cells.md, "Polydisperse seeding"); the memory is diskPackingBytes.
/// progress (Util/Progress.h) is called after every relaxation and at the end of every cycle;
/// false stops the packing (aborted).
DiskPacking packDisks(const std::vector<double>& radii, const DiskDomain& domain,
  std::uint64_t seed, std::uint64_t key, const ProgressFn& progress = {});

/// An upper estimate of the bytes packDisks allocates for this many disks (for a memory guard).
double diskPackingBytes(double disks);

} // namespace fiberpli
