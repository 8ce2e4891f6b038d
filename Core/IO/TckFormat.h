/// TckFormat: MRtrix streamlines `.tck` (docs/api.md §4; MRtrix3 docs, "Tracks file
/// format"). Layout: a text header whose first line is "mrtrix tracks", then "key: value" lines,
/// then "END"; the keys used here are `datatype` (Float32LE, Float32BE, Float64LE or Float64BE),
/// `file: . <offset>` (binary data of this file starts at byte <offset>) and `count` (number of
/// streamlines). The data is x y z triplets; a NaN triplet ends a streamline, an Inf triplet ends
/// the data. Coordinates are used as stored (MRtrix writes scanner mm; no unit conversion here).
/// .tck holds no radii: readTck gives every point defaultRadius and writeTck drops the radii (and
/// bundle ids). Radii travel in a companion track scalar file "<name>.radius.tsf" (TsfFormat.h),
/// which readFiberFile/writeFiberFile (FiberFile.h) read and write beside the .tck; the `timestamp`
/// header value pairs the two files. The header parsing and data layout shared with .tsf live in
/// MrtrixHeader.h and MrtrixData.h.
#pragma once

#include "IO/FiberReadResult.h"
#include "Model/FiberModel.h"

#include <istream>
#include <ostream>
#include <string>

namespace fiberpli
{

/// Reads a .tck stream; fileName is only used in messages. Fiber ids are streamline positions in
/// the file, bundle 0 for all; streamlines of fewer than 2 points are dropped and counted. Errors
/// name the byte offset (data) or line (header): missing "mrtrix tracks" magic, unknown datatype,
/// missing or bad `file:` offset, `count` that disagrees with the data or that the file is too
/// short to hold (checked before allocating), a triplet mixing finite and NaN/Inf values, data
/// without the Inf end marker (truncated), defaultRadius not finite and > 0. When timestamp is
/// given it receives the header's `timestamp` value ("" when absent), to match a .tsf against.
FiberReadResult readTck(std::istream& in, const std::string& fileName, double defaultRadius,
  std::string* timestamp = nullptr);

/// The `timestamp` writeTck puts in the header: a deterministic digest (not a time) of the data
/// section, so writes stay reproducible and a .tsf written for other tracks is noticed. Definition
/// (checked against Python in the tests): FNV-1a 64 over the data section bytes exactly as
/// writeTck writes them (float32 LE points, NaN and Inf triplets), modulo 10^15, in decimal.
std::string tckTimestamp(const FiberModel& model);

/// Writes the model as Float32LE .tck exactly like this (tested byte by byte):
///   "mrtrix tracks\ndatatype: Float32LE\ntimestamp: <tckTimestamp(model)>\ncount: <N>\n
///   file: . <offset>\nEND\n", where <offset> is the length of this header, followed by each
///   fiber's points (3 × float32 LE), a NaN triplet after each fiber and a final Inf triplet.
/// Radii, fiber ids and bundle ids are NOT stored (the format has no place for them; writeFiberFile
/// writes the radii to the companion .tsf). Coordinates
/// are rounded to float32; a coordinate beyond the float32 range is an error. Returns "" on
/// success, else the reason (model fails validateModel, value out of float range, stream failed).
std::string writeTck(std::ostream& out, const FiberModel& model);

/// Content sniffing for CanReadFile: the stream starts with the line "mrtrix tracks". The stream
/// position is restored.
bool looksLikeTck(std::istream& in);

} // namespace fiberpli
