#include "Tissue/BundleOptions.h"

#include "Model/FiberModel.h"
#include "Tissue/Trajectory.h"
#include "Util/MemoryBudget.h"
#include "Util/NumberFormat.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace fiberpli
{

namespace
{
int crossSectionCount(BundleShape shape)
{
  return (shape == BundleShape::Crossing || shape == BundleShape::Chiasm) ? 2 : 1;
}

// Seeds examined per cross-section (the grid before cropping, or the random count).
double seedCandidates(const BundleOptions& o)
{
  if (o.numberOfFibers > 0)
  {
    return static_cast<double>(o.numberOfFibers);
  }
  const double half = o.bundleRadius + o.fiberSpacing;
  const double h = o.fiberSpacing * std::sqrt(3.0) / 2.0;
  return (2.0 * half / o.fiberSpacing + 3.0) * (2.0 * half / h + 1.0);
}
} // namespace

const char* bundleShapeName(BundleShape shape)
{
  switch (shape)
  {
    case BundleShape::Cylinder:
      return "Cylinder";
    case BundleShape::Trajectory:
      return "Trajectory";
    case BundleShape::Crossing:
      return "Crossing";
    case BundleShape::YShape:
      return "YShape";
    case BundleShape::Chiasm:
      return "Chiasm";
  }
  return "Unknown";
}

bool parseBundleShape(const std::string& text, BundleShape& shape)
{
  for (BundleShape s : { BundleShape::Cylinder, BundleShape::Trajectory, BundleShape::Crossing,
         BundleShape::YShape, BundleShape::Chiasm })
  {
    if (text == bundleShapeName(s))
    {
      shape = s;
      return true;
    }
  }
  return false;
}

double effectiveRanvierSpacing(const BundleOptions& o)
{
  if (o.ranvierSpacing >= 0.0)
  {
    return o.ranvierSpacing;
  }
  return o.shape == BundleShape::Chiasm ? 20.0 : 0.0;
}

std::string validateBundleOptions(const BundleOptions& o, const std::vector<Vec3>* trajectory,
  const std::vector<double>* trajectoryScale, int pieces)
{
  const double ranvier = effectiveRanvierSpacing(o);
  const bool usesLength = o.shape != BundleShape::Trajectory;
  const auto finite = [](double v) { return std::isfinite(v); };
  const bool crossing = o.shape == BundleShape::Crossing;
  const bool branching = o.shape == BundleShape::YShape || o.shape == BundleShape::Chiasm;
  BundleShape known;
  std::string bundleRadius;
  if (!finite(o.bundleRadius) || o.bundleRadius < o.fiberRadius)
  {
    bundleRadius = "BundleRadius " + formatNumber(o.bundleRadius) +
      " is smaller than FiberRadius " + formatNumber(o.fiberRadius) + " (or not finite)";
  }
  const std::string checked =
    ValueChecks()
      .then(bundleShapeFromCode(static_cast<int>(o.shape), known))
      .require(finite(o.fiberRadius) && o.fiberRadius > 0.0, "FiberRadius", o.fiberRadius, "> 0")
      .then(bundleRadius)
      .require(!usesLength || (finite(o.length) && o.length > 0.0), "Length", o.length, "> 0")
      .then(validateRadiusDistribution(o.radiusDistribution, o.radiusSpread))
      .require(
        o.numberOfFibers >= 0, "NumberOfFibers", o.numberOfFibers, ">= 0 (0 = triangular grid)")
      .require(o.numberOfFibers != 0 || (finite(o.fiberSpacing) && o.fiberSpacing > 0.0),
        "FiberSpacing", o.fiberSpacing, "> 0 when NumberOfFibers is 0")
      .require(
        finite(o.segmentLength) && o.segmentLength > 0.0, "SegmentLength", o.segmentLength, "> 0")
      .require(
        finite(o.displacement) && o.displacement >= 0.0, "Displacement", o.displacement, ">= 0")
      .require(
        !crossing || (finite(o.crossingAngle) && o.crossingAngle > 0.0 && o.crossingAngle <= 180.0),
        "CrossingAngle", o.crossingAngle, "in (0, 180] for Shape Crossing")
      .require(
        !branching || (finite(o.crossingAngle) && o.crossingAngle > 0.0 && o.crossingAngle < 180.0),
        "CrossingAngle", o.crossingAngle,
        std::string("in (0, 180) for Shape ") + bundleShapeName(o.shape))
      .require(o.shape != BundleShape::Chiasm ||
          (finite(o.uncrossedFraction) && o.uncrossedFraction >= 0.0 && o.uncrossedFraction <= 1.0),
        "UncrossedFraction", o.uncrossedFraction, "in [0, 1]")
      .then(validateShapeOptions(o.realism))
      .require(finite(o.ranvierSpacing), "RanvierSpacing", o.ranvierSpacing, "finite")
      .require(!(ranvier > 0.0) ||
          (finite(o.ranvierDepth) && o.ranvierDepth >= 0.0 && o.ranvierDepth < 1.0),
        "RanvierDepth", o.ranvierDepth, "in [0, 1)")
      .require(!(ranvier > 0.0) ||
          (finite(o.ranvierLength) && o.ranvierLength > 0.0 && 2.0 * o.ranvierLength <= ranvier),
        "RanvierLength", o.ranvierLength,
        "> 0 and at most RanvierSpacing/2 = " + formatNumber(0.5 * ranvier))
      .error();
  if (!checked.empty())
  {
    return checked;
  }
  std::ostringstream msg;

  double pathLength = o.length;
  if (o.shape == BundleShape::Trajectory)
  {
    if (!trajectory)
    {
      return "Shape Trajectory needs an input polyline (input port 0)";
    }
    const std::string bad = validateTrajectory(*trajectory, trajectoryScale);
    if (!bad.empty())
    {
      return bad;
    }
    pathLength = polylineLength(*trajectory);
  }
  // The chiasm's side path and a Catmull–Rom curve are longer than the straight estimate: × 1.5.
  pathLength *= 1.5;
  const double fibers = seedCandidates(o) * crossSectionCount(o.shape);
  // A dispersed fiber is about 1/cos θ longer than its path (θ at most 75°): 1.5/√c2 covers the
  // mean of that with room to spare.
  const double tilt =
    o.realism.dispersed() ? std::min(3.9, 1.5 / std::sqrt(o.realism.dispersionC2)) : 1.0;
  const double perFiber = tilt * o.realism.tortuosity * pathLength / o.segmentLength + 2.0 +
    (ranvier > 0.0 ? 5.0 * (pathLength / ranvier + 2.0) : 0.0);
  // Fibers alone first (a tiny FiberSpacing), then with their points.
  const std::string fiberProblem =
    checkMemoryBudget(fiberModelBytes(fibers, 2.0 * fibers), "the fibers");
  const double share = 1.0 / std::max(1, pieces);
  const std::string pointProblem =
    checkMemoryBudget(fiberModelBytes(share * fibers, share * fibers * perFiber),
      pieces > 1 ? "the points of one piece of " + std::to_string(pieces)
                 : std::string("the points"));
  if (!fiberProblem.empty())
  {
    msg << "BundleRadius " << o.bundleRadius << " with FiberSpacing " << o.fiberSpacing
        << " / NumberOfFibers " << o.numberOfFibers << " would need about " << fibers
        << " fibers, more than the limit: " << fiberProblem;
  }
  else if (!pointProblem.empty())
  {
    msg << "Length " << pathLength / 1.5 << " with SegmentLength " << o.segmentLength
        << " (and RanvierSpacing " << ranvier << ") for about " << fibers
        << " fibers would need about " << fibers * perFiber
        << " points, more than the limit: " << pointProblem;
  }
  return msg.str();
}

} // namespace fiberpli
