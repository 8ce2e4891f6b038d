// An overlap counter for tests that shares no code with the solver: the axis distance of two
// segments is a convex function of the two segment parameters, minimised here by nested
// golden-section searches (slow and simple on purpose).
#pragma once

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkDataArray.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <vector>

namespace independent
{
using P = std::array<double, 3>;

inline double Golden(const std::function<double(double)>& f)
{
  double a = 0.0, b = 1.0;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  for (int i = 0; i < 60; ++i)
  {
    if (fc < fd)
    {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = f(c);
    }
    else
    {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = f(d);
    }
  }
  return std::min({ f(0.0), f(1.0), fc, fd });
}

inline double SegmentDistance(const P& a0, const P& a1, const P& b0, const P& b1)
{
  const auto at = [](const P& p, const P& q, double s) {
    return P{ p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1]), p[2] + s * (q[2] - p[2]) };
  };
  return Golden(
    [&](double s)
    {
      const P p = at(a0, a1, s);
      return Golden(
        [&](double t)
        {
          const P q = at(b0, b1, t);
          return std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
            (p[2] - q[2]) * (p[2] - q[2]));
        });
    });
}

/// Capsule pairs with axis distance < ρa + ρb − tolerance, ρ = max of the link's end radii.
/// Links of one fiber count when they are not neighbours and the arc length between them is at
/// least twice their summed radii (the design's skip rule, docs/solver.md §3.1).
inline int CountOverlaps(vtkPolyData* pd, double tolerance = 1e-5)
{
  struct Link
  {
    P a, b;
    double rho;
    vtkIdType fiber;
    int k;
    double arc;
    double length;
  };
  std::vector<Link> links;
  vtkDataArray* radius = pd->GetPointData()->GetArray("radius");
  auto it = vtk::TakeSmartPointer(pd->GetLines()->NewIterator());
  vtkIdType fiber = 0;
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell(), ++fiber)
  {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    double arc = 0.0;
    for (vtkIdType k = 0; k + 1 < n; ++k)
    {
      Link l;
      pd->GetPoint(ids[k], l.a.data());
      pd->GetPoint(ids[k + 1], l.b.data());
      l.rho = std::max(radius->GetTuple1(ids[k]), radius->GetTuple1(ids[k + 1]));
      l.fiber = fiber;
      l.k = static_cast<int>(k);
      l.arc = arc;
      l.length = std::sqrt(
        std::pow(l.b[0] - l.a[0], 2) + std::pow(l.b[1] - l.a[1], 2) + std::pow(l.b[2] - l.a[2], 2));
      arc += l.length;
      links.push_back(l);
    }
  }
  int count = 0;
  for (std::size_t i = 0; i < links.size(); ++i)
  {
    for (std::size_t j = i + 1; j < links.size(); ++j)
    {
      const Link& u = links[i];
      const Link& v = links[j];
      // u precedes v along its fiber: the arc strictly between them is v.arc − (u.arc + u.length).
      if (u.fiber == v.fiber &&
        (v.k - u.k == 1 || v.arc - (u.arc + u.length) < 2.0 * (u.rho + v.rho)))
      {
        continue;
      }
      // Cheap reject by bounding spheres before the expensive search.
      const P cu{ (u.a[0] + u.b[0]) / 2, (u.a[1] + u.b[1]) / 2, (u.a[2] + u.b[2]) / 2 };
      const P cv{ (v.a[0] + v.b[0]) / 2, (v.a[1] + v.b[1]) / 2, (v.a[2] + v.b[2]) / 2 };
      const double hu = 0.5 *
        std::sqrt(std::pow(u.b[0] - u.a[0], 2) + std::pow(u.b[1] - u.a[1], 2) +
          std::pow(u.b[2] - u.a[2], 2));
      const double hv = 0.5 *
        std::sqrt(std::pow(v.b[0] - v.a[0], 2) + std::pow(v.b[1] - v.a[1], 2) +
          std::pow(v.b[2] - v.a[2], 2));
      const double dc = std::sqrt(
        std::pow(cu[0] - cv[0], 2) + std::pow(cu[1] - cv[1], 2) + std::pow(cu[2] - cv[2], 2));
      if (dc - hu - hv >= u.rho + v.rho)
      {
        continue;
      }
      if (SegmentDistance(u.a, u.b, v.a, v.b) < u.rho + v.rho - tolerance)
      {
        ++count;
      }
    }
  }
  return count;
}
} // namespace independent
