/// DatFormat: the fastPLI text fiber format `.dat` (docs/api.md §4; the layout of
/// fastPLI's own reader/writer and of shared/bench/fiber_metrics.py read_dat/write_dat):
///   - one point per line: `x y z r` (4 numbers separated by spaces or tabs, µm);
///   - one blank line ends a fiber, a second consecutive blank line ends a bundle;
///   - lines whose first non-blank character is '#' are comments and are skipped entirely (they
///     neither end a fiber nor reset a run of blank lines, as in fiber_metrics.py);
///   - blank lines at the start, and runs of more than two blank lines, carry no meaning.
/// Bundle ids are counted 0, 1, 2, … in file order; fiber ids are the 0-based position of the
/// fiber in the file.
#pragma once

#include "IO/FiberReadResult.h"
#include "Model/FiberModel.h"

#include <istream>
#include <ostream>
#include <string>

namespace fiberpli
{

/// Reads a `.dat` stream straight into a FiberModel (no intermediate copy), line by line.
/// fileName is only used in messages. Errors (with line number): a point line that is not exactly
/// 4 numbers, text in a number field, NaN/Inf, radius <= 0, a line longer than 4096 characters, a
/// read error. Fibers of one point are dropped and counted (FiberReadResult::droppedFibers).
FiberReadResult readFastPliDat(std::istream& in, const std::string& fileName);

/// Writes the model in the layout above, fibers grouped by bundle in ascending bundle id (model
/// order inside a bundle), every number in the shortest form that reads back bit-exactly
/// (std::to_chars). Bundle ids are not stored as such: reading renumbers them 0, 1, … and fiber ids
/// become file positions. Returns "" on success, else why nothing valid was written (the model
/// fails validateModel, or the stream failed); use AtomicFile to protect the target file.
std::string writeFastPliDat(std::ostream& out, const FiberModel& model);

/// Content sniffing for CanReadFile (other ParaView readers also claim `.dat`, e.g. Tecplot's
/// "TITLE = ..." files): looks at the first 20 non-blank, non-comment lines within the first 64
/// KiB; true when more than three quarters of them hold exactly 4 finite numbers with a positive
/// radius and none starts with a Tecplot keyword (TITLE, VARIABLES, ZONE, …) or holds a NUL byte —
/// so a fastPLI file with one bad line still reaches our reader and its line-numbered error. The
/// stream position is restored (the stream must be seekable).
bool looksLikeFastPliDat(std::istream& in);

} // namespace fiberpli
