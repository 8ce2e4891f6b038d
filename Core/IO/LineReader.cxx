#include "IO/LineReader.h"

#include <cstring>

namespace fiberpli
{

namespace
{
constexpr std::size_t blockSize = std::size_t(1)
  << 16; // 64 KiB: big enough that read() calls are rare
}

LineReader::LineReader(std::istream& in, std::size_t maxLineLength)
  : in_(in)
  , maxLineLength_(maxLineLength)
  , buffer_(blockSize + maxLineLength + 1)
{
}

bool LineReader::fill()
{
  // Keep the unfinished line at the front so a view never spans two reads.
  if (begin_ > 0)
  {
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  if (end_ == buffer_.size())
  {
    return false;
  }
  in_.read(buffer_.data() + end_, static_cast<std::streamsize>(buffer_.size() - end_));
  const std::streamsize got = in_.gcount();
  if (in_.bad())
  {
    failed_ = true;
    return false;
  }
  if (got <= 0)
  {
    eof_ = true;
    return false;
  }
  end_ += static_cast<std::size_t>(got);
  return true;
}

LineReader::Status LineReader::next(std::string_view& line)
{
  std::size_t searched = begin_;
  for (;;)
  {
    const void* nl =
      searched < end_ ? std::memchr(buffer_.data() + searched, '\n', end_ - searched) : nullptr;
    if (nl)
    {
      const std::size_t pos =
        static_cast<std::size_t>(static_cast<const char*>(nl) - buffer_.data());
      std::size_t len = pos - begin_;
      ++lineNumber_;
      if (len > maxLineLength_)
      {
        return Status::TooLong;
      }
      if (len > 0 && buffer_[begin_ + len - 1] == '\r')
      {
        --len;
      }
      line = std::string_view(buffer_.data() + begin_, len);
      begin_ = pos + 1;
      return Status::Line;
    }
    if (end_ - begin_ > maxLineLength_)
    {
      ++lineNumber_;
      return Status::TooLong;
    }
    const std::size_t pending = end_ - begin_;
    if (!eof_ && !failed_ && fill())
    {
      searched = begin_ + pending;
      continue;
    }
    if (failed_)
    {
      return Status::Failed;
    }
    if (begin_ < end_) // last line without a newline
    {
      ++lineNumber_;
      std::size_t len = end_ - begin_;
      if (buffer_[begin_ + len - 1] == '\r')
      {
        --len;
      }
      line = std::string_view(buffer_.data() + begin_, len);
      begin_ = end_;
      return Status::Line;
    }
    return Status::End;
  }
}

bool LineReader::nextLine(std::string_view& line, Stop& stop, const std::string& tooLongNote)
{
  stop = Stop{};
  switch (next(line))
  {
    case Status::Line:
      return true;
    case Status::TooLong:
      stop.line = lineNumber_;
      stop.what = tooLongMessage() + tooLongNote;
      break;
    case Status::Failed:
      stop.line = lineNumber_ + 1;
      stop.what = "read error";
      break;
    case Status::End:
      break;
  }
  return false;
}

std::string LineReader::tooLongMessage() const
{
  return "line is longer than " + std::to_string(maxLineLength_) + " characters";
}

} // namespace fiberpli
