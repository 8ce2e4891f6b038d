#include "IO/McdcCylinders.h"

#include "IO/TextFields.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fiberpli
{

double mcdcAxisDeviation(const Fiber& fiber, McdcCylinderList kind)
{
  const Vec3 a = fiber.points.front();
  Vec3 axis = kind == McdcCylinderList::ZAligned ? Vec3{ 0.0, 0.0, 1.0 } : fiber.points.back() - a;
  const double length = norm(axis);
  double worst = 0.0;
  for (const Vec3& p : fiber.points)
  {
    const Vec3 d = p - a;
    // Distance from the line; a fiber whose ends coincide has no axis: every offset counts.
    const double off = length > 0.0 ? norm(cross(d, axis)) / length : norm(d);
    worst = std::max(worst, off);
  }
  return worst;
}

std::string writeMcdcCylinders(
  std::ostream& out, const FiberModel& model, McdcCylinderList kind, double tolerance)
{
  const char* const name =
    kind == McdcCylinderList::ZAligned ? "cylinders_list" : "oriented_cylinders_list";
  const std::string invalid = validateModel(model);
  if (!invalid.empty())
  {
    return std::string("cannot write MC/DC ") + name + ": " + invalid;
  }
  if (!std::isfinite(tolerance) || tolerance < 0.0)
  {
    return std::string("cannot write MC/DC ") + name + ": " +
      valueMustBe("straightness tolerance", tolerance, "finite and >= 0", "µm");
  }
  std::size_t worstFiber = 0;
  double worst = -1.0;
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const double d = mcdcAxisDeviation(model.fibers[f], kind);
    if (d > worst)
    {
      worst = d;
      worstFiber = f;
    }
  }
  if (worst > tolerance)
  {
    std::ostringstream msg;
    msg << "cannot write MC/DC " << name << ": fiber " << worstFiber << " (id "
        << model.fibers[worstFiber].id << ") deviates " << worst << " µm from "
        << (kind == McdcCylinderList::ZAligned ? "the z-parallel line through its first point"
                                               : "the line through its first and last point")
        << ", more than the straightness tolerance " << tolerance
        << " µm (only straight fibers are cylinders)";
    return msg.str();
  }
  std::string text = "0.001\n";
  for (const Fiber& f : model.fibers)
  {
    const double r = *std::max_element(f.radii.begin(), f.radii.end());
    const Vec3 a = f.points.front();
    const Vec3 b = f.points.back();
    const double values[7] = { a.x, a.y, a.z, b.x, b.y, b.z, r };
    const int n = kind == McdcCylinderList::ZAligned ? 4 : 7;
    for (int k = 0; k < n; ++k)
    {
      const double v = (kind == McdcCylinderList::ZAligned && k == 3) ? r : values[k];
      if (k > 0)
      {
        text += ' ';
      }
      textfields::appendNumber(text, v);
    }
    text += '\n';
    if (text.size() > (1 << 16))
    {
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
      text.clear();
    }
  }
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.flush();
  if (!out)
  {
    return std::string("cannot write MC/DC ") + name + ": the output stream failed";
  }
  return {};
}

} // namespace fiberpli
