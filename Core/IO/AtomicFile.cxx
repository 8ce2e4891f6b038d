#include "IO/AtomicFile.h"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <random>
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

namespace
{

/// One file of an atomic write: its target, whether and how it existed, and its temporary file.
struct Staged
{
  std::string path;
  std::string tmp;
  bool targetExists = false;
  struct stat targetInfo;
};

/// Writes the content of one file into a new temporary file beside its target, flushed, synced
/// and closed. "" on success (staged.tmp exists), else the error (no temporary file is left).
std::string stage(const std::string& path,
  const std::function<std::string(std::ostream& out)>& writeContent, Staged& staged)
{
  staged.path = path;
  if (path.empty())
  {
    return "cannot write a file with an empty path";
  }
  staged.targetExists = ::stat(path.c_str(), &staged.targetInfo) == 0;
  if (staged.targetExists && S_ISDIR(staged.targetInfo.st_mode))
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
  if (error.empty() && staged.targetExists && ::fchmod(fd, staged.targetInfo.st_mode & 07777) != 0)
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
  if (!error.empty())
  {
    ::unlink(tmp.c_str());
    return error;
  }
  staged.tmp = tmp;
  return {};
}

/// Makes the renames in the directories of `paths` durable; a failure here cannot undo the
/// (complete) write, so it is ignored.
void syncDirectories(const std::vector<std::string>& paths)
{
  std::vector<std::string> done;
  for (const std::string& path : paths)
  {
    const std::string dir = directoryOf(path);
    if (std::find(done.begin(), done.end(), dir) != done.end())
    {
      continue;
    }
    done.push_back(dir);
    const int dirFd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (dirFd >= 0)
    {
      ::fsync(dirFd);
      ::close(dirFd);
    }
  }
}

} // namespace

std::string writeFileAtomically(
  const std::string& path, const std::function<std::string(std::ostream& out)>& writeContent)
{
  return writeFilesAtomically({ AtomicPart{ path, writeContent } });
}

std::string writeFilesAtomically(const std::vector<AtomicPart>& parts)
{
  // 1. Every temporary file written and synced; the first failure removes them all, and no
  //    target has been touched.
  std::vector<Staged> staged(parts.size());
  std::string error;
  for (std::size_t i = 0; i < parts.size() && error.empty(); ++i)
  {
    error = stage(parts[i].path, parts[i].writeContent, staged[i]);
  }
  const auto removeTemporaries = [&staged]()
  {
    for (const Staged& s : staged)
    {
      if (!s.tmp.empty())
      {
        ::unlink(s.tmp.c_str());
      }
    }
  };
  if (!error.empty())
  {
    removeTemporaries();
    return error;
  }
  // 2. With several files, the targets that exist get a hard-linked backup first, so that a
  //    rename failing half-way can put back the ones already replaced (renames of complete,
  //    synced files into the same directory practically never fail, but then the set is whole).
  std::vector<std::string> backups(parts.size());
  const auto removeBackups = [&backups]()
  {
    for (const std::string& b : backups)
    {
      if (!b.empty())
      {
        ::unlink(b.c_str());
      }
    }
  };
  for (std::size_t i = 0; parts.size() > 1 && i < staged.size(); ++i)
  {
    if (!staged[i].targetExists)
    {
      continue;
    }
    std::string backup;
    int rc = -1;
    for (int attempt = 0; attempt < 64 && rc != 0; ++attempt)
    {
      backup = staged[i].path + ".old-" + randomSuffix();
      rc = ::link(staged[i].path.c_str(), backup.c_str());
      if (rc != 0 && errno != EEXIST)
      {
        break;
      }
    }
    if (rc != 0)
    {
      error = systemError("cannot keep the old", staged[i].path, errno);
      removeBackups();
      removeTemporaries();
      return error;
    }
    backups[i] = backup;
  }
  // 3. The renames, in order; a failure restores the targets replaced so far.
  for (std::size_t i = 0; i < staged.size(); ++i)
  {
    if (::rename(staged[i].tmp.c_str(), staged[i].path.c_str()) == 0)
    {
      staged[i].tmp.clear();
      continue;
    }
    error = systemError("cannot replace", staged[i].path, errno);
    for (std::size_t k = 0; k < i; ++k)
    {
      if (!backups[k].empty())
      {
        ::rename(backups[k].c_str(), staged[k].path.c_str());
        backups[k].clear();
      }
      else
      {
        ::unlink(staged[k].path.c_str()); // it did not exist before
      }
    }
    removeBackups();
    removeTemporaries();
    return error;
  }
  removeBackups();
  std::vector<std::string> paths;
  for (const AtomicPart& p : parts)
  {
    paths.push_back(p.path);
  }
  syncDirectories(paths);
  return {};
}

} // namespace fiberpli
