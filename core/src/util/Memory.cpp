#include "octrace/util/Memory.h"

#include "octrace/util/Error.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

namespace octrace {
namespace {

constexpr std::uint64_t kUnknown = 0;

// MemTotal of /proc/meminfo in bytes (the fallback when sysconf cannot tell).
std::uint64_t memTotal() {
    std::ifstream in("/proc/meminfo");
    std::string key;
    std::uint64_t kb = 0;
    while (in >> key) {
        if (key == "MemTotal:" && in >> kb) return saturatingMultiply(kb, 1024);
        in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    return kUnknown;
}

// The first number in a cgroup file ("max" or a missing file: no limit).
std::uint64_t cgroupLimit(const char* path) {
    std::ifstream in(path);
    unsigned long long v = 0;
    if (!(in >> v)) return kUnknown;
    return v;
}

}  // namespace

std::uint64_t saturatingMultiply(std::uint64_t a, std::uint64_t b) {
    constexpr std::uint64_t kMax = std::numeric_limits<std::uint64_t>::max();
    return b != 0 && a > kMax / b ? kMax : a * b;
}

std::uint64_t physicalMemoryBytes() {
    long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGESIZE);
    std::uint64_t physical = pages > 0 && pageSize > 0 ? saturatingMultiply(std::uint64_t(pages), std::uint64_t(pageSize))
                                                       : memTotal();
    // A container's limit is what the kernel enforces; v1 reports "no limit" as a huge number.
    for (const char* path : {"/sys/fs/cgroup/memory.max", "/sys/fs/cgroup/memory/memory.limit_in_bytes"}) {
        std::uint64_t limit = cgroupLimit(path);
        if (limit != kUnknown && (physical == kUnknown || limit < physical)) physical = limit;
    }
    return physical;
}

std::uint64_t defaultMemoryBudget() {
    std::uint64_t physical = physicalMemoryBytes();
    if (physical == kUnknown) return std::uint64_t(4) << 30;
    return physical / 100 * kDefaultMemoryBudgetPercent;
}

std::string formatBytes(std::uint64_t bytes) {
    if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
    const char* units[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    double v = double(bytes) / 1024.0;
    int u = 0;
    while (v >= 1024.0 && u < 5) {
        v /= 1024.0;
        ++u;
    }
    char buf[32];
    std::snprintf(buf, sizeof buf, v < 10.0 ? "%.2g %s" : v < 100.0 ? "%.3g %s" : "%.0f %s", v, units[u]);
    return buf;
}

void checkMemoryBudget(const std::string& what, std::uint64_t bytes, std::uint64_t budget) {
    if (budget == 0 || bytes <= budget) return;
    throw LimitError(what + " needs about " + formatBytes(bytes) + ", more than the memory budget of " + formatBytes(budget) +
                     " (`max_memory`)");
}

}  // namespace octrace
