/// FiberFile: path-level entry points of Core/IO for the VTK FiberReader/FiberWriter (docs/api.md
/// §4): pick the format by extension, open the file, call the stream reader or
/// writer, and write through AtomicFile. HDF5 (.h5) is not handled here (the Readers module does
/// it with VTK's HDF5).
#pragma once

#include "IO/FiberReadResult.h"
#include "Model/FiberModel.h"

#include <string>
#include <vector>

namespace fiberpli
{

enum class FiberFileFormat
{
  Unknown,
  FastPliDat,  ///< .dat
  Tck,         ///< .tck
  Trk,         ///< .trk
  Caterpillar, ///< .csv with the CATERPillar header (CaterpillarFormat.h)
  Cactus       ///< .txt holding a CACTUS strand list (CactusFormat.h)
};

/// Format from the extension of path (case-insensitive).
FiberFileFormat fiberFileFormatFromPath(const std::string& path);

/// True when the file at path has the content of the format its extension names (for
/// CanReadFile; other readers claim .dat, .csv and .txt too: a .csv must start with the CATERPillar
/// header, a .txt must open like a CACTUS strand list). False for unknown extensions or unreadable
/// files.
bool canReadFiberFile(const std::string& path);

/// The track scalar file that holds the radii of the .tck at tckPath: the extension replaced by
/// ".radius.tsf" ("dir/x.tck" -> "dir/x.radius.tsf"; TsfFormat.h).
std::string tckRadiusPath(const std::string& tckPath);

/// Reads .dat, .tck, .trk, .csv (CATERPillar) or .txt (CACTUS). defaultRadius (µm, > 0) is the
/// radius of every point of formats without radii (.trk, and .tck without a radius file). Errors
/// name the path; an unknown extension or unopenable file is an error too. .tck: when
/// tckRadiusPath(path) exists, its values are the radii. It must match the .tck (else an error
/// naming the .tsf): readable .tsf, the same number of streamlines, the same number of points in
/// every streamline, equal `timestamp` values when both files have one, and every value finite and
/// > 0 (the message gives the byte offset in the .tsf). When it does not exist, every point gets
/// defaultRadius as before.
FiberReadResult readFiberFile(const std::string& path, double defaultRadius);

/// What some formats store beside the model (the axon radii inside the outer radii travel in
/// Fiber::innerRadii; .csv writes them): the periodic cell and the box size of a .txt strand list.
/// The box size written is the cell's largest edge when there is a cell, else boxSize (a box size
/// read from a strand list), else -1, as CACTUS writes when it has none.
struct FiberFileExtras
{
  PeriodicCell cell;
  double boxSize = -1.0;         ///< .txt without a cell: µm, finite; -1 = none
  double sphereTolerance = 0.05; ///< .csv: µm, see CaterpillarFormat.h
};

/// The box size a .txt strand list gets for these extras (see FiberFileExtras).
double cactusBoxSize(const FiberFileExtras& extras);

/// Writes .dat, .tck, .csv (CATERPillar) or .txt (CACTUS) (by extension) atomically: on failure an
/// existing file is unchanged.
/// .tck also writes the radii to tckRadiusPath(path) (Float32LE .tsf, same timestamp as the .tck,
/// see tckTimestamp), atomically too. Radii that float32 cannot hold (> 3.4e38, or rounding to 0)
/// are refused before either file is touched. The two files are replaced as a pair
/// (writeFilesAtomically): when either cannot be written (a full disk, an I/O error), neither
/// old file is changed, so the old pair still reads.
/// Returns "" on success, else a message naming the path.
std::string writeFiberFile(
  const std::string& path, const FiberModel& model, const FiberFileExtras* extras = nullptr);

} // namespace fiberpli
