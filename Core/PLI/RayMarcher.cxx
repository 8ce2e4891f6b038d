#include "PLI/RayMarcher.h"

#include "PLI/AxisSampler.h"
#include "Util/Angles.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{
namespace pli
{

LabelProps LabelProps::fromSpec(const TissueSpec& spec)
{
  LabelProps p;
  const int n = spec.labelCount();
  const int L = spec.maxLayers();
  p.dn.assign(static_cast<std::size_t>(n), 0.0);
  p.mu.assign(static_cast<std::size_t>(n), 0.0);
  p.mu[0] = spec.backgroundMu;
  for (std::size_t b = 0; b < spec.layers.size(); ++b)
    for (std::size_t l = 0; l < spec.layers[b].size(); ++l)
    {
      const Layer& layer = spec.layers[b][l];
      const std::size_t label = 1 + b * static_cast<std::size_t>(L) + l;
      p.dn[label] = layer.model == AxisModel::Background ? 0.0 : layer.dn;
      p.mu[label] = layer.muPerMm;
    }
  return p;
}

std::int64_t RayMarcher::lateralReach(std::int64_t nz, double theta)
{
  return theta == 0.0
    ? 0
    : static_cast<std::int64_t>(std::ceil(0.5 * static_cast<double>(nz) * std::tan(theta)));
}

RayMarcher::RayMarcher(
  const SectionLattice& lattice, const SimParams& params, const View& view, const LabelProps& props)
  : lat_(lattice)
  , par_(params)
  , props_(props)
{
  const double th = view.theta, ph = view.phi;
  const double c = std::cos(th), s = std::sin(th);
  double cp, sp;
  cosSinQuarterExact(ph, cp, sp); // the 90°/180°/270° views stay on the voxel-centre planes
  tilted_ = th != 0.0;
  L_[0] = s * cp;
  L_[1] = s * sp;
  L_[2] = c;
  dir_[0] = cp;
  dir_[1] = sp;
  stretch_ = tilted_ ? view.stretch : 1.0;
  centre_[0] = 0.5 * static_cast<double>(lattice.n[0]);
  centre_[1] = 0.5 * static_cast<double>(lattice.n[1]);
  const double R[3][3] = { { c * cp * cp + sp * sp, (c - 1.0) * sp * cp, s * cp },
    { (c - 1.0) * sp * cp, c * sp * sp + cp * cp, s * sp }, { -s * cp, -s * sp, c } };
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      B_[a][b] = params.conv == TiltConvention::Physical ? R[b][a] : R[a][b];
  const double nz = static_cast<double>(lattice.n[2]);
  const double tn = std::tan(th);
  p0off_[0] = -0.5 * nz * tn * cp;
  p0off_[1] = -0.5 * nz * tn * sp;

  const double h = params.step;
  if (params.stepRule == StepRule::ExactLength)
  {
    const double D = nz / c;
    const std::int64_t N = static_cast<std::int64_t>(std::ceil(D / h - 1e-9));
    double cum = 0.0;
    for (std::int64_t k = 0; k < N; ++k)
    {
      const double l = k + 1 < N ? h : D - static_cast<double>(N - 1) * h;
      len_.push_back(l);
      mid_.push_back(cum + 0.5 * l);
      cum += l;
    }
  }
  else
  {
    for (std::int64_t k = 0; (static_cast<double>(k) + 0.5) * h * c < nz; ++k)
    {
      len_.push_back(h);
      mid_.push_back((static_cast<double>(k) + 0.5) * h);
    }
  }
  for (double r : params.rho)
  {
    c2r_.push_back(std::cos(2.0 * r));
    s2r_.push_back(std::sin(2.0 * r));
  }
}

void RayMarcher::midPlanePoint(std::int64_t i, std::int64_t j, double out[2]) const
{
  out[0] = static_cast<double>(i) + 0.5;
  out[1] = static_cast<double>(j) + 0.5;
  if (stretch_ == 1.0)
    return;
  // Only the component along the tilt azimuth is stretched (the tilt axis is perpendicular to d).
  const double t =
    (stretch_ - 1.0) * ((out[0] - centre_[0]) * dir_[0] + (out[1] - centre_[1]) * dir_[1]);
  out[0] += t * dir_[0];
  out[1] += t * dir_[1];
}

GridRange RayMarcher::midPlaneColumns(const GridRange& cols) const
{
  if (stretch_ == 1.0 || cols.nx() < 1 || cols.ny() < 1)
    return cols;
  // The map is affine: the extremes are at the corner columns.
  double lo[2] = { INFINITY, INFINITY }, hi[2] = { -INFINITY, -INFINITY };
  for (std::int64_t j : { cols.j0, cols.j1 - 1 })
    for (std::int64_t i : { cols.i0, cols.i1 - 1 })
    {
      double p[2];
      midPlanePoint(i, j, p);
      for (int a = 0; a < 2; ++a)
      {
        lo[a] = std::min(lo[a], p[a]);
        hi[a] = std::max(hi[a], p[a]);
      }
    }
  auto column = [](double x) { return static_cast<std::int64_t>(std::floor(x)); };
  return GridRange{ column(lo[0]) - 1, column(hi[0]) + 2, column(lo[1]) - 1, column(hi[1]) + 2 };
}

void RayMarcher::march(const TissueBlock& block, std::int64_t i, std::int64_t j,
  const GridRange& clamp, double* out) const
{
  const int nr = static_cast<int>(c2r_.size());
  // Stokes S1..S3 per rotation without attenuation: attenuation is a scalar for all four
  // components (§4.2), so it is accumulated as Σ μ·ℓ and applied once at the end.
  constexpr int kMaxStack = 64;
  double buf[3 * kMaxStack];
  std::vector<double> heap;
  double* S = buf;
  if (nr > kMaxStack)
  {
    heap.resize(static_cast<std::size_t>(3 * nr));
    S = heap.data();
  }
  double* S1 = S;
  double* S2 = S + nr;
  double* S3 = S + 2 * nr;
  const double I0 = par_.lightIntensity;
  for (int k = 0; k < nr; ++k)
  {
    S1[k] = 0.0;
    S2[k] = 0.0;
    S3[k] = 0.5 * I0;
  }
  double mid[2];
  midPlanePoint(i, j, mid);
  const double px0 = mid[0] + p0off_[0];
  const double py0 = mid[1] + p0off_[1];
  const double lambdaUm = par_.wavelengthNm * 1e-3;
  const double twoPiOverLambda = 2.0 * M_PI / lambdaUm;
  const double voxel = lat_.voxel;
  const std::int64_t nz = block.nz;
  double muSum = 0.0; // Σ μ·ℓ in (1/mm)·voxels

  const std::size_t N = len_.size();
  for (std::size_t s = 0; s < N; ++s)
  {
    const double m = mid_[s];
    const double p[3] = { px0 + m * L_[0], py0 + m * L_[1], m * L_[2] };
    const std::int64_t vi = static_cast<std::int64_t>(std::floor(p[0]));
    const std::int64_t vj = static_cast<std::int64_t>(std::floor(p[1]));
    const std::int64_t vk =
      std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(p[2])), 0, nz - 1);
    const std::int32_t label = block.contains(vi, vj) ? block.label(vi, vj, vk) : 0;
    const double l = len_[s];
    muSum += props_.mu[static_cast<std::size_t>(label)] * l;
    const double dn = props_.dn[static_cast<std::size_t>(label)];
    if (label == 0 || dn == 0.0)
      continue;
    double v[3];
    if (!sampleAxis(block, p, label, par_.interp, clamp, v))
      continue;
    double vb[3];
    if (tilted_)
    {
      for (int a = 0; a < 3; ++a)
        vb[a] = B_[a][0] * v[0] + B_[a][1] * v[1] + B_[a][2] * v[2];
    }
    else
    {
      vb[0] = v[0];
      vb[1] = v[1];
      vb[2] = v[2];
    }
    const double q = vb[0] * vb[0] + vb[1] * vb[1];
    if (q == 0.0)
      continue;
    const double n2 = q + vb[2] * vb[2];
    const double cos2a = q / n2;
    const double c2p = (vb[0] * vb[0] - vb[1] * vb[1]) / q;
    const double s2p = 2.0 * vb[0] * vb[1] / q;
    const double delta = twoPiOverLambda * dn * l * voxel * cos2a;
    const double cd = std::cos(delta), sd = std::sin(delta), omc = 1.0 - cd;
    for (int k = 0; k < nr; ++k)
    {
      const double c = c2p * c2r_[k] + s2p * s2r_[k];
      const double sn = s2p * c2r_[k] - c2p * s2r_[k];
      const double a1 = S1[k], a2 = S2[k], a3 = S3[k];
      const double cs = c * sn * omc;
      S1[k] = (c * c + sn * sn * cd) * a1 + cs * a2 - sn * sd * a3;
      S2[k] = cs * a1 + (sn * sn + c * c * cd) * a2 + c * sd * a3;
      S3[k] = sn * sd * a1 - c * sd * a2 + cd * a3;
    }
  }
  const double A = std::exp(-muSum * voxel * 1e-3);
  for (int k = 0; k < nr; ++k)
    out[k] = 0.5 * A * (0.5 * I0 - S1[k]);
}

} // namespace pli
} // namespace fiberpli
