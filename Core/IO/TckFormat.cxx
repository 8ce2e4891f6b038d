#include "IO/TckFormat.h"

#include "IO/BinaryIO.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>
#include <string_view>
#include <vector>

namespace fiberpli
{

namespace
{

constexpr std::size_t maxHeaderBytes = std::size_t(1) << 20; // MRtrix headers are a few KiB

std::string_view trim(std::string_view s)
{
  const char* ws = " \t\r\f\v";
  const std::size_t b = s.find_first_not_of(ws);
  if (b == std::string_view::npos)
  {
    return {};
  }
  const std::size_t e = s.find_last_not_of(ws);
  return s.substr(b, e - b + 1);
}

std::string lower(std::string_view s)
{
  std::string r(s);
  std::transform(r.begin(), r.end(), r.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return r;
}

bool parseUnsigned(std::string_view s, std::uint64_t& value)
{
  const std::from_chars_result r = std::from_chars(s.data(), s.data() + s.size(), value);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && !s.empty();
}

std::string at(const std::string& fileName, const char* unit, std::uint64_t where, const std::string& what)
{
  std::ostringstream msg;
  msg << fileName << " " << unit << " " << where << ": " << what;
  return msg.str();
}

} // namespace

FiberReadResult readTck(std::istream& in, const std::string& fileName, double defaultRadius)
{
  FiberReadResult result;
  auto fail = [&](const std::string& message) {
    FiberReadResult failed;
    failed.error = message;
    return failed;
  };
  if (!std::isfinite(defaultRadius) || defaultRadius <= 0.0)
  {
    std::ostringstream msg;
    msg << fileName << ": DefaultRadius " << defaultRadius << " must be finite and > 0";
    return fail(msg.str());
  }
  std::uint64_t fileSize = 0;
  if (!binary::remainingBytes(in, fileSize))
  {
    return fail(fileName + ": cannot determine the file size (stream is not seekable)");
  }

  // --- header: text up to the END line, bounded so a binary file cannot make us read it all.
  std::string head(static_cast<std::size_t>(std::min<std::uint64_t>(fileSize, maxHeaderBytes)), '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  if (static_cast<std::size_t>(in.gcount()) != head.size())
  {
    return fail(at(fileName, "byte", static_cast<std::uint64_t>(in.gcount()), "read error in the header"));
  }
  std::size_t pos = 0;
  std::size_t lineNo = 0;
  std::uint64_t headerEnd = 0;
  std::string datatype;
  std::string fileValue;
  std::string countValue;
  std::size_t fileLine = 0;
  std::size_t countLine = 0;
  std::size_t datatypeLine = 0;
  for (;;)
  {
    const std::size_t nl = head.find('\n', pos);
    if (nl == std::string::npos)
    {
      return fail(at(fileName, "line", lineNo + 1,
        head.size() < maxHeaderBytes ? "header ends without an END line (truncated file?)"
                                     : "no END line in the first 1 MiB of the header"));
    }
    const std::string_view line = trim(std::string_view(head).substr(pos, nl - pos));
    pos = nl + 1;
    ++lineNo;
    if (lineNo == 1)
    {
      if (line != "mrtrix tracks")
      {
        return fail(at(fileName, "line", 1, "not an MRtrix tracks file (first line must be 'mrtrix tracks')"));
      }
      continue;
    }
    if (line == "END")
    {
      headerEnd = pos;
      break;
    }
    const std::size_t colon = line.find(':');
    if (colon == std::string_view::npos)
    {
      return fail(at(fileName, "line", lineNo, "header line is not 'key: value'"));
    }
    const std::string key = lower(trim(line.substr(0, colon)));
    const std::string_view value = trim(line.substr(colon + 1));
    auto setOnce = [&](std::string& slot, std::size_t& slotLine) {
      if (!slot.empty() && slot != value)
      {
        return false;
      }
      slot = std::string(value);
      slotLine = lineNo;
      return true;
    };
    bool ok = true;
    if (key == "datatype")
    {
      ok = setOnce(datatype, datatypeLine);
    }
    else if (key == "file")
    {
      ok = setOnce(fileValue, fileLine);
    }
    else if (key == "count")
    {
      ok = setOnce(countValue, countLine);
    }
    if (!ok)
    {
      return fail(at(fileName, "line", lineNo, "'" + key + "' given twice with different values"));
    }
  }

  // --- header values
  const std::string dt = lower(datatype);
  std::size_t valueSize = 0;
  bool little = true;
  if (dt == "float32le" || dt == "float32be")
  {
    valueSize = 4;
  }
  else if (dt == "float64le" || dt == "float64be")
  {
    valueSize = 8;
  }
  else if (datatype.empty())
  {
    return fail(fileName + ": header has no 'datatype' line");
  }
  else
  {
    return fail(at(fileName, "line", datatypeLine,
      "datatype '" + datatype + "' is not supported (Float32LE, Float32BE, Float64LE, Float64BE)"));
  }
  little = dt.compare(dt.size() - 2, 2, "le") == 0;

  if (fileValue.empty())
  {
    return fail(fileName + ": header has no 'file: . <offset>' line");
  }
  std::uint64_t offset = 0;
  {
    const std::string_view fv(fileValue);
    if (fv.size() < 2 || fv[0] != '.' || (fv[1] != ' ' && fv[1] != '\t'))
    {
      return fail(at(fileName, "line", fileLine,
        "'file: " + fileValue + "': only data in the same file ('file: . <offset>') is supported"));
    }
    if (!parseUnsigned(trim(fv.substr(1)), offset))
    {
      return fail(at(fileName, "line", fileLine, "'file: " + fileValue + "': offset is not a number"));
    }
  }
  if (offset < headerEnd || offset > fileSize)
  {
    std::ostringstream msg;
    msg << "data offset " << offset << " must lie between the end of the header (byte " << headerEnd
        << ") and the end of the file (byte " << fileSize << ")";
    return fail(at(fileName, "line", fileLine, msg.str()));
  }
  const std::uint64_t tripletSize = 3 * valueSize;
  const std::uint64_t dataBytes = fileSize - offset;
  bool haveCount = !countValue.empty();
  std::uint64_t count = 0;
  if (haveCount)
  {
    if (!parseUnsigned(countValue, count))
    {
      return fail(at(fileName, "line", countLine, "count '" + countValue + "' is not a number"));
    }
    // Every streamline needs at least its NaN terminator, plus the final Inf triplet.
    if (count > dataBytes / tripletSize || count * tripletSize + tripletSize > dataBytes)
    {
      std::ostringstream msg;
      msg << "count " << count << " needs at least " << (count + 1) << " triplets but only "
          << dataBytes << " bytes of data follow the header";
      return fail(at(fileName, "line", countLine, msg.str()));
    }
    result.model.fibers.reserve(static_cast<std::size_t>(count));
  }

  // --- data, read in blocks of whole triplets
  in.clear();
  in.seekg(static_cast<std::streamoff>(offset));
  if (!in)
  {
    return fail(at(fileName, "byte", offset, "cannot seek to the data"));
  }
  const std::size_t tripletsPerBlock = 1 << 12;
  std::vector<unsigned char> block(static_cast<std::size_t>(tripletSize) * tripletsPerBlock);
  std::uint64_t remaining = dataBytes;
  std::uint64_t position = offset;
  std::uint64_t streamlines = 0;
  bool sawEnd = false;
  Fiber fiber;
  auto finishFiber = [&]() {
    if (fiber.points.size() >= 2)
    {
      fiber.points.shrink_to_fit(); // drop push_back's growth slack: the model holds the data once
      fiber.id = static_cast<std::int64_t>(streamlines);
      fiber.bundle = 0;
      fiber.radii.assign(fiber.points.size(), defaultRadius);
      result.model.fibers.push_back(std::move(fiber));
    }
    else
    {
      ++result.droppedFibers;
    }
    fiber = Fiber{};
    ++streamlines;
  };
  while (!sawEnd && remaining >= tripletSize)
  {
    const std::size_t triplets = static_cast<std::size_t>(std::min<std::uint64_t>(remaining / tripletSize, tripletsPerBlock));
    const std::size_t bytes = triplets * static_cast<std::size_t>(tripletSize);
    in.read(reinterpret_cast<char*>(block.data()), static_cast<std::streamsize>(bytes));
    if (static_cast<std::size_t>(in.gcount()) != bytes)
    {
      return fail(at(fileName, "byte", position + static_cast<std::uint64_t>(in.gcount()), "read error"));
    }
    for (std::size_t t = 0; t < triplets; ++t, position += tripletSize)
    {
      const unsigned char* p = block.data() + t * tripletSize;
      double v[3];
      for (int a = 0; a < 3; ++a)
      {
        v[a] = valueSize == 4 ? static_cast<double>(binary::loadFloat32(p + a * 4, little))
                              : binary::loadFloat64(p + a * 8, little);
      }
      const int nans = std::isnan(v[0]) + std::isnan(v[1]) + std::isnan(v[2]);
      const int infs = std::isinf(v[0]) + std::isinf(v[1]) + std::isinf(v[2]);
      if (nans == 0 && infs == 0)
      {
        fiber.points.push_back({ v[0], v[1], v[2] });
        continue;
      }
      if (nans == 3)
      {
        finishFiber();
        continue;
      }
      if (infs == 3)
      {
        if (!fiber.points.empty()) // tolerated: last streamline closed by the end marker only
        {
          finishFiber();
        }
        sawEnd = true;
        position += tripletSize;
        break;
      }
      return fail(at(fileName, "byte", position, "triplet mixes finite and NaN/Inf values"));
    }
    remaining -= bytes;
  }
  if (!sawEnd)
  {
    return fail(at(fileName, "byte", fileSize,
      "data ends without the Inf end-of-tracks triplet (truncated file?)"));
  }
  if (haveCount && streamlines != count)
  {
    std::ostringstream msg;
    msg << "header count " << count << " but the data holds " << streamlines << " streamlines";
    return fail(at(fileName, "line", countLine, msg.str()));
  }
  return result;
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

  // The offset is the header's own length, which depends on the offset's digits: iterate.
  const std::string start =
    "mrtrix tracks\ndatatype: Float32LE\ncount: " + std::to_string(model.fibers.size()) + "\n";
  std::size_t offset = 0;
  std::string header;
  for (;;)
  {
    header = start + "file: . " + std::to_string(offset) + "\nEND\n";
    if (header.size() == offset)
    {
      break;
    }
    offset = header.size();
  }
  out.write(header.data(), static_cast<std::streamsize>(header.size()));

  std::vector<unsigned char> block(12 * 4096);
  std::size_t used = 0;
  auto triplet = [&](float x, float y, float z) {
    if (used == block.size())
    {
      out.write(reinterpret_cast<const char*>(block.data()), static_cast<std::streamsize>(used));
      used = 0;
    }
    binary::storeFloat32LE(block.data() + used, x);
    binary::storeFloat32LE(block.data() + used + 4, y);
    binary::storeFloat32LE(block.data() + used + 8, z);
    used += 12;
  };
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (const Fiber& f : model.fibers)
  {
    for (const Vec3& p : f.points)
    {
      triplet(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z));
    }
    triplet(nan, nan, nan);
  }
  triplet(inf, inf, inf);
  out.write(reinterpret_cast<const char*>(block.data()), static_cast<std::streamsize>(used));
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
