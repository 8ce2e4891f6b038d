#include "IO/FiberFile.h"
#include "IO/RegularFile.h"
#include "Util/PrintableText.h"

#include "IO/AtomicFile.h"
#include "IO/CactusFormat.h"
#include "IO/CaterpillarFormat.h"
#include "IO/DatFormat.h"
#include "IO/MrtrixHeader.h"
#include "IO/TckFormat.h"
#include "IO/TrkFormat.h"
#include "IO/TsfFormat.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

#include <sys/stat.h>

namespace fiberpli
{

namespace
{

/// Replaces the default radii of a .tck read (tck) with the values of its radius file (tsf) after
/// checking that both describe the same streamlines (FiberFile.h, readFiberFile).
FiberReadResult applyRadii(FiberReadResult tck, const std::string& tckTimestampValue,
  const std::string& tckPath, const TsfReadResult& tsf, const std::string& tsfPath)
{
  if (!tsf.ok())
  {
    return readFailure(tsf.error);
  }
  if (!tsf.timestamp.empty() && !tckTimestampValue.empty() && tsf.timestamp != tckTimestampValue)
  {
    return readFailure(tsfPath + ": timestamp '" + printableText(tsf.timestamp) +
      "' differs from timestamp '" + printableText(tckTimestampValue) + "' of " + tckPath +
      " (the radii belong to other tracks; rewrite or remove the .tsf)");
  }
  const std::size_t streamlines = tck.model.fibers.size() + tck.droppedFibers;
  if (tsf.values.size() != streamlines)
  {
    std::ostringstream msg;
    msg << tsfPath << ": holds " << tsf.values.size() << " streamlines but " << tckPath << " holds "
        << streamlines;
    return readFailure(msg.str());
  }
  // Streamlines readTck dropped (fewer than 2 points) have no fiber: they must be short here too.
  std::vector<bool> kept(streamlines, false);
  for (const Fiber& f : tck.model.fibers)
  {
    kept[static_cast<std::size_t>(f.id)] = true; // readTck: id = streamline position < streamlines
  }
  for (std::size_t s = 0; s < streamlines; ++s)
  {
    if (!kept[s] && tsf.values[s].size() >= 2)
    {
      std::ostringstream msg;
      msg << "streamline " << s << " has " << tsf.values[s].size()
          << " values but fewer than 2 points in " << tckPath;
      return readFailure(mrtrixErrorAt(tsfPath, "byte", tsf.firstValueOffsets[s], msg.str()));
    }
  }
  for (Fiber& f : tck.model.fibers)
  {
    const std::size_t s = static_cast<std::size_t>(f.id);
    const std::vector<double>& values = tsf.values[s];
    if (values.size() != f.points.size())
    {
      std::ostringstream msg;
      msg << "streamline " << s << " has " << values.size() << " values but " << f.points.size()
          << " points in " << tckPath;
      return readFailure(mrtrixErrorAt(tsfPath, "byte", tsf.firstValueOffsets[s], msg.str()));
    }
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      if (!std::isfinite(values[i]) || values[i] <= 0.0)
      {
        std::ostringstream msg;
        msg << "radius " << values[i] << " of streamline " << s << " point " << i
            << " must be finite and > 0";
        return readFailure(mrtrixErrorAt(tsfPath, "byte", tsf.byteOffset(s, i), msg.str()));
      }
    }
    f.radii = values;
  }
  return tck;
}

FiberReadResult readTckWithRadii(std::istream& in, const std::string& path, double defaultRadius)
{
  std::string timestamp;
  FiberReadResult tck = readTck(in, path, defaultRadius, &timestamp);
  if (!tck.ok())
  {
    return tck;
  }
  const std::string tsfPath = tckRadiusPath(path);
  struct stat info;
  if (::stat(tsfPath.c_str(), &info) != 0 && errno == ENOENT)
  {
    return tck; // no radius file: defaultRadius everywhere, as for any .tck
  }
  const std::string special = checkRegularFile(tsfPath); // a FIFO would block the read forever
  if (!special.empty())
  {
    return readFailure("cannot read the radii of " + path + ": " + special);
  }
  std::ifstream tsfIn(tsfPath, std::ios::binary);
  if (!tsfIn)
  {
    return readFailure(
      "cannot open " + tsfPath + " (radii of " + path + "): " + std::strerror(errno));
  }
  return applyRadii(std::move(tck), timestamp, path, readTsf(tsfIn, tsfPath), tsfPath);
}

std::string writeTckWithRadii(const std::string& path, const FiberModel& model)
{
  const std::string tsfPath = tckRadiusPath(path);
  std::vector<std::vector<double>> radii;
  if (validateModel(model).empty()) // else writeTck below reports the problem
  {
    radii.reserve(model.fibers.size());
    for (std::size_t fi = 0; fi < model.fibers.size(); ++fi)
    {
      const Fiber& f = model.fibers[fi];
      for (std::size_t i = 0; i < f.radii.size(); ++i)
      {
        const float stored = static_cast<float>(f.radii[i]);
        if (!std::isfinite(stored) || stored <= 0.0f)
        {
          std::ostringstream msg;
          msg << tsfPath << ": cannot write .tsf: fiber " << fi << " (fiber_id " << f.id
              << ") point " << i << " has radius " << f.radii[i] << ", which float32 stores as "
              << stored;
          return msg.str();
        }
      }
      radii.push_back(f.radii);
    }
  }
  // One pair: both files are written and synced before either replaces its old version, so a
  // failure (a full disk) leaves the old pair, which still reads (AtomicFile.h).
  return writeFilesAtomically({
    AtomicPart{ path,
      [&](std::ostream& out)
      {
        const std::string error = writeTck(out, model);
        return error.empty() ? error : path + ": " + error;
      } },
    AtomicPart{ tsfPath,
      [&](std::ostream& out)
      {
        const std::string error = writeTsf(out, radii, tckTimestamp(model));
        return error.empty() ? error : tsfPath + ": " + error;
      } },
  });
}

} // namespace

