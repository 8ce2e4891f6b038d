#include "PLI/AxisSampler.h"

#include <algorithm>
#include <cmath>

namespace fiberpli
{
namespace pli
{

namespace
{
struct Ax
{
  double v[3];
  bool ok;
};

inline double dot3(const double* a, const double* b)
{
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Pairwise combination of §4.5; axes are orientations, so b is flipped onto a's hemisphere.
// A neighbour of weight zero never enters, whether the other one is missing or not: on a
// voxel-centre plane (t == 0) the pair is a alone. Only then does a missing neighbour hand its
// weight to the other one. Both formulas are symmetric, mix(a, b, t) = mix(b, a, 1 − t), so a
// mirrored or rotated model gives the mirrored or rotated axis.
inline Ax mix(const Ax& a, Ax b, double t, Interp interp)
{
  if (t == 0.0)
    return a;
  if (t == 1.0)
    return b;
  if (!a.ok)
    return b;
  if (!b.ok)
    return a;
  if (dot3(a.v, b.v) < 0.0)
    for (double& x : b.v)
      x = -x;
  Ax r;
  r.ok = true;
  double c = 1.0, w = 0.0;
  if (interp == Interp::Slerp)
  {
    const double na = std::sqrt(dot3(a.v, a.v)), nb = std::sqrt(dot3(b.v, b.v));
    c = std::clamp(dot3(a.v, b.v) / (na * nb), -1.0, 1.0);
    w = std::acos(c);
  }
  // Lerp, and Slerp's limit for (nearly) parallel axes, where its weights lose precision.
  if (w < 1e-6)
  {
    for (int d = 0; d < 3; ++d)
      r.v[d] = (1.0 - t) * a.v[d] + t * b.v[d];
    return r;
  }
  // sin(acos c) = sqrt(1 − c²): one transcendental call fewer per pair.
  const double s = std::sqrt(1.0 - c * c), wa = std::sin((1.0 - t) * w) / s,
               wb = std::sin(t * w) / s;
  for (int d = 0; d < 3; ++d)
    r.v[d] = wa * a.v[d] + wb * b.v[d];
  return r;
}

inline Ax fetch(
  const TissueBlock& b, std::int64_t i, std::int64_t j, std::int64_t k, std::int32_t label)
{
  Ax a;
  a.ok = false;
  if (!b.contains(i, j) || b.label(i, j, k) != label)
    return a;
  float f[3];
  b.axis(i, j, k, f);
  a.v[0] = f[0];
  a.v[1] = f[1];
  a.v[2] = f[2];
  a.ok = !(f[0] == 0.0f && f[1] == 0.0f && f[2] == 0.0f);
  return a;
}
} // namespace

bool sampleAxis(const TissueBlock& block, const double p[3], std::int32_t label, Interp interp,
  const GridRange& clamp, double out[3])
{
  if (interp == Interp::NN)
  {
    const Ax a = fetch(block, static_cast<std::int64_t>(std::floor(p[0])),
      static_cast<std::int64_t>(std::floor(p[1])),
      std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(p[2])), 0, block.nz - 1),
      label);
    if (!a.ok)
      return false;
    const double n = std::sqrt(dot3(a.v, a.v));
    for (int d = 0; d < 3; ++d)
      out[d] = a.v[d] / n;
    return true;
  }
  std::int64_t lo[3], hi[3];
  double t[3];
  const std::int64_t minI[3] = { clamp.i0, clamp.j0, 0 };
  const std::int64_t maxI[3] = { clamp.i1 - 1, clamp.j1 - 1, block.nz - 1 };
  for (int d = 0; d < 3; ++d)
  {
    const double f = std::floor(p[d] - 0.5);
    t[d] = p[d] - 0.5 - f;
    const std::int64_t i0 = static_cast<std::int64_t>(f);
    lo[d] = std::clamp(i0, minI[d], maxI[d]);
    hi[d] = std::clamp(i0 + 1, minI[d], maxI[d]);
  }
  Ax c[2][2][2]; // [z][y][x]
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      for (int x = 0; x < 2; ++x)
        c[z][y][x] = fetch(block, x ? hi[0] : lo[0], y ? hi[1] : lo[1], z ? hi[2] : lo[2], label);
  Ax yz[2][2];
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 2; ++y)
      yz[z][y] = mix(c[z][y][0], c[z][y][1], t[0], interp);
  const Ax z0 = mix(yz[0][0], yz[0][1], t[1], interp);
  const Ax z1 = mix(yz[1][0], yz[1][1], t[1], interp);
  const Ax r = mix(z0, z1, t[2], interp);
  if (!r.ok)
    return false;
  const double n = std::sqrt(dot3(r.v, r.v));
  if (!(n > 0.0))
    return false;
  for (int d = 0; d < 3; ++d)
    out[d] = r.v[d] / n;
  return true;
}

} // namespace pli
} // namespace fiberpli
