/// MemoryBudget: how many bytes one Core call may allocate, derived at run time from the machine
/// instead of fixed numbers. The budget is half of the smallest of: physical memory, the cgroup
/// limit (containers, batch jobs) and the address-space / data rlimits (`ulimit -v`), so a guard
/// trips long before the process is killed. FIBERPLI_MEMORY_LIMIT (bytes, or with a K/M/G suffix)
/// overrides it, for tests and for users who share a node.
#pragma once

#include <cstdint>
#include <string>

namespace fiberpli
{

/// The smallest of physical memory, the cgroup memory limit and RLIMIT_AS / RLIMIT_DATA, in bytes.
std::uint64_t usableMemoryBytes();

/// Bytes one allocation-heavy call may plan for: FIBERPLI_MEMORY_LIMIT if set and valid, else half
/// of usableMemoryBytes().
double memoryBudgetBytes();

/// "1.5 GiB", "320 MiB", "12 KiB", "17 B": for error messages.
std::string formatBytes(double bytes);

/// Empty if `bytes` fits the budget, else a message "<what> needs X, more than the memory budget Y
/// (half of this machine's usable memory; FIBERPLI_MEMORY_LIMIT overrides it)".
std::string checkMemoryBudget(double bytes, const std::string& what);

} // namespace fiberpli
