/// AtomicFile: replace a file (or several together) so that a failed write never destroys what was
/// there (docs/api.md §4: writers write to a temporary file beside the target and rename it).
/// Steps: create "<target>.tmp-<16 random hex digits>" beside the target (same directory, hence
/// same file system, so rename(2) is atomic) with O_EXCL | O_NOFOLLOW, so nothing planted there is
/// followed or overwritten; let the caller write into it, flush, fsync, close (checked), rename
/// over the target, fsync the directory. On any failure the temporary file is removed and an
/// existing target is left untouched. POSIX only (the plugin targets Linux).
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace fiberpli
{

/// Writes the content produced by writeContent to path atomically. writeContent returns "" on
/// success or an error message (which aborts the write and is returned unchanged). Returns "" on
/// success, else a message naming the path and the system error. A new file gets mode 0666 minus
/// the umask; a replaced file keeps its permission bits.
std::string writeFileAtomically(
  const std::string& path, const std::function<std::string(std::ostream& out)>& writeContent);

/// One file of writeFilesAtomically: its path and what to write into it (as for
/// writeFileAtomically).
struct AtomicPart
{
  std::string path;
  std::function<std::string(std::ostream& out)> writeContent;
};

/// Replaces several files together or not at all (a .tck and its .radius.tsf): first every
/// temporary file is written, flushed, synced and closed; only when all are complete are they
/// renamed over their targets, in order. A failed write leaves every target untouched; should a
/// rename fail after others succeeded, the targets already replaced are put back from hard-linked
/// copies taken before the first rename (a target that did not exist is removed again). Returns
/// "" or the first error, naming its path; no temporary or backup file is left behind.
std::string writeFilesAtomically(const std::vector<AtomicPart>& parts);

} // namespace fiberpli
