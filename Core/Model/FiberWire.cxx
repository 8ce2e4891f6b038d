#include "Model/FiberWire.h"

namespace fiberpli
{

void putFiber(ByteWriter& w, const Fiber& fiber)
{
  const bool inner = fiber.innerRadii.size() == fiber.size();
  w.put<long long>(static_cast<long long>(fiber.id));
  w.put<long long>(fiber.bundle);
  w.put<long long>(static_cast<long long>(fiber.size()));
  for (std::size_t i = 0; i < fiber.size(); ++i)
  {
    const double point[5] = { fiber.points[i].x, fiber.points[i].y, fiber.points[i].z,
      fiber.radii[i], inner ? fiber.innerRadii[i] : 0.0 };
    w.put(point, 5);
  }
}

Fiber getFiber(ByteReader& r)
{
  Fiber fiber;
  fiber.id = r.get<long long>();
  fiber.bundle = static_cast<int>(r.get<long long>());
  const std::size_t n = static_cast<std::size_t>(r.get<long long>());
  fiber.points.resize(n);
  fiber.radii.resize(n);
  fiber.innerRadii.resize(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    double point[5];
    r.get(point, 5);
    fiber.points[i] = Vec3{ point[0], point[1], point[2] };
    fiber.radii[i] = point[3];
    fiber.innerRadii[i] = point[4];
  }
  if (n == 0 || fiber.innerRadii[0] <= 0.0) // a fiber has inner radii at every point or none
  {
    fiber.innerRadii.clear();
  }
  return fiber;
}

void writeFibers(const FiberModel& model, const std::vector<std::size_t>& which, long long offset,
  std::vector<char>& out)
{
  ByteWriter w(out);
  for (std::size_t f : which)
  {
    w.put<long long>(offset + static_cast<long long>(f));
    putFiber(w, model.fibers[f]);
  }
}

void readFibers(const std::vector<char>& in, std::vector<std::pair<long long, Fiber>>& out)
{
  ByteReader r(in);
  while (!r.done())
  {
    const long long global = r.get<long long>();
    out.emplace_back(global, getFiber(r));
  }
}

} // namespace fiberpli
