/**
 * @class   FiberH5Format
 * @brief   fastPLI HDF5 fiber bundles (.h5) through VTK's HDF5 library
 *
 * Layout (docs/api.md §4, fastPLI `io.fiber_bundles`): the root — or the group given to fastPLI's
 * `save(..., group_name=...)` — holds one group per bundle named "0",
 * "1", …; each group holds one float64 dataset of shape (n, 4) — x, y, z, r per point — per fiber,
 * named "0", "1", …. Names are ordered numerically (HDF5 lists "10" before "2"). The bundle index
 * becomes bundle_id; fibers get consecutive fiber ids in bundle/fiber order. This lives in the
 * Readers module, not in Core, because it needs ParaView's HDF5 (docs/architecture.md §5).
 */
#ifndef FiberH5Format_h
#define FiberH5Format_h

#include "Geometry/PeriodicCell.h"
#include "Model/FiberModel.h"

#include <string>

namespace fiberpli
{

class FiberH5Format
{
public:
  /// True when `path` is an HDF5 file in which the root or some group (hard links, 8 levels deep)
  /// holds bundles: a group "0" with a dataset "0" of shape (n, 4).
  static bool LooksLikeFiberH5(const std::string& path);

  /// Reads the bundles of `group` of `path` into `model` (`group` "" = the one group holding
  /// bundles, root included, or the root when none does; several such groups are an error listing
  /// them); returns an
  /// empty string or an error naming the file and the group/dataset. Below the group only hard
  /// links are followed (soft and external links are errors), bundle group names must be
  /// 0 .. INT_MAX, and the total of the declared points (a dataset hard-linked n times counts n
  /// times) is checked against the file size and the memory budget before any allocation.
  /// cell (optional) receives the attribute `periodic_cell` (6 float64: xmin xmax ymin ymax zmin
  /// zmax) of the group when present (else it is left disabled); a malformed one is an error. A
  /// fiber dataset's float64 attributes `inner_radius`, `inner_radius_1`, … (together one value per
  /// point, finite in (0, r]) become Fiber::innerRadii; malformed ones are an error naming the
  /// dataset.
  static std::string Read(const std::string& path, const std::string& group, FiberModel& model,
    PeriodicCell* cell = nullptr);

  /// Writes `model` to `path` the way every FiberPLI writer does (IO/AtomicFile.h): the HDF5 file
  /// is built in memory and written to an exclusive temporary file that replaces the target only
  /// when complete; the target's permission bits are kept. Fibers are grouped by bundle_id in
  /// increasing order. An enabled cell is stored as the root attribute `periodic_cell`, a fiber's
  /// inner radii as attributes of its dataset (`inner_radius`, then `inner_radius_1`, … for every
  /// further 4096 points: the original HDF5 object header holds no attribute above 64 KiB) (fastPLI
  /// ignores attributes it does not know; the (n, 4) datasets are unchanged). Returns an empty
  /// string or an error naming the file.
  static std::string Write(
    const std::string& path, const FiberModel& model, const PeriodicCell& cell = PeriodicCell{});
};

} // namespace fiberpli

#endif
// VTK-HeaderTest-Exclude: FiberH5Format.h
