#include "IO/MrtrixHeader.h"
#include "Util/PrintableText.h"

#include "Util/BinaryIO.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <sstream>
#include <string_view>

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
  std::transform(r.begin(), r.end(), r.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return r;
}

bool parseUnsigned(std::string_view s, std::uint64_t& value)
{
  const std::from_chars_result r = std::from_chars(s.data(), s.data() + s.size(), value);
  return r.ec == std::errc() && r.ptr == s.data() + s.size() && !s.empty();
}

} // namespace

std::string mrtrixErrorAt(
  const std::string& fileName, const char* unit, std::uint64_t where, const std::string& what)
{
  std::ostringstream msg;
  msg << fileName << " " << unit << " " << where << ": " << what;
  return msg.str();
}

MrtrixHeader readMrtrixHeader(std::istream& in, const std::string& fileName,
  const std::string& magic, const std::string& kind, std::size_t valuesPerPoint)
{
  MrtrixHeader h;
  auto fail = [&](const std::string& message)
  {
    MrtrixHeader failed;
    failed.error = message;
    return failed;
  };
  if (!binary::remainingBytes(in, h.fileSize))
  {
    return fail(fileName + ": cannot determine the file size (stream is not seekable)");
  }

  // Text up to the END line, bounded so a binary file cannot make us read it all.
  std::string head(
    static_cast<std::size_t>(std::min<std::uint64_t>(h.fileSize, maxHeaderBytes)), '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  if (static_cast<std::size_t>(in.gcount()) != head.size())
  {
    return fail(mrtrixErrorAt(
      fileName, "byte", static_cast<std::uint64_t>(in.gcount()), "read error in the header"));
  }
  std::size_t pos = 0;
  std::size_t lineNo = 0;
  std::uint64_t headerEnd = 0;
  std::string datatype;
  std::string fileValue;
  std::string countValue;
  std::size_t fileLine = 0;
  std::size_t datatypeLine = 0;
  std::size_t timestampLine = 0;
  for (;;)
  {
    const std::size_t nl = head.find('\n', pos);
    if (nl == std::string::npos)
    {
      return fail(mrtrixErrorAt(fileName, "line", lineNo + 1,
        head.size() < maxHeaderBytes ? "header ends without an END line (truncated file?)"
                                     : "no END line in the first 1 MiB of the header"));
    }
    const std::string_view line = trim(std::string_view(head).substr(pos, nl - pos));
    pos = nl + 1;
    ++lineNo;
    if (lineNo == 1)
    {
      if (line != magic)
      {
        return fail(mrtrixErrorAt(
          fileName, "line", 1, "not an " + kind + " file (first line must be '" + magic + "')"));
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
      return fail(mrtrixErrorAt(fileName, "line", lineNo, "header line is not 'key: value'"));
    }
    const std::string key = lower(trim(line.substr(0, colon)));
    const std::string_view value = trim(line.substr(colon + 1));
    auto setOnce = [&](std::string& slot, std::size_t& slotLine)
    {
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
      ok = setOnce(countValue, h.countLine);
    }
    else if (key == "timestamp")
    {
      ok = setOnce(h.timestamp, timestampLine);
    }
    if (!ok)
    {
      return fail(mrtrixErrorAt(fileName, "line", lineNo,
        "'" + printableText(key) + "' given twice with different values"));
    }
  }

  const std::string dt = lower(datatype);
  if (dt == "float32le" || dt == "float32be")
  {
    h.valueSize = 4;
  }
  else if (dt == "float64le" || dt == "float64be")
  {
    h.valueSize = 8;
  }
  else if (datatype.empty())
  {
    return fail(fileName + ": header has no 'datatype' line");
  }
  else
  {
    return fail(mrtrixErrorAt(fileName, "line", datatypeLine,
      "datatype '" + printableText(datatype) +
        "' is not supported (Float32LE, Float32BE, Float64LE, Float64BE)"));
  }
  h.littleEndian = dt.compare(dt.size() - 2, 2, "le") == 0;

  if (fileValue.empty())
  {
    return fail(fileName + ": header has no 'file: . <offset>' line");
  }
  const std::string_view fv(fileValue);
  if (fv.size() < 2 || fv[0] != '.' || (fv[1] != ' ' && fv[1] != '\t'))
  {
    return fail(mrtrixErrorAt(fileName, "line", fileLine,
      "'file: " + printableText(fileValue) +
        "': only data in the same file ('file: . <offset>') is supported"));
  }
  if (!parseUnsigned(trim(fv.substr(1)), h.dataOffset))
  {
    return fail(mrtrixErrorAt(fileName, "line", fileLine,
      "'file: " + printableText(fileValue) + "': offset is not a number"));
  }
  if (h.dataOffset < headerEnd || h.dataOffset > h.fileSize)
  {
    std::ostringstream msg;
    msg << "data offset " << h.dataOffset << " must lie between the end of the header (byte "
        << headerEnd << ") and the end of the file (byte " << h.fileSize << ")";
    return fail(mrtrixErrorAt(fileName, "line", fileLine, msg.str()));
  }

  h.haveCount = !countValue.empty();
  if (h.haveCount)
  {
    if (!parseUnsigned(countValue, h.count))
    {
      return fail(mrtrixErrorAt(fileName, "line", h.countLine,
        "count '" + printableText(countValue) + "' is not a number"));
    }
    // Every streamline needs at least its NaN separator, plus the final Inf: this bounds any
    // allocation sized by count to the real file length.
    const std::uint64_t groupSize = valuesPerPoint * h.valueSize;
    const std::uint64_t dataBytes = h.fileSize - h.dataOffset;
    if (h.count > dataBytes / groupSize || h.count * groupSize + groupSize > dataBytes)
    {
      std::ostringstream msg;
      msg << "count " << h.count << " needs at least " << (h.count + 1)
          << (valuesPerPoint == 3 ? " triplets" : " values") << " but only " << dataBytes
          << " bytes of data follow the header";
      return fail(mrtrixErrorAt(fileName, "line", h.countLine, msg.str()));
    }
  }
  return h;
}

std::string composeMrtrixHeader(const std::string& magic, const std::string& keyLines)
{
  // The offset is the header's own length, which depends on the offset's digits: iterate.
  const std::string start = magic + "\n" + keyLines;
  std::size_t offset = 0;
  for (;;)
  {
    std::string header = start + "file: . " + std::to_string(offset) + "\nEND\n";
    if (header.size() == offset)
    {
      return header;
    }
    offset = header.size();
  }
}

} // namespace fiberpli
