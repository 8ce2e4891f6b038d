#include "IO/CactusFormat.h"

#include "IO/LineReader.h"
#include "IO/TextFields.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <sstream>

namespace fiberpli
{

namespace
{

using namespace textfields;

constexpr std::size_t maxLineLength = 4096;
/// The shortest text a strand and a point line can have: "0\n" and "0 0 0 1\n".
constexpr std::uintmax_t kMinStrandBytes = 2;
constexpr std::uintmax_t kMinPointBytes = 8;

bool isBlank(std::string_view line)
{
  return std::all_of(line.begin(), line.end(), isBlankChar);
}

/// Reads lines while tracking how many bytes of the file they used.
struct CountingReader
{
  LineReader reader;
  std::uintmax_t consumed = 0;
  LineReader::Status next(std::string_view& line)
  {
    const LineReader::Status s = reader.next(line);
    if (s == LineReader::Status::Line)
    {
      consumed += line.size() + 1;
    }
    return s;
  }
};

} // namespace

CactusReadResult readCactusStrands(
  std::istream& in, const std::string& fileName, std::uintmax_t fileBytes)
{
  CactusReadResult result;
  CountingReader lines{ LineReader(in, maxLineLength) };
  auto fail = [&](std::size_t line, const std::string& what)
  {
    CactusReadResult failed;
    failed.error = lineError(fileName, line, what);
    return failed;
  };
  auto remaining = [&]()
  { return fileBytes > lines.consumed ? fileBytes - lines.consumed : std::uintmax_t(0); };
  std::string_view line;
  // One line of exactly one token; what names the line's meaning for messages.
  auto single = [&](const char* what, std::string_view& token, std::string& why)
  {
    const LineReader::Status s = lines.next(line);
    if (s == LineReader::Status::TooLong)
    {
      why = lines.reader.tooLongMessage();
      return false;
    }
    if (s != LineReader::Status::Line)
    {
      why = std::string("file ends where ") + what + " is expected";
      return false;
    }
    std::string_view t[2];
    const std::size_t n = splitTokens(line, t, 2);
    if (n != 1)
    {
      why = std::string("expected ") + what + " alone on the line, found " + std::to_string(n) +
        " fields";
      return false;
    }
    token = t[0];
    return true;
  };

  std::string why;
  std::string_view token;
  if (!single("the box size", token, why))
  {
    return fail(std::max<std::size_t>(lines.reader.lineNumber(), 1), why);
  }
  why = parseFinite(token, result.boxSize);
  if (!why.empty())
  {
    return fail(lines.reader.lineNumber(), "box size " + why);
  }
  unsigned long long strands = 0;
  if (!single("the strand count", token, why))
  {
    return fail(lines.reader.lineNumber() + (why.rfind("file ends", 0) == 0 ? 1 : 0), why);
  }
  why = parseCount(token, strands);
  if (!why.empty())
  {
    return fail(lines.reader.lineNumber(), "strand " + why);
  }
  if (strands > remaining() / kMinStrandBytes)
  {
    std::ostringstream msg;
    msg << "strand count " << strands << " needs at least " << kMinStrandBytes
        << " bytes per strand but only " << remaining() << " bytes follow";
    return fail(lines.reader.lineNumber(), msg.str());
  }
  result.model.fibers.reserve(static_cast<std::size_t>(strands));
  for (unsigned long long s = 0; s < strands; ++s)
  {
    unsigned long long points = 0;
    if (!single("a point count", token, why))
    {
      std::ostringstream msg;
      msg << "strand " << s << " of " << strands << ": " << why
          << " (the strand count on line 2 says " << strands << ")";
      return fail(lines.reader.lineNumber() + (why.rfind("file ends", 0) == 0 ? 1 : 0), msg.str());
    }
    why = parseCount(token, points);
    if (!why.empty())
    {
      return fail(lines.reader.lineNumber(), "point " + why);
    }
    if (points > remaining() / kMinPointBytes)
    {
      std::ostringstream msg;
      msg << "point count " << points << " of strand " << s << " needs at least " << kMinPointBytes
          << " bytes per point but only " << remaining() << " bytes follow";
      return fail(lines.reader.lineNumber(), msg.str());
    }
    Fiber fiber;
    fiber.id = static_cast<std::int64_t>(s);
    fiber.points.reserve(static_cast<std::size_t>(points));
    fiber.radii.reserve(static_cast<std::size_t>(points));
    for (unsigned long long p = 0; p < points; ++p)
    {
      const LineReader::Status st = lines.next(line);
      if (st == LineReader::Status::TooLong)
      {
        return fail(lines.reader.lineNumber(), lines.reader.tooLongMessage());
      }
      if (st != LineReader::Status::Line)
      {
        std::ostringstream msg;
        msg << "file ends after " << p << " of the " << points << " points of strand " << s;
        return fail(lines.reader.lineNumber() + 1, msg.str());
      }
      std::string_view t[4];
      const std::size_t n = splitTokens(line, t, 4);
      if (n != 4)
      {
        std::ostringstream msg;
        msg << "expected 4 numbers 'x y z r' (point " << p << " of " << points << " of strand " << s
            << "), found " << n << " fields";
        return fail(lines.reader.lineNumber(), msg.str());
      }
      double v[4];
      for (int k = 0; k < 4; ++k)
      {
        why = parseFinite(t[k], v[k]);
        if (!why.empty())
        {
          return fail(lines.reader.lineNumber(), why);
        }
      }
      if (!(v[3] > 0.0))
      {
        return fail(lines.reader.lineNumber(), valueMustBe("radius", v[3], "> 0"));
      }
      fiber.points.push_back({ v[0], v[1], v[2] });
      fiber.radii.push_back(v[3]);
    }
    if (fiber.points.size() >= 2)
    {
      result.model.fibers.push_back(std::move(fiber));
    }
    else
    {
      ++result.droppedFibers;
    }
  }
  for (;;)
  {
    const LineReader::Status st = lines.next(line);
    if (st == LineReader::Status::End)
    {
      break;
    }
    if (st != LineReader::Status::Line || !isBlank(line))
    {
      std::ostringstream msg;
      msg << "content after the last of the " << strands
          << " strands the count on line 2 announces";
      return fail(lines.reader.lineNumber(), msg.str());
    }
  }
  return result;
}

std::string writeCactusStrands(std::ostream& out, const FiberModel& model, double boxSize)
{
  const std::string invalid = validateModel(model);
  if (!invalid.empty())
  {
    return "cannot write CACTUS strands: " + invalid;
  }
  if (!std::isfinite(boxSize))
  {
    return "cannot write CACTUS strands: the box size is not finite";
  }
  std::string text;
  appendNumber(text, boxSize);
  text += '\n';
  text += std::to_string(model.fibers.size());
  text += '\n';
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  for (const Fiber& f : model.fibers)
  {
    text = std::to_string(f.size());
    text += '\n';
    for (std::size_t i = 0; i < f.size(); ++i)
    {
      appendNumber(text, f.points[i].x);
      text += ' ';
      appendNumber(text, f.points[i].y);
      text += ' ';
      appendNumber(text, f.points[i].z);
      text += ' ';
      appendNumber(text, f.radii[i]);
      text += '\n';
    }
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  }
  out.flush();
  if (!out)
  {
    return "cannot write CACTUS strands: the output stream failed";
  }
  return {};
}

bool looksLikeCactusStrands(std::istream& in)
{
  const std::streampos start = in.tellg();
  if (start == std::streampos(-1))
  {
    return false;
  }
  bool ok = true;
  {
    LineReader reader(in, 256);
    std::string_view line;
    std::string_view t[5];
    double x = 0.0;
    unsigned long long count = 0;
    unsigned long long firstStrandPoints = 0;
    for (int k = 0; k < 4 && ok; ++k)
    {
      if (reader.next(line) != LineReader::Status::Line)
      {
        ok = k >= 2 && (k == 3 ? firstStrandPoints == 0 : count == 0); // short but complete files
        break;
      }
      const std::size_t n = splitTokens(line, t, 5);
      if (k == 0)
      {
        ok = n == 1 && parseFinite(t[0], x).empty();
      }
      else if (k == 1)
      {
        ok = n == 1 && parseCount(t[0], count).empty();
      }
      else if (k == 2)
      {
        ok = n == 1 && parseCount(t[0], firstStrandPoints).empty();
      }
      else
      {
        ok = n == 4;
        for (std::size_t i = 0; i < 4 && ok; ++i)
        {
          ok = parseFinite(t[i], x).empty();
        }
      }
    }
  }
  in.clear();
  in.seekg(start);
  return ok;
}

} // namespace fiberpli
