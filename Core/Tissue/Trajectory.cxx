#include "Tissue/Trajectory.h"

#include "Util/NumberFormat.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace fiberpli
{

namespace
{
// Dense samples per Catmull–Rom piece: enough that the chord error is far below the link length.
constexpr int kMinSamplesPerPiece = 4;
constexpr int kMaxSamplesPerPiece = 32;

std::string pointText(const Vec3& p)
{
  std::ostringstream s;
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

// Barry–Goldman pyramid of the centripetal Catmull–Rom piece between p1 and p2 (knots t0..t3).
Vec3 catmullRom(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p3, double t0,
  double t1, double t2, double t3, double t)
{
  const Vec3 a1 = ((t1 - t) * p0 + (t - t0) * p1) / (t1 - t0);
  const Vec3 a2 = ((t2 - t) * p1 + (t - t1) * p2) / (t2 - t1);
  const Vec3 a3 = ((t3 - t) * p2 + (t - t2) * p3) / (t3 - t2);
  const Vec3 b1 = ((t2 - t) * a1 + (t - t0) * a2) / (t2 - t0);
  const Vec3 b2 = ((t3 - t) * a2 + (t - t1) * a3) / (t3 - t1);
  return ((t2 - t) * b1 + (t - t1) * b2) / (t2 - t1);
}
} // namespace

std::string validateTrajectory(const std::vector<Vec3>& points, const std::vector<double>* scale)
{
  std::ostringstream msg;
  if (points.size() < 2)
  {
    msg << "Trajectory has " << points.size() << " point(s), needs at least 2";
    return msg.str();
  }
  if (points.size() > kMaxTrajectoryPoints)
  {
    msg << "Trajectory has " << points.size() << " points, more than the limit "
        << kMaxTrajectoryPoints;
    return msg.str();
  }
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    if (!isFinite(points[i]))
    {
      msg << "Trajectory point " << i << " " << pointText(points[i]) << " is not finite";
      return msg.str();
    }
    if (i > 0 && points[i] == points[i - 1])
    {
      msg << "Trajectory point " << i << " " << pointText(points[i]) << " repeats point " << i - 1
          << "; remove repeated consecutive points";
      return msg.str();
    }
  }
  if (scale)
  {
    if (scale->size() != points.size())
    {
      msg << "Trajectory scale has " << scale->size() << " values for " << points.size()
          << " points";
      return msg.str();
    }
    for (std::size_t i = 0; i < scale->size(); ++i)
    {
      if (!std::isfinite((*scale)[i]) || !((*scale)[i] > 0.0))
      {
        return mustBe(
          "Trajectory scale at point " + formatNumber(i), (*scale)[i], "finite and > 0");
      }
    }
  }
  return msg.str();
}

double polylineLength(const std::vector<Vec3>& points)
{
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i)
  {
    length += distance(points[i], points[i - 1]);
  }
  return length;
}

