#include "Analysis/OrientationTensor.h"

#include "Analysis/Axis.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fiberpli
{

void symmetricEigen3(const double m[3][3], double values[3], Vec3 vectors[3])
{
  double a[3][3], v[3][3] = { { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  for (int r = 0; r < 3; ++r)
  {
    for (int c = 0; c < 3; ++c)
    {
      a[r][c] = m[r][c];
    }
  }
  for (int sweep = 0; sweep < 50; ++sweep)
  {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    if (off == 0.0)
    {
      break;
    }
    for (int p = 0; p < 2; ++p)
    {
      for (int q = p + 1; q < 3; ++q)
      {
        if (a[p][q] == 0.0)
        {
          continue;
        }
        // Rotation that zeroes a[p][q] (Golub & Van Loan, symmetric Schur 2×2).
        const double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        const double t =
          (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1.0));
        const double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < 3; ++k)
        {
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k)
        {
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k)
        {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  int order[3] = { 0, 1, 2 };
  for (int i = 0; i < 3; ++i)
  {
    for (int j = i + 1; j < 3; ++j)
    {
      if (a[order[j]][order[j]] > a[order[i]][order[i]])
      {
        const int t = order[i];
        order[i] = order[j];
        order[j] = t;
      }
    }
  }
  for (int k = 0; k < 3; ++k)
  {
    values[k] = a[order[k]][order[k]];
    vectors[k] = normalized(Vec3{ v[0][order[k]], v[1][order[k]], v[2][order[k]] });
  }
}

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
