#include "IO/FiberFile.h"

#include "IO/AtomicFile.h"
#include "IO/DatFormat.h"
#include "IO/TckFormat.h"
#include "IO/TrkFormat.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>

namespace fiberpli
{

FiberFileFormat fiberFileFormatFromPath(const std::string& path)
{
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return FiberFileFormat::Unknown;
  }
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == "dat")
  {
    return FiberFileFormat::FastPliDat;
  }
  if (ext == "tck")
  {
    return FiberFileFormat::Tck;
  }
  if (ext == "trk")
  {
    return FiberFileFormat::Trk;
  }
  return FiberFileFormat::Unknown;
}

bool canReadFiberFile(const std::string& path)
{
  const FiberFileFormat format = fiberFileFormatFromPath(path);
  if (format == FiberFileFormat::Unknown)
  {
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    return false;
  }
  switch (format)
  {
    case FiberFileFormat::FastPliDat: return looksLikeFastPliDat(in);
    case FiberFileFormat::Tck: return looksLikeTck(in);
    case FiberFileFormat::Trk: return looksLikeTrk(in);
    case FiberFileFormat::Unknown: break;
  }
  return false;
}

FiberReadResult readFiberFile(const std::string& path, double defaultRadius)
{
  const FiberFileFormat format = fiberFileFormatFromPath(path);
  if (format == FiberFileFormat::Unknown)
  {
    FiberReadResult r;
    r.error = path + ": unknown fiber file extension (expected .dat, .tck or .trk)";
    return r;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    FiberReadResult r;
    r.error = "cannot open " + path + ": " + std::strerror(errno);
    return r;
  }
  switch (format)
  {
    case FiberFileFormat::FastPliDat: return readFastPliDat(in, path);
    case FiberFileFormat::Tck: return readTck(in, path, defaultRadius);
    case FiberFileFormat::Trk: return readTrk(in, path, defaultRadius);
    case FiberFileFormat::Unknown: break;
  }
  return {};
}

std::string writeFiberFile(const std::string& path, const FiberModel& model)
{
  const FiberFileFormat format = fiberFileFormatFromPath(path);
  std::string (*writer)(std::ostream&, const FiberModel&) = nullptr;
  if (format == FiberFileFormat::FastPliDat)
  {
    writer = &writeFastPliDat;
  }
  else if (format == FiberFileFormat::Tck)
  {
    writer = &writeTck;
  }
  else
  {
    return path + ": cannot write this extension (FiberWriter writes .dat and .tck here)";
  }
  return writeFileAtomically(path, [&](std::ostream& out) {
    const std::string error = writer(out, model);
    return error.empty() ? error : path + ": " + error;
  });
}

} // namespace fiberpli