FiberFileFormat fiberFileFormatFromPath(const std::string& path)
{
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return FiberFileFormat::Unknown;
  }
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
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
  if (ext == "csv")
  {
    return FiberFileFormat::Caterpillar;
  }
  if (ext == "txt")
  {
    return FiberFileFormat::Cactus;
  }
  return FiberFileFormat::Unknown;
}

std::string tckRadiusPath(const std::string& tckPath)
{
  const std::size_t dot = tckPath.find_last_of('.');
  const std::size_t slash = tckPath.find_last_of('/');
  const bool hasExtension = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return (hasExtension ? tckPath.substr(0, dot) : tckPath) + ".radius.tsf";
}

bool canReadFiberFile(const std::string& path)
{
  const FiberFileFormat format = fiberFileFormatFromPath(path);
  if (format == FiberFileFormat::Unknown)
  {
    return false;
  }
  if (!checkRegularFile(path).empty())
  {
    return false; // never open a FIFO or device (it could block or never end)
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    return false;
  }
  switch (format)
  {
    case FiberFileFormat::FastPliDat:
      return looksLikeFastPliDat(in);
    case FiberFileFormat::Tck:
      return looksLikeTck(in);
    case FiberFileFormat::Trk:
      return looksLikeTrk(in);
    case FiberFileFormat::Caterpillar:
      return looksLikeCaterpillarCsv(in);
    case FiberFileFormat::Cactus:
      return looksLikeCactusStrands(in);
    case FiberFileFormat::Unknown:
      break;
  }
  return false;
}

FiberReadResult readFiberFile(const std::string& path, double defaultRadius)
{
  const FiberFileFormat format = fiberFileFormatFromPath(path);
  if (format == FiberFileFormat::Unknown)
  {
    return readFailure(
      path + ": unknown fiber file extension (expected .dat, .tck, .trk, .csv or .txt)");
  }
  const std::string special = checkRegularFile(path); // a FIFO would block the read forever
  if (!special.empty())
  {
    return readFailure("cannot read " + special);
  }
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    return readFailure("cannot open " + path + ": " + std::strerror(errno));
  }
  switch (format)
  {
    case FiberFileFormat::FastPliDat:
      return readFastPliDat(in, path);
    case FiberFileFormat::Tck:
      return readTckWithRadii(in, path, defaultRadius);
    case FiberFileFormat::Trk:
      return readTrk(in, path, defaultRadius);
    case FiberFileFormat::Caterpillar:
      return readCaterpillarCsv(in, path);
    case FiberFileFormat::Cactus:
    {
      struct stat info;
      if (::stat(path.c_str(), &info) != 0)
      {
        return readFailure("cannot stat " + path + ": " + std::strerror(errno));
      }
      return readCactusStrands(in, path, static_cast<std::uintmax_t>(info.st_size)); // boxSize kept
    }
    case FiberFileFormat::Unknown:
      break;
  }
  return {};
}

double cactusBoxSize(const FiberFileExtras& extras)
{
  if (extras.cell.enabled())
  {
    const Vec3 e = extras.cell.edge();
    return std::max({ e.x, e.y, e.z });
  }
  return extras.boxSize;
}

std::string writeFiberFile(
  const std::string& path, const FiberModel& model, const FiberFileExtras* extras)
{
  const FiberFileFormat format = fiberFileFormatFromPath(path);
  if (format == FiberFileFormat::Tck)
  {
    return writeTckWithRadii(path, model);
  }
  const FiberFileExtras none;
  const FiberFileExtras& more = extras != nullptr ? *extras : none;
  if (format == FiberFileFormat::Caterpillar)
  {
    return writeFileAtomically(path,
      [&](std::ostream& out)
      {
        const std::string error = writeCaterpillarCsv(out, model, more.sphereTolerance);
        return error.empty() ? error : path + ": " + error;
      });
  }
  if (format == FiberFileFormat::Cactus)
  {
    const double box = cactusBoxSize(more);
    return writeFileAtomically(path,
      [&](std::ostream& out)
      {
        const std::string error = writeCactusStrands(out, model, box);
        return error.empty() ? error : path + ": " + error;
      });
  }
  if (format != FiberFileFormat::FastPliDat)
  {
    return path +
      ": cannot write this extension (FiberWriter writes .dat, .tck, .csv and .txt here)";
  }
  return writeFileAtomically(path,
    [&](std::ostream& out)
    {
      const std::string error = writeFastPliDat(out, model);
      return error.empty() ? error : path + ": " + error;
    });
}

} // namespace fiberpli
