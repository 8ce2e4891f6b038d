#include "IO/CaterpillarFormat.h"

#include "IO/LineReader.h"
#include "IO/TextFields.h"
#include "Model/InnerRadii.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <unordered_set>

namespace fiberpli
{

const char* const kCaterpillarHeader =
  "cell_type cell_id component component_id X Y Z inner_radius outer_radius";

namespace
{

using namespace textfields;

constexpr std::size_t maxLineLength = 4096;
constexpr std::size_t kFields = 9;

bool isHeader(std::string_view line)
{
  std::string_view tokens[kFields + 1];
  std::string_view expected[kFields + 1];
  const std::size_t n = splitTokens(line, tokens, kFields + 1);
  const std::size_t m = splitTokens(kCaterpillarHeader, expected, kFields + 1);
  if (n != m)
  {
    return false;
  }
  for (std::size_t i = 0; i < n; ++i)
  {
    if (tokens[i] != expected[i])
    {
      return false;
    }
  }
  return true;
}

bool isBlank(std::string_view line)
{
  return std::all_of(line.begin(), line.end(), isBlankChar);
}

std::string parseInteger(std::string_view token, long long& value)
{
  const std::from_chars_result r =
    std::from_chars(token.data(), token.data() + token.size(), value);
  if (r.ec != std::errc() || r.ptr != token.data() + token.size())
  {
    return "'" + std::string(token.substr(0, 40)) + "' is not an integer id";
  }
  return {};
}

} // namespace

FiberReadResult readCaterpillarCsv(std::istream& in, const std::string& fileName)
{
  FiberReadResult result;
  LineReader reader(in, maxLineLength);
  bool headerSeen = false;
  bool anyInnerDiffers = false;
  std::size_t skippedSpheres = 0;
  std::unordered_set<long long> axonIds;

  Fiber fiber;
  std::vector<double> inner;
  bool chainIsAxon = false;
  std::string chainKey; // cell_type, cell_id, component, component_id of the open chain
  bool chainOpen = false;

  auto fail = [&](std::size_t line, const std::string& what)
  {
    FiberReadResult failed;
    failed.error = lineError(fileName, line, what);
    return failed;
  };
  auto closeChain = [&]()
  {
    if (chainOpen && chainIsAxon)
    {
      if (fiber.points.size() >= 2)
      {
        fiber.points.shrink_to_fit();
        fiber.radii.shrink_to_fit();
        inner.shrink_to_fit();
        fiber.innerRadii = std::move(inner);
        result.model.fibers.push_back(std::move(fiber));
      }
      else
      {
        ++result.droppedFibers;
      }
    }
    fiber = Fiber{};
    inner.clear();
    chainOpen = false;
  };

  std::string_view line;
  LineReader::Stop stop;
  while (reader.nextLine(line, stop, " (not a CATERPillar sphere line)"))
  {
    if (isBlank(line))
    {
      continue;
    }
    if (!headerSeen)
    {
      if (!isHeader(line))
      {
        return fail(reader.lineNumber(),
          std::string("expected the CATERPillar header '") + kCaterpillarHeader + "'");
      }
      headerSeen = true;
      continue;
    }
    std::string_view t[kFields];
    const std::size_t count = splitTokens(line, t, kFields);
    if (count != kFields)
    {
      std::ostringstream msg;
      msg << "expected 9 fields '" << kCaterpillarHeader << "', found " << count;
      return fail(reader.lineNumber(), msg.str());
    }
    long long cellId = 0;
    long long componentId = 0;
    std::string why = parseInteger(t[1], cellId);
    if (why.empty())
    {
      why = parseInteger(t[3], componentId);
    }
    double v[5];
    for (int k = 0; k < 5 && why.empty(); ++k)
    {
      why = parseFinite(t[4 + k], v[k]);
    }
    if (!why.empty())
    {
      return fail(reader.lineNumber(), why);
    }
    if (!(v[3] > 0.0) || !(v[4] > 0.0))
    {
      return fail(reader.lineNumber(),
        v[3] > 0.0 ? valueMustBe("outer_radius", v[4], "> 0")
                   : valueMustBe("inner_radius", v[3], "> 0"));
    }
    if (v[3] > v[4])
    {
      std::ostringstream msg;
      msg << "inner_radius " << v[3] << " exceeds outer_radius " << v[4];
      return fail(reader.lineNumber(), msg.str());
    }
    std::string key;
    key.append(t[0]).append(1, ' ').append(t[1]).append(1, ' ').append(t[2]).append(1, ' ').append(
      t[3]);
    if (!chainOpen || key != chainKey)
    {
      closeChain();
      chainOpen = true;
      chainKey = key;
      chainIsAxon = t[0] == "axon";
      if (chainIsAxon)
      {
        if (componentId < std::numeric_limits<int>::min() ||
          componentId > std::numeric_limits<int>::max())
        {
          return fail(reader.lineNumber(),
            "component_id " + std::string(t[3]) + " does not fit bundle_id (int)");
        }
        if (!axonIds.insert(cellId).second)
        {
          return fail(reader.lineNumber(),
            "axon " + std::string(t[1]) +
              " starts a second sphere chain (its spheres must be consecutive lines)");
        }
        fiber.id = cellId;
        fiber.bundle = static_cast<int>(componentId);
      }
    }
    if (!chainIsAxon)
    {
      ++skippedSpheres;
      continue;
    }
    fiber.points.push_back({ v[0], v[1], v[2] });
    fiber.radii.push_back(v[4]);
    inner.push_back(v[3]);
    anyInnerDiffers = anyInnerDiffers || v[3] != v[4];
  }
  if (stop.failed())
  {
    return fail(stop.line, stop.what);
  }
  if (!headerSeen)
  {
    return fail(
      reader.lineNumber() + 1, std::string("no CATERPillar header '") + kCaterpillarHeader + "'");
  }
  closeChain();
  if (!anyInnerDiffers)
  {
    for (Fiber& f : result.model.fibers)
    {
      f.innerRadii.clear(); // no myelin anywhere: no inner_radius, as the other readers
      f.innerRadii.shrink_to_fit();
    }
  }
  if (skippedSpheres > 0)
  {
    result.warnings.push_back(fileName + ": " + std::to_string(skippedSpheres) +
      " spheres of cells other than axons (glial cells, vessels) were skipped: they are not "
      "fibers");
  }
  return result;
}

double caterpillarSphereSpacing(double radius, double tolerance)
{
  if (tolerance >= radius)
  {
    return 2.0 * radius;
  }
  return 2.0 * std::sqrt(2.0 * radius * tolerance - tolerance * tolerance);
}

std::string writeCaterpillarCsv(std::ostream& out, const FiberModel& model, double tolerance)
{
  const std::string invalid = validateModel(model);
  if (!invalid.empty())
  {
    return "cannot write CATERPillar .csv: " + invalid;
  }
  if (!std::isfinite(tolerance) || !(tolerance > 0.0))
  {
    return "cannot write CATERPillar .csv: " +
      valueMustBe("sphere tolerance", tolerance, "finite and > 0", "µm");
  }
  // The one rule of Model/InnerRadii.h: per fiber none, or one value per point in (0, radius].
  const std::string badInner = validateInnerRadii(model);
  if (!badInner.empty())
  {
    return "cannot write CATERPillar .csv: " + badInner;
  }
  auto innerAt = [&](std::size_t f, std::size_t i)
  {
    const Fiber& fiber = model.fibers[f];
    return fiber.innerRadii.empty() ? fiber.radii[i] : fiber.innerRadii[i];
  };
  auto spheresOfLink = [&](std::size_t f, std::size_t k)
  {
    const Fiber& fiber = model.fibers[f];
    const double r =
      std::min({ fiber.radii[k], fiber.radii[k + 1], innerAt(f, k), innerAt(f, k + 1) });
    const double length = norm(fiber.points[k + 1] - fiber.points[k]);
    return std::max(1.0, std::ceil(length / caterpillarSphereSpacing(r, tolerance)));
  };
  // Count first: a tiny tolerance on a long model must not fill the disk.
  double total = 0.0;
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    for (std::size_t k = 0; k + 1 < model.fibers[f].size(); ++k)
    {
      total += spheresOfLink(f, k);
    }
  }
  if (total > 1e9)
  {
    std::ostringstream msg;
    msg << "cannot write CATERPillar .csv: sphere tolerance " << tolerance << " µm needs " << total
        << " spheres (more than 1e9); raise the tolerance";
    return msg.str();
  }

