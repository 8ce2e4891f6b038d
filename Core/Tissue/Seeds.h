/// Seeds: 2D seed points of a bundle cross-section (docs/tissue-models.md §1). The seed plane is
/// the local (x, y) plane of the cross-section; §2 lifts a seed to (x, y, 0) and transports it
/// along the trajectory.
#pragma once

#include <vector>

namespace fiberpli
{

struct Seed2D
{
  double x = 0.0;
  double y = 0.0;
};

/// Centred triangular (hexagonal) grid, docs/tissue-models.md §1.1 [ours]: rows y = j·h with
/// h = d·√3/2, x = (i + (j mod 2)/2)·d, all points with |x| <= halfWidth and |y| <= halfHeight,
/// sorted by row (y) then x. (0, 0) is a seed and the set is symmetric about both axes. Nearest
/// neighbours are exactly d apart. Returns an empty set for d <= 0, non-finite or negative sizes.
/// Callers guard the count (about 4·halfWidth·halfHeight / (h·d) points).
std::vector<Seed2D> triangularGrid(double halfWidth, double halfHeight, double spacing);

/// Circle crop, docs/tissue-models.md §1.2: true when the whole fiber disc of radius seedRadius
/// around s lies in the circle of radius circleRadius about the origin, |s|² <= (R − r)² with R >=
/// r.
bool seedInsideCircle(const Seed2D& s, double seedRadius, double circleRadius);

/// docs/tissue-models.md §1.2 `triangular_circle`: the centred grid of size 2(R + d), cropped with
/// seedInsideCircle for a constant fiber radius.
std::vector<Seed2D> triangularCircle(double radius, double spacing, double fiberRadius);

/// Random seed uniform in area in the disc of radius effectiveRadius (= R − r_s),
/// docs/tissue-models.md §1.3: s = R_eff·√u1·(cos 2πu2, sin 2πu2). u1, u2 in [0, 1) are drawn by
/// the caller so that the caller owns the draw order (§7).
Seed2D randomSeedInDisc(double u1, double u2, double effectiveRadius);

} // namespace fiberpli
