#include "IO/RegularFile.h"

#include <sys/stat.h>

namespace fiberpli
{

std::string checkRegularFile(const std::string& path)
{
  struct stat info;
  if (::stat(path.c_str(), &info) != 0 || S_ISREG(info.st_mode))
  {
    return {};
  }
  const char* what = S_ISFIFO(info.st_mode) ? "a FIFO (named pipe)"
    : S_ISDIR(info.st_mode)                 ? "a directory"
    : S_ISSOCK(info.st_mode)                ? "a socket"
    : S_ISCHR(info.st_mode)                 ? "a character device"
    : S_ISBLK(info.st_mode)                 ? "a block device"
                                            : "not a file";
  return path + " is " + what + ", not a regular file";
}

} // namespace fiberpli
