#include "Model/InnerRadii.h"

#include <cmath>
#include <sstream>

namespace fiberpli
{

std::string validateInnerRadii(const FiberModel& model, const InnerRadii& inner, std::size_t* badFiber)
{
  if (inner.empty())
  {
    return {};
  }
  if (inner.size() != model.fibers.size())
  {
    std::ostringstream s;
    s << "inner_radius has values for " << inner.size() << " fibers, the model has " << model.fibers.size();
    return s.str();
  }
  for (std::size_t f = 0; f < inner.size(); ++f)
  {
    const Fiber& fiber = model.fibers[f];
    std::ostringstream s;
    s << "inner_radius of fiber " << f << " (fiber_id " << fiber.id << ")";
    if (badFiber != nullptr)
    {
      *badFiber = f;
    }
    if (inner[f].size() != fiber.size())
    {
      s << " has " << inner[f].size() << " values for " << fiber.size() << " points";
      return s.str();
    }
    for (std::size_t i = 0; i < fiber.size(); ++i)
    {
      const double v = inner[f][i];
      if (!std::isfinite(v) || v <= 0.0 || v > fiber.radii[i])
      {
        s << " point " << i << " is " << v << " (must be finite, > 0 and <= radius " << fiber.radii[i] << ")";
        return s.str();
      }
    }
  }
  return {};
}

FiberModel axonModel(const FiberModel& model, const InnerRadii& inner)
{
  FiberModel axons = model;
  for (std::size_t f = 0; f < axons.fibers.size(); ++f)
  {
    axons.fibers[f].radii = inner[f];
  }
  return axons;
}

} // namespace fiberpli
