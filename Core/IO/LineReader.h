/// LineReader: block-buffered line splitter over a std::istream for the text formats of Core/IO.
/// Reads 64 KiB blocks (much faster than std::getline per line) and hands out views into its own
/// buffer, so memory stays bounded whatever the file: a line longer than maxLineLength is reported
/// instead of being buffered. Internal helper, not part of the public API.
#pragma once

#include <cstddef>
#include <istream>
#include <string>
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

  /// What ended nextLine before the end of the text: the line it concerns and the message.
  struct Stop
  {
    std::size_t line = 0;
    std::string what; ///< "" at the end of the text
    bool failed() const { return !what.empty(); }
  };
  /// The loop of a reader that reads every line: true with the next line; false at the end of the
  /// text (stop not failed), at a line longer than maxLineLength (stop: that line, "line is longer
  /// than <maxLineLength> characters" and tooLongNote) or at a read error (stop: the line after
  /// the last one returned, "read error").
  bool nextLine(std::string_view& line, Stop& stop, const std::string& tooLongNote = {});
  /// "line is longer than <maxLineLength> characters": how the readers report Status::TooLong.
  std::string tooLongMessage() const;
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
