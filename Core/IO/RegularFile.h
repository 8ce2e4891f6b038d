/// RegularFile: files FiberPLI reads must be regular files. Opening a FIFO (named pipe) for
/// reading blocks until something writes into it — forever for a pipeline whose FileName or
/// CheckpointFile names one — and a character device can deliver endless data. So every reader
/// asks this first and refuses anything else with a message naming the path and what it is.
#pragma once

#include <string>

namespace fiberpli
{

/// "" when `path` is a regular file (symbolic links followed) or does not exist (opening it then
/// reports that); else "<path> is a FIFO (named pipe), not a regular file" (or a directory, a
/// socket, a character or block device).
std::string checkRegularFile(const std::string& path);

} // namespace fiberpli
