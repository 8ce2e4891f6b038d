#include "IO/TckFormat.h"

#include "IO/MrtrixData.h"
#include "IO/MrtrixHeader.h"
#include "Util/BinaryIO.h"
#include "Util/Fnv1a.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <string_view>

namespace fiberpli
{

namespace
{

/// Calls emit(float) for every value of the .tck data section in file order.
template <class Emit>
void forEachTckValue(const FiberModel& model, Emit emit)
{
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (const Fiber& f : model.fibers)
  {
    for (const Vec3& p : f.points)
    {
      emit(static_cast<float>(p.x));
      emit(static_cast<float>(p.y));
      emit(static_cast<float>(p.z));
    }
    emit(nan);
    emit(nan);
    emit(nan);
  }
  emit(inf);
  emit(inf);
  emit(inf);
}

} // namespace

FiberReadResult readTck(
  std::istream& in, const std::string& fileName, double defaultRadius, std::string* timestamp)
{
  FiberReadResult result;
  const auto fail = readFailure;
  if (const std::string bad = defaultRadiusError(fileName, defaultRadius); !bad.empty())
  {
    return fail(bad);
  }
  const MrtrixHeader header = readMrtrixHeader(in, fileName, "mrtrix tracks", "MRtrix tracks", 3);
  if (!header.error.empty())
  {
    return fail(header.error);
  }
  if (header.haveCount)
  {
    result.model.fibers.reserve(static_cast<std::size_t>(header.count)); // bounded by the file size
  }
  std::uint64_t streamlines = 0;
  Fiber fiber;
  const std::string error = walkMrtrixData(
    in, fileName, header, 3, streamlines,
    [&](const double* v, std::uint64_t) {
      fiber.points.push_back({ v[0], v[1], v[2] });
    },
    [&]()
    {
      if (fiber.points.size() >= 2)
      {
        fiber.points
          .shrink_to_fit(); // drop push_back's growth slack: the model holds the data once
        fiber.id = static_cast<std::int64_t>(streamlines); // walkMrtrixData counts after this call
        fiber.bundle = 0;
        fiber.radii.assign(fiber.points.size(), defaultRadius);
        result.model.fibers.push_back(std::move(fiber));
      }
      else
      {
        ++result.droppedFibers;
      }
      fiber = Fiber{};
    });
  if (!error.empty())
  {
    return fail(error);
  }
  if (timestamp)
  {
    *timestamp = header.timestamp;
  }
  return result;
}

std::string tckTimestamp(const FiberModel& model)
{
  std::uint64_t hash = kFnv1aOffset;
  unsigned char bytes[4];
  forEachTckValue(model,
    [&](float value)
    {
      binary::storeFloat32LE(bytes, value);
      fnv1aAdd(hash, bytes, sizeof bytes);
    });
  // Below 2^53, so MRtrix (which reads timestamps as doubles) sees the exact value.
  return std::to_string(hash % 1000000000000000ull);
}

std::string writeTck(std::ostream& out, const FiberModel& model)
{
  const std::string invalid = validateModel(model);
  if (!invalid.empty())
  {
    return "cannot write .tck: " + invalid;
  }
  const double floatMax = static_cast<double>(std::numeric_limits<float>::max());
  for (std::size_t fi = 0; fi < model.fibers.size(); ++fi)
  {
    const Fiber& f = model.fibers[fi];
    for (std::size_t i = 0; i < f.points.size(); ++i)
    {
      for (int a = 0; a < 3; ++a)
      {
        if (std::fabs(f.points[i][a]) > floatMax)
        {
          std::ostringstream msg;
          msg << "cannot write .tck: fiber " << fi << " (fiber_id " << f.id << ") point " << i
              << " has coordinate " << f.points[i][a] << " beyond the float32 range";
          return msg.str();
        }
      }
    }
  }

  const std::string header = composeMrtrixHeader("mrtrix tracks",
    "datatype: Float32LE\ntimestamp: " + tckTimestamp(model) +
      "\ncount: " + std::to_string(model.fibers.size()) + "\n");
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  MrtrixFloat32Writer data(out);
  forEachTckValue(model, [&](float value) { data.put(value); });
  data.flush();
  out.flush();
  if (!out)
  {
    return "cannot write .tck: the output stream failed";
  }
  return {};
}

bool looksLikeTck(std::istream& in)
{
  const std::streampos start = in.tellg();
  if (start == std::streampos(-1))
  {
    return false;
  }
  char head[16] = {};
  in.read(head, 14);
  const std::streamsize got = in.gcount();
  in.clear();
  in.seekg(start);
  const std::string_view s(head, static_cast<std::size_t>(got));
  return s.substr(0, 13) == "mrtrix tracks" && (got == 13 || s[13] == '\n' || s[13] == '\r');
}

} // namespace fiberpli
