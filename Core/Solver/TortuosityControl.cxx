#include "Solver/TortuosityControl.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace fiberpli
{

double fiberTortuosity(const Fiber& f, const Vec3* closure)
{
  const std::size_t n = f.size();
  if (n < 2)
  {
    return 0.0;
  }
  double length = 0.0;
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    length += distance(f.points[i], f.points[i + 1]);
  }
  const double chord =
    closure ? std::sqrt(norm2(*closure)) : distance(f.points.front(), f.points.back());
  return chord > 0.0 ? length / chord : 0.0;
}

FiberDeviation fiberDeviation(const Fiber& f, const Vec3* closure)
{
  const std::size_t n = f.size();
  FiberDeviation fd;
  const Vec3 chord = closure ? *closure : f.points.back() - f.points.front();
  fd.span = std::sqrt(norm2(chord));
  fd.axis = chord * (1.0 / fd.span);
  // The axis passes through the ends of an open fiber (they stay) or the points' mean of a closed
  // one (its first and last point are one point: counted once).
  Vec3 origin = f.points.front();
  if (closure)
  {
    origin = Vec3{};
    for (std::size_t i = 0; i + 1 < n; ++i)
    {
      origin += f.points[i];
    }
    origin *= 1.0 / static_cast<double>(n - 1);
  }
  fd.t.resize(n);
  fd.deviation.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const Vec3 r = f.points[i] - origin;
    fd.t[i] = dot(f.points[i] - f.points.front(), fd.axis);
    fd.deviation[i] = r - dot(r, fd.axis) * fd.axis;
  }
  return fd;
}

bool controlTortuosity(Fiber& f, double target, double tolerance, double maxMove,
  double minWavelength, const Vec3* closure, double maxWavelength)
{
  const std::size_t n = f.size();
  if (target <= 1.0 || n < 3 || !(maxMove > 0.0))
  {
    return false;
  }
  const double tau = fiberTortuosity(f, closure);
  if (!(tau > 1.0) || tau >= target - tolerance)
  {
    return false; // straight (nothing to scale), degenerate, or undulating enough
  }
  // The deviations' smooth part: the fiber's lowest Fourier modes along the axis (periodic over
  // the closure; a sine series between the fixed ends of an open fiber), wavelengths down to
  // minWavelength. Scaling only these leaves the small bumps the pushes make (which the fiber's
  // neighbours caused) as they are instead of amplifying them into kinks.
  const FiberDeviation fd = fiberDeviation(f, closure);
  const Vec3& axis = fd.axis;
  const double span = fd.span;
  const std::vector<double>& t = fd.t;
  const std::vector<Vec3>& deviation = fd.deviation;
  if (!(minWavelength > 0.0)) // no segment length: five mean links
  {
    minWavelength = 5.0 * tau * span / static_cast<double>(n - 1);
  }
  // Mode m has wavelength period/m: span/m over a closure, 2·span/m in the sine series of an open
  // fiber.
  const double period = (closure ? 1.0 : 2.0) * span;
  const int modes = std::max(1, static_cast<int>(period / minWavelength));
  // The longest wavelength scaled: the first mode at or below maxWavelength.
  const int firstMode = maxWavelength > 0.0
    ? std::max(1, static_cast<int>(std::ceil(period / maxWavelength - 1e-9)))
    : 1;
  if (firstMode > modes)
  {
    return false; // no mode in the band: nothing to scale
  }
  const double pi = 3.14159265358979323846;
  std::vector<Vec3> smooth(n, Vec3{});
  for (int m = firstMode; m <= modes; ++m)
  {
    // Closed: cos and sin of 2πmt/T; open: sin of πmt/T (zero at both ends).
    const double w = (closure ? 2.0 : 1.0) * pi * m / span;
    Vec3 a{}, b{};
    for (std::size_t i = 0; i + 1 < n; ++i)
    {
      const double dt = t[i + 1] - t[i];
      const Vec3 dm = 0.5 * (deviation[i] + deviation[i + 1]);
      const double tm = 0.5 * (t[i] + t[i + 1]);
      a += (dt * std::sin(w * tm)) * dm;
      b += (dt * std::cos(w * tm)) * dm;
    }
    a *= 2.0 / span;
    b *= 2.0 / span;
    for (std::size_t i = 0; i < n; ++i)
    {
      smooth[i] += std::sin(w * t[i]) * a;
      if (closure)
      {
        smooth[i] += std::cos(w * t[i]) * b;
      }
    }
  }
  double largest = 0.0;
  for (const Vec3& d : smooth)
  {
    largest = std::max(largest, std::sqrt(norm2(d)));
  }
  if (!(largest > 0.0))
  {
    return false;
  }
  const double k = std::sqrt((target - 1.0) / (tau - 1.0));
  const double grow = std::min(k - 1.0, maxMove / largest);
  // The ends of an open fiber stay exactly (the sine series vanishes there up to rounding).
  const std::size_t first = closure ? 0 : 1, end = closure ? n : n - 1;
  for (std::size_t i = first; i < end; ++i)
  {
    f.points[i] += grow * smooth[i];
  }
  if (closure)
  {
    f.points.back() = f.points.front() + *closure; // exactly, whatever the rounding
  }
  return true;
}

} // namespace fiberpli
