/// LineReader: block-buffered line splitter over a std::istream for the text formats of Core/IO.
/// Reads 64 KiB blocks (much faster than std::getline per line) and hands out views into its own
/// buffer, so memory stays bounded whatever the file: a line longer than maxLineLength is reported
/// instead of being buffered. Internal helper, not part of the public API.
#pragma once

#include <cstddef>
#include <istream>
#include <string_view>
#include <vector>

namespace fiberpli
{

class LineReader
{
public:
  enum class Status
  {
    Line,    ///< line holds the next line without '\n' (and without a trailing '\r')
    End,     ///< no more lines
    TooLong, ///< the next line exceeds maxLineLength
    Failed   ///< the stream reported a read error
  };

  LineReader(std::istream& in, std::size_t maxLineLength);

  /// The view stays valid until the next call.
  Status next(std::string_view& line);
  /// 1-based number of the line last returned (or of the too-long line).
  std::size_t lineNumber() const { return lineNumber_; }

private:
  bool fill();

  std::istream& in_;
  std::size_t maxLineLength_;
  std::vector<char> buffer_;
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  bool eof_ = false;
  bool failed_ = false;
  std::size_t lineNumber_ = 0;
};

} // namespace fiberpli
