#include "Tissue/Myelin.h"

#include <cmath>

namespace fiberpli
{

double lee2019MyelinThickness(double d)
{
  return 0.35 + 0.006 * d + 0.024 * std::log(d);
}

double innerRadius(double R, double gRatio, GRatioModel model)
{
  if (model == GRatioModel::Constant)
    return gRatio * R;
  // R(d) = d/2 + t(d) is increasing (derivative 0.506 + 0.024/d > 0) and tends to −∞ as d → 0; at
  // d = 2R it exceeds R whenever t(2R) > 0; otherwise widen the bracket.
  const auto outer = [](double d) { return 0.5 * d + lee2019MyelinThickness(d); };
  double lo = 0.0;
  double hi = 2.0 * R;
  while (outer(hi) < R)
    hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i)
  {
    const double mid = 0.5 * (lo + hi);
    (outer(mid) < R ? lo : hi) = mid;
  }
  return 0.25 * (lo + hi);
}

void addMyelin(FiberModel& model, const ShapeOptions& realism)
{
  if (!realism.myelinated())
  {
    return;
  }
  for (Fiber& f : model.fibers)
  {
    f.innerRadii.resize(f.radii.size());
    for (std::size_t i = 0; i < f.radii.size(); ++i)
    {
      f.innerRadii[i] = innerRadius(f.radii[i], realism.gRatio, realism.gRatioModel);
    }
  }
}

} // namespace fiberpli
