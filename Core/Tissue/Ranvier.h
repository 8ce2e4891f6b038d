/// Ranvier: periodic radius variation along a fiber, the nodes of Ranvier (docs/tissue-models.md
/// §5.4 [ours]).
#pragma once

#include "Model/FiberModel.h"

namespace fiberpli
{

struct RanvierOptions
{
  double spacing = 0.0; ///< Λ, µm between node centres; <= 0 = off
  double depth = 0.3;   ///< relative radius reduction at a node, in [0, 1)
  double length = 1.0;  ///< w, µm: full depth over w, cosine taper over a further w/2 each side
};

/// Radius factor at arc length s, docs/tissue-models.md §5.4: 1 − depth·g(((s − φ) mod Λ) − Λ/2)
/// with g = 1 for |x| <= w/2, ½(1 + cos(π(|x| − w/2)/(w/2))) for w/2 < |x| <= w, 0 beyond. Node
/// centres are at s = φ + Λ/2 + mΛ. Returns 1 when Λ <= 0.
double ranvierFactor(double s, double phase, const RanvierOptions& options);

/// Applies the profile to fiber f (docs/tissue-models.md §5.4): sets radii[i] =
/// baseRadius·factor(s_i) with s the arc length from the first point, after inserting points at
/// node centre, ±w/2 and ±w on the polyline so that the profile is sampled. An insertion closer
/// than min(w/2, link length)/4 to an existing interior point moves that point along the polyline
/// instead (no very short links); insertions that close to an end point are dropped. The shape of
/// the polyline does not change. Does nothing to the points when Λ <= 0 (radii still set).
void applyRanvier(Fiber& f, double baseRadius, double phase, const RanvierOptions& options);

} // namespace fiberpli
