#include "Analysis/OrientationTensor.h"

#include "Analysis/Axis.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fiberpli
{

TruthAccumulator::TruthAccumulator(int nPhi, int nAlpha)
  : nPhi_(nPhi < 1 ? 1 : nPhi)
  , nAlpha_(nAlpha < 1 ? 1 : nAlpha)
  , counts_(static_cast<std::size_t>(nPhi_) * static_cast<std::size_t>(nAlpha_), 0)
{
}

void TruthAccumulator::reset()
{
  nAll_ = nT_ = 0;
  for (auto& row : m_)
  {
    for (double& x : row)
    {
      x = 0.0;
    }
  }
  std::fill(counts_.begin(), counts_.end(), 0);
}

void TruthAccumulator::addTissue(const Vec3& axis)
{
  const Vec3 e = canonicalAxis(axis);
  ++nAll_;
  ++nT_;
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m_[r][c] += e[r] * e[c];
    }
  }
  double phi, alpha;
  axisAngles(e, phi, alpha);
  // Bins in degrees as the notes define them; min() keeps φ = 180° − ε and |α| = 90° in range.
  const double phiDeg = phi * 180.0 / M_PI, alphaDeg = std::abs(alpha) * 180.0 / M_PI;
  int iPhi = static_cast<int>(std::floor(phiDeg / (180.0 / nPhi_)));
  int iAlpha = static_cast<int>(std::floor(alphaDeg / (90.0 / nAlpha_)));
  iPhi = iPhi < 0 ? 0 : (iPhi > nPhi_ - 1 ? nPhi_ - 1 : iPhi);
  iAlpha = iAlpha < 0 ? 0 : (iAlpha > nAlpha_ - 1 ? nAlpha_ - 1 : iAlpha);
  ++counts_[static_cast<std::size_t>(iAlpha) * nPhi_ + iPhi];
}

PixelTruth TruthAccumulator::result(double* histogram) const
{
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  PixelTruth t{ nan, nan, nan, nan, nan };
  if (nAll_ > 0)
  {
    t.fraction = static_cast<double>(nT_) / static_cast<double>(nAll_);
  }
  if (histogram)
  {
    for (std::size_t k = 0; k < counts_.size(); ++k)
    {
      histogram[k] = nT_ > 0 ? static_cast<double>(counts_[k]) / static_cast<double>(nT_) : 0.0;
    }
  }
  if (nT_ == 0)
  {
    return t;
  }
  double m[3][3];
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      m[r][c] = m_[r][c] / static_cast<double>(nT_);
    }
  }
  double values[3];
  Vec3 vectors[3];
  symmetricEigen3(m, values, vectors);
  axisAngles(vectors[0], t.direction, t.inclinationSigned);
  t.inclination = std::abs(t.inclinationSigned);
  t.anisotropy = values[0] - values[1];
  return t;
}

} // namespace fiberpli
