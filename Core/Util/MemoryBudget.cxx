#include "Util/MemoryBudget.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace fiberpli
{
namespace
{

/// Parses "123", "64K", "512M", "2G" (binary multiples); 0 when malformed.
std::uint64_t parseByteCount(const char* text)
{
  if (!text || !*text)
  {
    return 0;
  }
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (errno != 0 || end == text || !(value > 0.0))
  {
    return 0;
  }
  double scale = 1.0;
  switch (*end)
  {
    case 'k':
    case 'K':
      scale = 1024.0;
      ++end;
      break;
    case 'm':
    case 'M':
      scale = 1024.0 * 1024.0;
      ++end;
      break;
    case 'g':
    case 'G':
      scale = 1024.0 * 1024.0 * 1024.0;
      ++end;
      break;
    case 't':
    case 'T':
      scale = 1024.0 * 1024.0 * 1024.0 * 1024.0;
      ++end;
      break;
    default:
      break;
  }
  if (*end == 'i' || *end == 'B')
  {
    ++end;
  }
  if (*end == 'B')
  {
    ++end;
  }
  const double bytes = value * scale;
  if (*end != '\0' || !(bytes < 1.8e19))
  {
    return 0;
  }
  return static_cast<std::uint64_t>(bytes);
}

/// cgroup v2 memory.max, then v1 memory.limit_in_bytes; 0 when absent or "max".
std::uint64_t cgroupLimitBytes()
{
  for (const char* path :
    { "/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes" })
  {
    std::ifstream in(path);
    std::string word;
    if (in >> word && word != "max")
    {
      const std::uint64_t limit = parseByteCount(word.c_str());
      if (limit > 0)
      {
        return limit;
      }
    }
  }
  return 0;
}

} // namespace

std::uint64_t usableMemoryBytes()
{
  std::uint64_t usable = 0;
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long pageSize = sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && pageSize > 0)
  {
    usable = static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(pageSize);
  }
  auto lower = [&usable](std::uint64_t limit)
  {
    if (limit > 0 && (usable == 0 || limit < usable))
    {
      usable = limit;
    }
  };
  lower(cgroupLimitBytes());
  for (int resource : { RLIMIT_AS, RLIMIT_DATA })
  {
    rlimit rl{};
    if (getrlimit(resource, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
    {
      lower(static_cast<std::uint64_t>(rl.rlim_cur));
    }
  }
  return usable > 0 ? usable : (std::uint64_t{ 4 } << 30); // unknown machine: assume 4 GiB
}

double memoryBudgetBytes()
{
  const std::uint64_t forced = parseByteCount(std::getenv("FIBERPLI_MEMORY_LIMIT"));
  if (forced > 0)
  {
    return static_cast<double>(forced);
  }
  return 0.5 * static_cast<double>(usableMemoryBytes());
}

std::string formatBytes(double bytes)
{
  const char* units[] = { "B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB" };
  int unit = 0;
  while (bytes >= 1024.0 && unit < 6)
  {
    bytes /= 1024.0;
    ++unit;
  }
  char text[64];
  std::snprintf(text, sizeof(text), unit == 0 ? "%.0f %s" : "%.3g %s", bytes, units[unit]);
  return text;
}

std::string checkMemoryBudget(double bytes, const std::string& what)
{
  const double budget = memoryBudgetBytes();
  if (bytes <= budget) // false for NaN: a NaN estimate is refused too
  {
    return {};
  }
  std::ostringstream msg;
  msg << what << " needs " << formatBytes(bytes) << ", more than the memory budget "
      << formatBytes(budget)
      << " (half of this machine's usable memory; FIBERPLI_MEMORY_LIMIT overrides it)";
  return msg.str();
}

} // namespace fiberpli