ResampledTrajectory resampleTrajectory(
  const std::vector<Vec3>& points, const std::vector<double>* scale, double segmentLength)
{
  const std::size_t m = points.size();
  ResampledTrajectory out;
  if (m < 2 || !(segmentLength > 0.0))
  {
    return out;
  }
  auto sigma = [&](std::size_t k) { return scale ? (*scale)[k] : 1.0; };

  // Dense sampling of the curve with its scale and cumulative arc length.
  std::vector<Vec3> dense;
  std::vector<double> denseScale;
  dense.push_back(points[0]);
  denseScale.push_back(sigma(0));
  for (std::size_t k = 0; k + 1 < m; ++k)
  {
    const Vec3& p1 = points[k];
    const Vec3& p2 = points[k + 1];
    const Vec3 p0 = k > 0 ? points[k - 1] : 2.0 * p1 - p2;
    const Vec3 p3 = k + 2 < m ? points[k + 2] : 2.0 * p2 - p1;
    // Centripetal knots: t_(i+1) − t_i = |P_(i+1) − P_i|^(1/2) avoids cusps and overshoot.
    const double t0 = 0.0;
    const double t1 = t0 + std::sqrt(distance(p0, p1));
    const double t2 = t1 + std::sqrt(distance(p1, p2));
    const double t3 = t2 + std::sqrt(distance(p2, p3));
    const double chord = distance(p1, p2);
    const int samples = std::max(kMinSamplesPerPiece,
      std::min(kMaxSamplesPerPiece, static_cast<int>(std::ceil(8.0 * chord / segmentLength))));
    for (int s = 1; s <= samples; ++s)
    {
      const double f = static_cast<double>(s) / samples;
      dense.push_back(
        s == samples ? p2 : catmullRom(p0, p1, p2, p3, t0, t1, t2, t3, t1 + f * (t2 - t1)));
      denseScale.push_back((1.0 - f) * sigma(k) + f * sigma(k + 1));
    }
  }
  std::vector<double> arc(dense.size(), 0.0);
  for (std::size_t i = 1; i < dense.size(); ++i)
  {
    arc[i] = arc[i - 1] + distance(dense[i], dense[i - 1]);
  }
  const double total = arc.back();
  const std::size_t n =
    static_cast<std::size_t>(std::max(2L, std::lround(total / segmentLength) + 1));
  out.points.resize(n);
  out.scale.resize(n);
  std::size_t seg = 0;
  for (std::size_t i = 0; i < n; ++i)
  {
    if (i == 0 || i + 1 == n)
    {
      out.points[i] = i == 0 ? dense.front() : dense.back();
      out.scale[i] = i == 0 ? denseScale.front() : denseScale.back();
      continue;
    }
    const double s = total * static_cast<double>(i) / static_cast<double>(n - 1);
    while (seg + 2 < dense.size() && arc[seg + 1] < s)
    {
      ++seg;
    }
    const double len = arc[seg + 1] - arc[seg];
    const double f = len > 0.0 ? std::min(1.0, std::max(0.0, (s - arc[seg]) / len)) : 0.0;
    out.points[i] = (1.0 - f) * dense[seg] + f * dense[seg + 1];
    out.scale[i] = (1.0 - f) * denseScale[seg] + f * denseScale[seg + 1];
  }
  return out;
}

TrajectoryFrames transportFrames(const std::vector<Vec3>& points)
{
  TrajectoryFrames fr;
  const std::size_t m = points.size();
  if (m < 2)
  {
    return fr;
  }
  fr.tangent.resize(m);
  fr.u.resize(m);
  fr.v.resize(m);
  Vec3 previous{ 0.0, 0.0, 1.0 };
  Vec3 u{ 1.0, 0.0, 0.0 };
  Vec3 v{ 0.0, 1.0, 0.0 };
  for (std::size_t k = 0; k < m; ++k)
  {
    const Vec3& ahead = points[std::min(k + 1, m - 1)];
    const Vec3& behind = points[k > 0 ? k - 1 : 0];
    Vec3 t = normalized(ahead - behind);
    if (norm2(t) == 0.0)
    {
      // Central difference of a polyline that reverses exactly at k: keep the incoming direction.
      t = normalized(points[k] - behind);
    }
    u = rotateMinimal(previous, t, u);
    v = rotateMinimal(previous, t, v);
    fr.tangent[k] = t;
    fr.u[k] = u;
    fr.v[k] = v;
    previous = t;
  }
  return fr;
}

double minimumCircumradius(const std::vector<Vec3>& points, std::size_t* where)
{
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i + 1 < points.size(); ++i)
  {
    const Vec3 ab = points[i] - points[i - 1];
    const Vec3 bc = points[i + 1] - points[i];
    const Vec3 ac = points[i + 1] - points[i - 1];
    const double twiceArea = norm(cross(ab, ac));
    if (twiceArea <= 0.0)
    {
      continue;
    }
    // R = abc / (4F) with 4F = 2·|ab × ac|.
    const double r = norm(ab) * norm(bc) * norm(ac) / (2.0 * twiceArea);
    if (r < best)
    {
      best = r;
      if (where)
      {
        *where = i;
      }
    }
  }
  return best;
}

} // namespace fiberpli
