/// AtomicFile: replace a file so that a failed write never destroys what was there (docs/api.md
/// §4: writers write to a temporary file beside the target and rename it).
/// Steps: create "<target>.tmp-<16 random hex digits>" beside the target (same directory, hence
/// same file system, so rename(2) is atomic) with O_EXCL | O_NOFOLLOW, so nothing planted there is
/// followed or overwritten; let the caller write into it, flush, fsync, close (checked), rename
/// over the target, fsync the directory. On any failure the temporary file is removed and an existing
/// target is left untouched. POSIX only (the plugin targets Linux).
#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace fiberpli
{

/// Writes the content produced by writeContent to path atomically. writeContent returns "" on
/// success or an error message (which aborts the write and is returned unchanged). Returns "" on
/// success, else a message naming the path and the system error. A new file gets mode 0666 minus
/// the umask; a replaced file keeps its permission bits.
std::string writeFileAtomically(const std::string& path,
  const std::function<std::string(std::ostream& out)>& writeContent);

} // namespace fiberpli
