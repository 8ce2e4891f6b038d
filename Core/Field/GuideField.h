/// GuideField: an orientation field made from guide polylines, e.g. tractography streamlines
/// (docs/field-source.md §7). The grid covers the guides' bounds padded by the guide radius; at
/// every grid point the axis is the principal axis of the length-weighted orientation tensor
/// Σ l · u uᵀ of the guide segments within the guide radius (l = the length of the segment inside
/// the ball of that radius about the point, u its direction), and the point is empty where no
/// segment comes that close. The field then goes to the field source's tracer like any other
/// (Field/FieldFibers.h); with one population per bundle id the guides of each bundle make their
/// own field on the shared grid.
#pragma once

#include "Field/OrientationField.h"
#include "Geometry/Vec3.h"
#include "Util/Progress.h"
#include "Util/Status.h"

#include <cstdint>
#include <string>
#include <vector>

namespace fiberpli
{

/// One guide: a polyline in µm and its bundle id.
struct GuideLine
{
  std::vector<Vec3> points;
  std::int64_t bundle = 0;
};

/// `GuidePopulations` property: api strings "One" and "ByBundle".
enum class GuidePopulations
{
  One = 0,     ///< all guides make one field (one population, bundle_id 0)
  ByBundle = 1 ///< the guides of each bundle id make one field, at most two (bundle_id 0, 1)
};

struct GuideFieldOptions
{
  double radius = 5.0;  ///< `GuideRadius`, µm > 0: how far a guide reaches
  double spacing = 1.0; ///< `GuideSpacing`, µm, in (0, radius]: the grid's spacing
  GuidePopulations populations = GuidePopulations::One;
  int threads = 0; ///< 0 = all cores (Util/Threads.h); the fields do not depend on it
};

struct GuideFieldResult : Status
{
  std::vector<OrientationField> fields; ///< one per population, one grid, unit vectors or zero
  std::vector<std::int64_t> bundles; ///< ByBundle: the guides' bundle id of each field, ascending
  std::size_t segments = 0;          ///< guide segments of positive length used
};

/// Empty when the options are usable, else a message naming GuideRadius or GuideSpacing and the
/// value.
std::string validateGuideFieldOptions(const GuideFieldOptions& options);

/// The length of the segment [a, b] inside the open ball of `radius` about `centre`.
double segmentLengthInBall(const Vec3& a, const Vec3& b, const Vec3& centre, double radius);

/// The fields of `guides` (see the file comment). Guides of fewer than 2 points and segments of
/// zero length add nothing. Errors (named): bad options, a point that is not finite (the guide
/// and point index), no segment of positive length at all, more than two bundle ids with
/// ByBundle, a grid beyond the memory budget. Every grid point's tensor sums its segments in guide
/// order, so the fields are the same for any thread count. Progress is reported per slab of grid
/// planes; when it returns false the result is `aborted` with no fields.
GuideFieldResult guideOrientationFields(const std::vector<GuideLine>& guides,
  const GuideFieldOptions& options, const ProgressFn& progress = {});

} // namespace fiberpli
