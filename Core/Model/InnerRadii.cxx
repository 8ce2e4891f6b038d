#include "Model/InnerRadii.h"

#include <cmath>
#include <sstream>

namespace fiberpli
{

bool hasInnerRadii(const FiberModel& model)
{
  for (const Fiber& f : model.fibers)
  {
    if (!f.innerRadii.empty())
    {
      return true;
    }
  }
  return false;
}

std::string validateInnerRadii(const FiberModel& model, std::size_t* badFiber)
{
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fiber = model.fibers[f];
    if (fiber.innerRadii.empty())
    {
      continue;
    }
    std::ostringstream s;
    s << "inner_radius of fiber " << f << " (fiber_id " << fiber.id << ")";
    bool bad = fiber.innerRadii.size() != fiber.size();
    if (bad)
    {
      s << " has " << fiber.innerRadii.size() << " values for " << fiber.size() << " points";
    }
    for (std::size_t i = 0; !bad && i < fiber.size(); ++i)
    {
      const double v = fiber.innerRadii[i];
      if (!std::isfinite(v) || v <= 0.0 || v > fiber.radii[i])
      {
        s << " point " << i << " is " << v << " (must be finite, > 0 and <= radius "
          << fiber.radii[i] << ")";
        bad = true;
      }
    }
    if (bad)
    {
      if (badFiber != nullptr)
      {
        *badFiber = f;
      }
      return s.str();
    }
  }
  return {};
}

FiberModel axonModel(const FiberModel& model)
{
  FiberModel axons = model;
  for (Fiber& f : axons.fibers)
  {
    if (!f.innerRadii.empty())
    {
      f.radii.swap(f.innerRadii);
      f.innerRadii.clear();
    }
  }
  return axons;
}

} // namespace fiberpli
