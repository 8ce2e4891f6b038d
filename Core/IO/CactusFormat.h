/// CactusFormat: the strand list text file of the CACTUS generator (docs/diffusion-export.md §3;
/// the layout of CACTUS's own strand reader and writer, one value or point a line):
///   line 1: the box size (µm; one number, CACTUS writes -1 when it has none);
///   line 2: the number of strands N;
///   then N times: the strand's point count n, followed by n lines `x y z r` (µm).
/// Blank lines are allowed only after the last strand. Fiber ids are the strands' positions in
/// the file, every fiber is in bundle 0; strands of fewer than 2 points are dropped and counted.
#pragma once

#include "IO/FiberReadResult.h"
#include "Model/FiberModel.h"

#include <cstdint>
#include <istream>
#include <ostream>
#include <string>

namespace fiberpli
{

/// boxSize (FiberReadResult) holds line 1 of the file.
struct CactusReadResult : FiberReadResult
{
};

/// Reads a strand file of fileBytes bytes (the file's size: counts are checked against it before
/// anything is reserved, so a count of 10^10 in a 1 KB file is refused at once). Errors name the
/// file and line: a count that is no integer or needs more bytes than the file holds, a strand
/// whose points run past the end of the file (a count that lies), lines after the last strand, a
/// point line that is not 4 finite numbers, a radius <= 0.
CactusReadResult readCactusStrands(
  std::istream& in, const std::string& fileName, std::uintmax_t fileBytes);

/// Writes the model in the layout above with boxSize on line 1, numbers in the shortest form that
/// reads back bit-exactly. Returns "" on success, else the reason.
std::string writeCactusStrands(std::ostream& out, const FiberModel& model, double boxSize);

/// Content check for CanReadFile: line 1 one number, line 2 and 3 one non-negative integer each,
/// line 4 (when line 3 > 0) four numbers. Restores the stream position.
bool looksLikeCactusStrands(std::istream& in);

} // namespace fiberpli
