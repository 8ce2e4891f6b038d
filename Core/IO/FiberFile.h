/// FiberFile: path-level entry points of Core/IO for the VTK FiberReader/FiberWriter (api.md
/// "Readers and writers"): pick the format by extension, open the file, call the stream reader or
/// writer, and write through AtomicFile. HDF5 (.h5) is not handled here (the Readers module does
/// it with VTK's HDF5).
#pragma once

#include "IO/FiberReadResult.h"
#include "Model/FiberModel.h"

#include <string>

namespace fiberpli
{

enum class FiberFileFormat
{
  Unknown,
  FastPliDat, ///< .dat
  Tck,        ///< .tck
  Trk         ///< .trk
};

/// Format from the extension of path (case-insensitive).
FiberFileFormat fiberFileFormatFromPath(const std::string& path);

/// True when the file at path has the content of the format its extension names (for
/// CanReadFile; other readers claim .dat too). False for unknown extensions or unreadable files.
bool canReadFiberFile(const std::string& path);

/// Reads .dat, .tck or .trk. defaultRadius (µm, > 0) is the radius of every point of formats
/// without radii (.tck, .trk). Errors name the path; an unknown extension or unopenable file is an
/// error too.
FiberReadResult readFiberFile(const std::string& path, double defaultRadius);

/// Writes .dat or .tck (by extension) atomically: on failure an existing file is unchanged.
/// Returns "" on success, else a message naming the path.
std::string writeFiberFile(const std::string& path, const FiberModel& model);

} // namespace fiberpli
