#pragma once
/// @file Memory.h
/// Memory budgets: how much memory a job may allocate, so that one that would need more is
/// refused with a message instead of being killed by the kernel (or swapping for hours).
/// Readers check the samples they are about to allocate, buildShellOctree its estimate and
/// then what it really allocates (see OctreeBuilder.h); the CLI's `--max-memory` sets it.
#include <cstdint>
#include <string>

namespace octrace {

/// The default budget is this share of physicalMemoryBytes().
inline constexpr int kDefaultMemoryBudgetPercent = 50;

/// Physical memory in bytes (sysconf, else /proc/meminfo's MemTotal), or the memory limit
/// of this process's cgroup when that is lower (containers: cgroup v2 `memory.max`, v1
/// `memory.limit_in_bytes`); 0 when none of them can be read. Thread-safe.
std::uint64_t physicalMemoryBytes();

/// kDefaultMemoryBudgetPercent of physicalMemoryBytes(), or 4 GiB when that is unknown.
std::uint64_t defaultMemoryBudget();

/// Bytes in binary units for messages: "512 bytes", "1.5 KiB", "38.2 MiB", "11.6 GiB".
std::string formatBytes(std::uint64_t bytes);

/// a * b, or UINT64_MAX when the product does not fit (sizes announced by a file may be absurd).
std::uint64_t saturatingMultiply(std::uint64_t a, std::uint64_t b);

/// Throws LimitError "<what> needs about <bytes>, more than the memory budget of <budget>
/// (--max-memory)" when `budget` is not 0 (no limit) and `bytes` exceeds it. `what` says
/// what would be allocated, with the file's path first when there is one.
void checkMemoryBudget(const std::string& what, std::uint64_t bytes, std::uint64_t budget);

}  // namespace octrace
