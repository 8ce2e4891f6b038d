#include "Model/FiberModel.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fiberpli
{

std::size_t FiberModel::numberOfPoints() const
{
  std::size_t n = 0;
  for (const Fiber& f : fibers)
  {
    n += f.points.size();
  }
  return n;
}

std::size_t FiberModel::numberOfLinks() const
{
  std::size_t n = 0;
  for (const Fiber& f : fibers)
  {
    n += f.points.size() > 1 ? f.points.size() - 1 : 0;
  }
  return n;
}

bool modelBounds(const FiberModel& model, bool withRadii, Vec3& lo, Vec3& hi)
{
  bool any = false;
  for (const Fiber& f : model.fibers)
  {
    for (std::size_t i = 0; i < f.points.size(); ++i)
    {
      const double r = withRadii ? f.radii[i] : 0.0;
      const Vec3& p = f.points[i];
      if (!any)
      {
        lo = { p.x - r, p.y - r, p.z - r };
        hi = { p.x + r, p.y + r, p.z + r };
        any = true;
        continue;
      }
      for (int a = 0; a < 3; ++a)
      {
        lo[a] = std::min(lo[a], p[a] - r);
        hi[a] = std::max(hi[a], p[a] + r);
      }
    }
  }
  return any;
}

double largestRadius(const FiberModel& model)
{
  double largest = 0.0;
  for (const Fiber& f : model.fibers)
  {
    if (f.size() >= 2)
    {
      for (double r : f.radii)
      {
        largest = std::max(largest, r);
      }
    }
  }
  return largest;
}

bool isClosedFiber(const Fiber& fiber, const PeriodicCell& cell, Vec3& closure)
{
  return fiber.size() >= 3 &&
    closesThroughCell(fiber.points.front(), fiber.points.back(), cell, closure);
}

std::string validateModel(const FiberModel& model, std::size_t* badFiber, ShortFibers shortFibers)
{
  for (std::size_t fi = 0; fi < model.fibers.size(); ++fi)
  {
    const Fiber& f = model.fibers[fi];
    // The problem with this fiber, if any; the message is only built on the error path.
    std::ostringstream problem;
    if (f.points.size() < 2 && shortFibers == ShortFibers::Refused)
    {
      problem << " has fewer than 2 points";
    }
    else if (f.radii.size() != f.points.size())
    {
      problem << " has a different number of radii and points";
    }
    else
    {
      for (std::size_t i = 0; i < f.points.size(); ++i)
      {
        if (!isFinite(f.points[i]))
        {
          problem << " point " << i << " has a non-finite coordinate";
          break;
        }
        if (!std::isfinite(f.radii[i]) || f.radii[i] <= 0.0)
        {
          problem << " point " << i << " has radius " << f.radii[i] << " (must be finite and > 0)";
          break;
        }
      }
    }
    if (problem.tellp() > 0)
    {
      if (badFiber != nullptr)
      {
        *badFiber = fi;
      }
      std::ostringstream msg;
      msg << "fiber " << fi << " (fiber_id " << f.id << ")" << problem.str();
      return msg.str();
    }
  }
  return {};
}

} // namespace fiberpli
