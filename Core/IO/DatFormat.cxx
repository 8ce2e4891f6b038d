#include "IO/DatFormat.h"
#include "Util/PrintableText.h"

#include "IO/LineReader.h"
#include "IO/TextFields.h"
#include "Util/ValueCheck.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <system_error>

namespace fiberpli
{

namespace
{

constexpr std::size_t maxLineLength = 4096; // a point line is < 100 characters

using textfields::isBlankChar;

std::string_view trim(std::string_view s)
{
  std::size_t b = 0;
  std::size_t e = s.size();
  while (b < e && isBlankChar(s[b]))
  {
    ++b;
  }
  while (e > b && isBlankChar(s[e - 1]))
  {
    --e;
  }
  return s.substr(b, e - b);
}

enum class PointParse
{
  Ok,
  WrongCount,
  NotANumber,
  NotFinite,
  BadRadius
};

/// Parses "x y z r" into v[4]; count and bad token are returned for the message.
PointParse parsePointLine(
  std::string_view line, double v[4], int& count, std::string_view& badToken)
{
  std::string_view tokens[4];
  const std::size_t total =
    textfields::splitTokens(line, tokens, 4); // all tokens counted, for the message
  count = 0;
  while (static_cast<std::size_t>(count) < std::min<std::size_t>(total, 4))
  {
    const std::string_view token = tokens[count];
    const char* first = token.data();
    const char* last = token.data() + token.size();
    if (last - first > 1 && *first == '+') // Python's float() (fastPLI's reader) accepts "+1.5"
    {
      ++first;
    }
    double value = 0.0;
    const std::from_chars_result r = std::from_chars(first, last, value);
    if (r.ec == std::errc::result_out_of_range)
    {
      badToken = token;
      return PointParse::NotFinite;
    }
    if (r.ec != std::errc() || r.ptr != last)
    {
      badToken = token;
      return PointParse::NotANumber;
    }
    if (!std::isfinite(value))
    {
      badToken = token;
      return PointParse::NotFinite;
    }
    v[count++] = value;
  }
  count = static_cast<int>(std::min<std::size_t>(total, 1 << 30));
  if (count != 4)
  {
    return PointParse::WrongCount;
  }
  if (!(v[3] > 0.0))
  {
    return PointParse::BadRadius;
  }
  return PointParse::Ok;
}

std::string lineError(const std::string& fileName, std::size_t line, const std::string& what)
{
  std::ostringstream msg;
  msg << fileName << " line " << line << ": " << what;
  return msg.str();
}

std::string describePointError(
  PointParse p, int count, std::string_view badToken, const double v[4])
{
  std::ostringstream msg;
  switch (p)
  {
    case PointParse::WrongCount:
      msg << "expected 4 numbers 'x y z r', found " << count;
      break;
    case PointParse::NotANumber:
      msg << "'" << printableText(badToken) << "' is not a number";
      break;
    case PointParse::NotFinite:
      msg << "'" << printableText(badToken) << "' is not a finite number";
      break;
    case PointParse::BadRadius:
      msg << valueMustBe("radius", v[3], "> 0");
      break;
    case PointParse::Ok:
      break;
  }
  return msg.str();
}

} // namespace

FiberReadResult readFastPliDat(std::istream& in, const std::string& fileName)
{
  FiberReadResult result;
  FiberModel& model = result.model;
  LineReader reader(in, maxLineLength);
  Fiber fiber;
  std::int64_t fiberOrdinal = 0;
  int bundle = 0;
  bool bundleHasFibers = false;
  int blankRun = 0;

  // One blank line closes the fiber; fiber ids count every fiber of the file, kept or dropped.
  auto finishFiber = [&]()
  {
    if (fiber.points.size() >= 2)
    {
      // Drop push_back's growth slack (up to 2x) so the model holds the data once, not ~1.3 times.
      fiber.points.shrink_to_fit();
      fiber.radii.shrink_to_fit();
      fiber.id = fiberOrdinal;
      fiber.bundle = bundle;
      model.fibers.push_back(std::move(fiber));
    }
    else
    {
      ++result.droppedFibers;
    }
    fiber = Fiber{};
    ++fiberOrdinal;
    bundleHasFibers = true;
  };
  auto fail = [&](std::size_t line, const std::string& what)
  {
    result.model = FiberModel{};
    result.droppedFibers = 0;
    result.error = lineError(fileName, line, what);
    return result;
  };

  std::string_view line;
  LineReader::Stop stop;
  while (reader.nextLine(line, stop, " (not a fastPLI .dat point line)"))
  {
    const std::string_view s = trim(line);
    if (!s.empty() && s.front() == '#')
    {
      continue;
    }
    if (s.empty())
    {
      ++blankRun;
      if (blankRun == 1 && !fiber.points.empty())
      {
        finishFiber();
      }
      else if (blankRun == 2 && bundleHasFibers)
      {
        if (bundle == std::numeric_limits<int>::max())
        {
          return fail(reader.lineNumber(), "more bundles than bundle_id (int) can number");
        }
        ++bundle;
        bundleHasFibers = false;
      }
      continue;
    }
    blankRun = 0;
    double v[4];
    int count = 0;
    std::string_view badToken;
    const PointParse p = parsePointLine(s, v, count, badToken);
    if (p != PointParse::Ok)
    {
      return fail(reader.lineNumber(), describePointError(p, count, badToken, v));
    }
    fiber.points.push_back({ v[0], v[1], v[2] });
    fiber.radii.push_back(v[3]);
  }
  if (stop.failed())
  {
    return fail(stop.line, stop.what);
  }
  if (!fiber.points.empty())
  {
    finishFiber();
  }
  return result;
}

std::string writeFastPliDat(std::ostream& out, const FiberModel& model)
{
  const std::string invalid = validateModel(model);
  if (!invalid.empty())
  {
    return "cannot write .dat: " + invalid;
  }
  std::vector<std::size_t> order(model.fibers.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
    [&](std::size_t a, std::size_t b) { return model.fibers[a].bundle < model.fibers[b].bundle; });

  // Format into a block and write it in one call: per-number ostream << is several times slower.
  std::vector<char> block(1 << 16);
  std::size_t used = 0;
  auto flush = [&]()
  {
    out.write(block.data(), static_cast<std::streamsize>(used));
    used = 0;
  };
  auto put = [&](char c) { block[used++] = c; };
  auto number = [&](double x)
  {
    const std::to_chars_result r =
      std::to_chars(block.data() + used, block.data() + block.size(), x);
    used = static_cast<std::size_t>(r.ptr - block.data());
  };

  for (std::size_t k = 0; k < order.size(); ++k)
  {
    const Fiber& f = model.fibers[order[k]];
    if (k > 0 && f.bundle != model.fibers[order[k - 1]].bundle)
    {
      put('\n'); // second blank line: a new bundle
    }
    for (std::size_t i = 0; i < f.points.size(); ++i)
    {
      if (block.size() - used < 128) // 4 numbers of <= 24 characters + separators
      {
        flush();
      }
      number(f.points[i].x);
      put(' ');
      number(f.points[i].y);
      put(' ');
      number(f.points[i].z);
      put(' ');
      number(f.radii[i]);
      put('\n');
    }
    put('\n');
  }
  flush();
  out.flush();
  if (!out)
  {
    return "cannot write .dat: the output stream failed";
  }
  return {};
}

namespace
{
/// Tecplot ASCII files open with records such as TITLE = "...", VARIABLES = ..., ZONE ...
bool startsWithTecplotKeyword(std::string_view line)
{
  static const char* const keywords[] = { "TITLE", "VARIABLES", "ZONE", "TEXT", "GEOMETRY",
    "FILETYPE", "DATASETAUXDATA", "VARAUXDATA" };
  std::size_t end = 0;
  while (end < line.size() && std::isalpha(static_cast<unsigned char>(line[end])))
  {
    ++end;
  }
  for (const char* keyword : keywords)
  {
    const std::string_view k(keyword);
    if (end == k.size() &&
      std::equal(k.begin(), k.end(), line.begin(),
        [](char a, char b) { return a == std::toupper(static_cast<unsigned char>(b)); }))
    {
      return true;
    }
  }
  return false;
}
} // namespace

bool looksLikeFastPliDat(std::istream& in)
{
  const std::streampos start = in.tellg();
  if (start == std::streampos(-1))
  {
    return false;
  }
  std::string head(64 * 1024, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  in.clear();
  in.seekg(start);

  const bool complete = head.size() < 64 * 1024; // else the last line may be cut off
  // A broken fastPLI file (one bad line) must still reach our reader, which names the line;
  // only a majority of point lines and no Tecplot keyword make the file ours.
  int goodLines = 0, badLines = 0;
  std::size_t pos = 0;
  while (pos < head.size() && goodLines + badLines < 20)
  {
    std::size_t nl = head.find('\n', pos);
    if (nl == std::string::npos)
    {
      if (!complete)
      {
        break;
      }
      nl = head.size();
    }
    const std::string_view s = trim(std::string_view(head).substr(pos, nl - pos));
    pos = nl + 1;
    if (s.empty() || s.front() == '#')
    {
      continue;
    }
    if (s.find('\0') != std::string_view::npos || startsWithTecplotKeyword(s))
    {
      return false; // binary data, or a Tecplot header
    }
    double v[4];
    int count = 0;
    std::string_view bad;
    if (parsePointLine(s, v, count, bad) == PointParse::Ok)
    {
      ++goodLines;
    }
    else
    {
      ++badLines;
    }
  }
  return goodLines > 3 * badLines;
}

} // namespace fiberpli
