/// TsfFormat: MRtrix track scalar files `.tsf` (docs/api.md §4; MRtrix3 docs,
/// "Track Scalar File format"): one value per point of the streamlines of a .tck. Layout as .tck
/// (MrtrixHeader.h) with the first line "mrtrix track scalars" and one value instead of an x y z
/// triplet per point: a NaN after each streamline, an Inf at the end. The header's `timestamp`
/// must equal the one of the .tck the values belong to. FiberFile uses a "<name>.radius.tsf"
/// beside "<name>.tck" for the fiber radii.
#pragma once

#include "Util/Status.h"

#include <cstddef>
#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

namespace fiberpli
{

/// What readTsf returns. On failure only error is set: empty when the file was read; else
/// "<file> line N: ..." or "<file> byte N: ...".
struct TsfReadResult : Status
{
  /// Values of every streamline in file order, empty streamlines included (unlike readTck, which
  /// drops streamlines of fewer than 2 points but keeps their position as the fiber id).
  std::vector<std::vector<double>> values;
  /// Byte offset of the first value of each streamline (of its NaN when it is empty).
  std::vector<std::uint64_t> firstValueOffsets;
  /// Bytes per stored value (4 or 8), for byteOffset.
  std::size_t valueSize = 4;
  /// The header's `timestamp` as written; empty when absent.
  std::string timestamp;
  /// Byte offset in the file of value j of streamline i, for messages about a value.
  std::uint64_t byteOffset(std::size_t i, std::size_t j) const
  {
    return firstValueOffsets[i] + static_cast<std::uint64_t>(j) * valueSize;
  }
};

/// Reads a .tsf stream (seekable); fileName is only used in messages. Errors name the header line
/// or byte offset: missing "mrtrix track scalars" magic, unknown datatype, missing or bad `file:`
/// offset, `count` that disagrees with the data or that the file is too short to hold (checked
/// before allocating), data without the Inf end marker (truncated). Values are not range-checked
/// here: what is valid depends on the scalar (FiberFile checks radii).
TsfReadResult readTsf(std::istream& in, const std::string& fileName);

/// Writes values (one vector per streamline, in .tck order) as Float32LE .tsf exactly like this
/// (tested byte by byte against a Python-made sample):
///   "mrtrix track scalars\ndatatype: Float32LE\ntimestamp: <timestamp>\ncount: <N>\n
///   file: . <offset>\nEND\n" (<offset> = length of this header; no timestamp line when timestamp
///   is empty), then each streamline's values (float32 LE), a NaN after each and a final Inf.
/// Values are rounded to float32. Returns "" on success, else the reason: a value that is not
/// finite or beyond the float32 range (it would corrupt the NaN/Inf structure; names streamline
/// and point), a timestamp with a line break, stream failure.
std::string writeTsf(
  std::ostream& out, const std::vector<std::vector<double>>& values, const std::string& timestamp);

} // namespace fiberpli
