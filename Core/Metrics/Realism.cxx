#include "Metrics/Realism.h"

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
const double kPi = 3.14159265358979323846;

/// Arc-length mean and standard deviation of a quantity taken linear along each link (exact
/// integrals of the linear interpolant: ∫v = l·(a + b)/2, ∫v² = l·(a² + ab + b²)/3).
struct LinearMoments
{
  double length = 0.0, sum = 0.0, sumSquares = 0.0;

  void add(double l, double a, double b)
  {
    length += l;
    sum += l * 0.5 * (a + b);
    sumSquares += l * (a * a + a * b + b * b) / 3.0;
  }
  double mean() const { return length > 0.0 ? sum / length : NaN; }
  double cv() const
  {
    if (!(length > 0.0))
    {
      return NaN;
    }
    const double m = sum / length;
    const double variance = std::max(0.0, sumSquares / length - m * m);
    return std::sqrt(variance) / m;
  }
};

/// A length-weighted mean of per-fiber values (NaN values skipped).
struct WeightedMean
{
  double sum = 0.0, weight = 0.0;
  void add(double v, double w)
  {
    if (std::isfinite(v) && w > 0.0)
    {
      sum += v * w;
      weight += w;
    }
  }
  double value() const { return weight > 0.0 ? sum / weight : NaN; }
};

/// Principal eigenvector (sign: largest component positive) and eigenvalue of a tensor sum.
void principal(const double sum[3][3], double weight, Vec3& axis, double& value)
{
  if (!(weight > 0.0))
  {
    axis = Vec3{ NaN, NaN, NaN };
    value = NaN;
    return;
  }
  double t[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      t[r][c] = sum[r][c] / weight;
    }
  }
  double values[3];
  Vec3 vectors[3];
  symmetricEigen3(t, values, vectors);
  axis = vectors[0];
  int largest = 0;
  for (int i = 1; i < 3; ++i)
  {
    largest = std::abs(axis[i]) > std::abs(axis[largest]) ? i : largest;
  }
  if (axis[largest] < 0.0)
  {
    axis = -axis;
  }
  value = values[0];
}

struct PopulationAccumulator
{
  std::vector<std::size_t> fibers;
  double endToEnd[3][3] = {};
  double directions = 0.0;
};

} // namespace

RealismResult measureRealism(const FiberModel& model, const ShapeResult& shape, std::size_t bins)
{
  RealismResult result;
  const bool anyMyelin = hasInnerRadii(model);
  std::map<int, PopulationAccumulator> perBundle;
  std::vector<double> pointRadii, pointGRatios;
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fiber = model.fibers[f];
    PopulationAccumulator& population = perBundle[fiber.bundle];
    population.fibers.push_back(f);
    if (fiber.size() > 1)
    {
      const Vec3 e = fiber.points.back() - fiber.points.front();
      const double l = norm(e);
      if (l > 0.0)
      {
        for (int r = 0; r < 3; ++r)
        {
          for (int c = 0; c < 3; ++c)
          {
            population.endToEnd[r][c] += e[r] * e[c] / (l * l);
          }
        }
        population.directions += 1.0;
      }
    }
    const std::vector<double>& inner = fiber.innerRadii;
    const bool myelin = !inner.empty();
    LinearMoments radius, gRatio;
    for (std::size_t k = 0; k + 1 < fiber.size(); ++k)
    {
      const double l = distance(fiber.points[k], fiber.points[k + 1]);
      radius.add(l, fiber.radii[k], fiber.radii[k + 1]);
      if (myelin)
      {
        gRatio.add(l, inner[k] / fiber.radii[k], inner[k + 1] / fiber.radii[k + 1]);
      }
    }
    result.fiberRadiusCV.push_back(radius.cv());
    result.fiberGRatio.push_back(myelin ? gRatio.mean() : NaN);
    pointRadii.insert(pointRadii.end(), fiber.radii.begin(), fiber.radii.end());
    for (std::size_t i = 0; myelin && i < fiber.size(); ++i)
    {
      pointGRatios.push_back(inner[i] / fiber.radii[i]);
    }
  }

  WeightedMean allCV, allG;
  std::vector<double> angles, angleWeights;
  for (const auto& entry : perBundle)
  {
    const PopulationAccumulator& acc = entry.second;
    PopulationRealism p;
    p.bundle = entry.first;
    p.fibers = acc.fibers.size();
    principal(acc.endToEnd, acc.directions, p.axis, p.c2EndToEnd);
    double cos2 = 0.0, length = 0.0;
    WeightedMean cv, g;
    std::vector<double> tortuosities;
    for (std::size_t f : acc.fibers)
    {
      const Fiber& fiber = model.fibers[f];
      for (std::size_t k = 0; k + 1 < fiber.size() && std::isfinite(p.axis.x); ++k)
      {
        const Vec3 d = fiber.points[k + 1] - fiber.points[k];
        const double l = norm(d);
        if (l > 0.0)
        {
          const double c = std::min(1.0, std::abs(dot(d, p.axis)) / l);
          cos2 += l * c * c;
          length += l;
          angles.push_back(std::acos(c) * 180.0 / kPi);
          angleWeights.push_back(l);
        }
      }
      const double fiberLength = shape.fiberLength[f];
      cv.add(result.fiberRadiusCV[f], fiberLength);
      allCV.add(result.fiberRadiusCV[f], fiberLength);
      g.add(result.fiberGRatio[f], fiberLength); // NaN (no sheath) is skipped
      allG.add(result.fiberGRatio[f], fiberLength);
      tortuosities.push_back(shape.tortuosity[f]);
    }
    p.c2Segments = length > 0.0 ? cos2 / length : NaN;
    p.radiusCV = cv.value();
    p.gRatio = g.value();
    double lo = 0.0, hi = 0.0;
    if (finiteRange(tortuosities, lo, hi))
    {
      double sum = 0.0;
      std::size_t n = 0;
      for (double t : tortuosities)
      {
        if (std::isfinite(t))
        {
          sum += t;
          ++n;
        }
      }
      p.tortuosity = { lo, sum / static_cast<double>(n), hi, n };
    }
    else
    {
      p.tortuosity = { NaN, NaN, NaN, 0 };
    }
    result.populations.push_back(p);
  }
  result.radiusCV = allCV.value();
  result.gRatio = anyMyelin ? allG.value() : NaN;

  // Histograms over the range of their values (angles always over [0, 90] degrees).
  const auto histogramOf = [bins](const std::vector<double>& values)
  {
    double lo = 0.0, hi = 0.0;
    Histogram h =
      finiteRange(values, lo, hi) ? makeHistogram(lo, hi, bins) : makeHistogram(0.0, 1.0, bins);
    for (double v : values)
    {
      addToHistogram(h, v);
    }
    return h;
  };
  result.radiusHistogram = histogramOf(pointRadii);
  result.tortuosityHistogram = histogramOf(shape.tortuosity);
  result.gRatioHistogram = histogramOf(pointGRatios);
  result.segmentAngleHistogram = makeHistogram(0.0, 90.0, bins);
  for (std::size_t i = 0; i < angles.size(); ++i)
  {
    addToHistogram(result.segmentAngleHistogram, angles[i], angleWeights[i]);
  }
  return result;
}

} // namespace fiberpli
