#include "Metrics/FiberShape.h"

#include "Analysis/OrientationTensor.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace fiberpli
{
namespace
{

const double NaN = std::numeric_limits<double>::quiet_NaN();

class RangeAccumulator
{
public:
  void add(double v)
  {
    if (!std::isfinite(v))
    {
      return;
    }
    min_ = std::min(min_, v);
    max_ = std::max(max_, v);
    sum_ += v;
    ++count_;
  }
  Range range() const
  {
    if (count_ == 0)
    {
      return { NaN, NaN, NaN, 0 };
    }
    return { min_, sum_ / static_cast<double>(count_), max_, count_ };
  }

private:
  double min_ = std::numeric_limits<double>::infinity(),
         max_ = -std::numeric_limits<double>::infinity();
  double sum_ = 0.0;
  std::size_t count_ = 0;
};

/// The length-weighted orientation tensor of the links added so far.
class TensorAccumulator
{
public:
  void add(const Fiber& fiber)
  {
    for (std::size_t k = 0; k + 1 < fiber.size(); ++k)
    {
      const Vec3 d = fiber.points[k + 1] - fiber.points[k];
      const double l = norm(d);
      if (l <= 0.0)
      {
        continue;
      }
      // l·u·uᵀ = d·dᵀ / l
      for (int r = 0; r < 3; ++r)
      {
        for (int c = 0; c < 3; ++c)
        {
          t_[r][c] += d[r] * d[c] / l;
        }
      }
      weight_ += l;
    }
  }

  Orientation orientation() const
  {
    if (weight_ <= 0.0)
    {
      return { NaN, Vec3{ NaN, NaN, NaN } };
    }
    double t[3][3];
    for (int r = 0; r < 3; ++r)
    {
      for (int c = 0; c < 3; ++c)
      {
        t[r][c] = t_[r][c] / weight_;
      }
    }
    double values[3];
    Vec3 vectors[3];
    symmetricEigen3(t, values, vectors);
    Vec3 dir = vectors[0];
    int largest = 0;
    for (int i = 1; i < 3; ++i)
    {
      largest = std::abs(dir[i]) > std::abs(dir[largest]) ? i : largest;
    }
    if (dir[largest] < 0.0)
    {
      dir = -dir;
    }
    return { 1.5 * values[0] - 0.5, dir };
  }

private:
  double t_[3][3] = {};
  double weight_ = 0.0;
};

/// What fiberShape gathers per bundle in its single pass over the fibers.
struct BundleAccumulator
{
  RangeAccumulator tortuosity, length;
  TensorAccumulator tensor;
  std::size_t fibers = 0;
};

} // namespace

ShapeResult fiberShape(const FiberModel& model, const CapsuleSet& set)
{
  ShapeResult result;
  RangeAccumulator tortuosity, linkLength, radius;
  TensorAccumulator tensor;
  // One pass, per-bundle accumulators: bundle_id = fiber index is common (one fiber per bundle).
  std::map<int, BundleAccumulator> perBundle;
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fiber = model.fibers[f];
    const double length = set.fiberLength[f];
    const double ends =
      fiber.size() > 1 ? distance(fiber.points.front(), fiber.points.back()) : 0.0;
    // A closed loop (or a fiber back at its start) has no meaningful tortuosity.
    const double tau = ends > 1e-12 * length ? length / ends : NaN;
    result.fiberLength.push_back(length);
    result.tortuosity.push_back(tau);
    tortuosity.add(tau);
    BundleAccumulator& bundle = perBundle[fiber.bundle];
    bundle.tortuosity.add(tau);
    bundle.length.add(length);
    bundle.tensor.add(fiber);
    ++bundle.fibers;
    tensor.add(fiber);
    for (double r : fiber.radii)
    {
      radius.add(r);
    }
  }
  for (const Capsule& c : set.capsules)
  {
    linkLength.add(distance(c.a, c.b));
  }
  result.orientation = tensor.orientation();
  result.tortuosityRange = tortuosity.range();
  result.linkLength = linkLength.range();
  result.radius = radius.range();
  for (const auto& entry : perBundle)
  {
    BundleShape b;
    b.bundle = entry.first;
    b.fibers = entry.second.fibers;
    b.orientation = entry.second.tensor.orientation();
    b.tortuosity = entry.second.tortuosity.range();
    b.fiberLength = entry.second.length.range();
    result.bundles.push_back(b);
  }
  return result;
}

} // namespace fiberpli
