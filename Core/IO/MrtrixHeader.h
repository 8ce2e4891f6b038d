/// MrtrixHeader: the text header shared by MRtrix's streamline files, tracks (.tck, TckFormat.h)
/// and track scalars (.tsf, TsfFormat.h) (docs/api.md §4; MRtrix3 docs, "Tracks file
/// format"). Layout: a magic first line, "key: value" lines, "END". Keys used here: `datatype`
/// (Float32LE, Float32BE, Float64LE, Float64BE), `file: . <offset>` (data in the same file from
/// byte <offset>), `count` (streamlines) and `timestamp` (pairs a .tsf with its .tck); other keys
/// are ignored. Internal helper, not part of the public API.
#pragma once

#include "Util/Status.h"

#include <cstddef>
#include <cstdint>
#include <istream>
#include <string>

namespace fiberpli
{

/// error: empty when the header is usable.
struct MrtrixHeader : Status
{
  std::uint64_t fileSize = 0;   ///< bytes from the stream start to its end
  std::uint64_t dataOffset = 0; ///< `file: . <offset>`, checked to lie in [end of header, fileSize]
  std::size_t valueSize = 0;    ///< 4 or 8
  bool littleEndian = true;
  bool haveCount = false;
  std::uint64_t count = 0;   ///< checked against the data size (see readMrtrixHeader)
  std::size_t countLine = 0; ///< header line of `count`, for messages
  std::string timestamp;     ///< value of `timestamp:` as written; empty when absent
};

/// Reads the header from the start of in (which must be seekable: sizes are checked against the
/// file length before anything is allocated). magic is the required first line ("mrtrix tracks" or
/// "mrtrix track scalars"), kind names the file type in messages. valuesPerPoint (3 for .tck, 1
/// for .tsf) bounds `count`: every streamline needs at least its NaN separator, plus the final Inf.
/// Errors name fileName and the header line.
MrtrixHeader readMrtrixHeader(std::istream& in, const std::string& fileName,
  const std::string& magic, const std::string& kind, std::size_t valuesPerPoint);

/// The header text "<magic>\n<keyLines>file: . <offset>\nEND\n" where <offset> is the length of
/// the returned text itself (the data follows immediately). keyLines: "key: value\n" lines.
std::string composeMrtrixHeader(const std::string& magic, const std::string& keyLines);

/// "<fileName> <unit> <where>: <what>", the error form of every MRtrix reader message.
std::string mrtrixErrorAt(
  const std::string& fileName, const char* unit, std::uint64_t where, const std::string& what);

} // namespace fiberpli