  out << kCaterpillarHeader << '\n';
  std::string line;
  auto sphere = [&](const Fiber& fiber, const Vec3& c, double innerR, double outerR)
  {
    line.clear();
    line += "axon ";
    line += std::to_string(fiber.id);
    line += " axon ";
    line += std::to_string(fiber.bundle);
    for (double x : { c.x, c.y, c.z, innerR, outerR })
    {
      line += ' ';
      appendNumber(line, x);
    }
    line += '\n';
    out.write(line.data(), static_cast<std::streamsize>(line.size()));
  };
  for (std::size_t f = 0; f < model.fibers.size(); ++f)
  {
    const Fiber& fiber = model.fibers[f];
    for (std::size_t k = 0; k + 1 < fiber.size(); ++k)
    {
      const std::size_t n = static_cast<std::size_t>(spheresOfLink(f, k));
      const Vec3 a = fiber.points[k];
      const Vec3 b = fiber.points[k + 1];
      for (std::size_t j = 0; j < n; ++j)
      {
        if (j == 0)
        {
          sphere(fiber, a, innerAt(f, k), fiber.radii[k]);
          continue;
        }
        const double t = static_cast<double>(j) / static_cast<double>(n);
        sphere(fiber, a + (b - a) * t, innerAt(f, k) + (innerAt(f, k + 1) - innerAt(f, k)) * t,
          fiber.radii[k] + (fiber.radii[k + 1] - fiber.radii[k]) * t);
      }
    }
    const std::size_t last = fiber.size() - 1;
    sphere(fiber, fiber.points[last], innerAt(f, last), fiber.radii[last]);
  }
  out.flush();
  if (!out)
  {
    return "cannot write CATERPillar .csv: the output stream failed";
  }
  return {};
}

bool looksLikeCaterpillarCsv(std::istream& in)
{
  const std::streampos start = in.tellg();
  if (start == std::streampos(-1))
  {
    return false;
  }
  bool found = false;
  {
    LineReader reader(in, maxLineLength);
    std::string_view line;
    while (reader.next(line) == LineReader::Status::Line)
    {
      if (isBlank(line))
      {
        continue;
      }
      found = isHeader(line);
      break;
    }
  }
  in.clear();
  in.seekg(start);
  return found;
}

} // namespace fiberpli
