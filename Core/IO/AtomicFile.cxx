#include "IO/AtomicFile.h"

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <exception>
#include <streambuf>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace fiberpli
{

namespace
{

/// Buffered ostream target over a POSIX descriptor: std::ofstream cannot fsync its file.
class FdStreamBuf : public std::streambuf
{
public:
  explicit FdStreamBuf(int fd)
    : fd_(fd)
    , buffer_(1 << 16)
  {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }
  int error() const { return error_; }

protected:
  int_type overflow(int_type c) override
  {
    if (!flushBuffer())
    {
      return traits_type::eof();
    }
    if (!traits_type::eq_int_type(c, traits_type::eof()))
    {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return flushBuffer() ? 0 : -1; }

private:
  bool flushBuffer()
  {
    const char* p = pbase();
    std::size_t left = static_cast<std::size_t>(pptr() - pbase());
    while (left > 0)
    {
      const ssize_t n = ::write(fd_, p, left);
      if (n < 0)
      {
        if (errno == EINTR)
        {
          continue;
        }
        error_ = errno;
        return false;
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return true;
  }

  int fd_;
  std::vector<char> buffer_;
  int error_ = 0;
};

std::string systemError(const std::string& what, const std::string& path, int err)
{
  return what + " " + path + ": " + std::strerror(err);
}

std::string directoryOf(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  if (slash == std::string::npos)
  {
    return ".";
  }
  return slash == 0 ? "/" : path.substr(0, slash);
}

/// 16 hex digits from the system's entropy source, mixed with pid, time and a counter so that a
/// failing std::random_device still gives distinct names.
std::string randomSuffix()
{
  static std::atomic<std::uint64_t> counter{ 0 };
  std::uint64_t x = static_cast<std::uint64_t>(::getpid()) << 40;
  x ^= static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
  x ^= counter.fetch_add(0x9e3779b97f4a7c15ULL);
  try
  {
    std::random_device rd;
    x ^= (static_cast<std::uint64_t>(rd()) << 32) ^ rd();
  }
  catch (const std::exception&)
  {
  }
  // splitmix64 finaliser: neighbouring inputs give unrelated names.
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  x ^= x >> 31;
  char text[17];
  std::snprintf(text, sizeof(text), "%016llx", static_cast<unsigned long long>(x));
  return text;
}

} // namespace

std::string writeFileAtomically(const std::string& path,
  const std::function<std::string(std::ostream& out)>& writeContent)
{
  if (path.empty())
  {
    return "cannot write a file with an empty path";
  }
  struct stat targetInfo;
  const bool targetExists = ::stat(path.c_str(), &targetInfo) == 0;
  if (targetExists && S_ISDIR(targetInfo.st_mode))
  {
    return "cannot write " + path + ": it is a directory";
  }

  // A random name, created with O_EXCL | O_NOFOLLOW: a file or symlink planted at a predictable
  // name could otherwise be followed (and its target overwritten); on a clash, draw again.
  std::string tmp;
  int fd = -1;
  for (int attempt = 0; attempt < 64 && fd < 0; ++attempt)
  {
    tmp = path + ".tmp-" + randomSuffix();
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd < 0 && errno != EEXIST)
    {
      break;
    }
  }
  if (fd < 0)
  {
    return systemError("cannot create temporary file for", path, errno);
  }

  std::string error;
  {
    FdStreamBuf buf(fd);
    std::ostream out(&buf);
    try
    {
      error = writeContent(out);
    }
    catch (const std::exception& e) // nothing may escape the Core API, and the temp file must go
    {
      error = "cannot write " + path + ": " + e.what();
    }
    catch (...)
    {
      error = "cannot write " + path + ": unknown failure";
    }
    if (error.empty())
    {
      out.flush();
      if (!out)
      {
        error = systemError("cannot write", path, buf.error() ? buf.error() : EIO);
      }
    }
  }
  if (error.empty() && targetExists && ::fchmod(fd, targetInfo.st_mode & 07777) != 0)
  {
    error = systemError("cannot set permissions of", path, errno);
  }
  if (error.empty() && ::fsync(fd) != 0)
  {
    error = systemError("cannot sync", path, errno);
  }
  if (::close(fd) != 0 && error.empty())
  {
    error = systemError("cannot close", path, errno);
  }
  if (error.empty() && ::rename(tmp.c_str(), path.c_str()) != 0)
  {
    error = systemError("cannot replace", path, errno);
  }
  if (!error.empty())
  {
    ::unlink(tmp.c_str());
    return error;
  }
  // Make the rename itself durable; failure here cannot undo the (complete) write, so ignore it.
  const int dirFd = ::open(directoryOf(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dirFd >= 0)
  {
    ::fsync(dirFd);
    ::close(dirFd);
  }
  return {};
}

} // namespace fiberpli
