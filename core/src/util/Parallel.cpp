#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstdio>
#include <thread>

namespace octrace {

int hardwareThreads() {
    unsigned n = std::thread::hardware_concurrency();
    return n == 0 ? 1 : int(n);
}

void parallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& body) {
    if (count == 0) return;
    if (threads == 1 || count == 1) {
        for (std::size_t i = 0; i < count; ++i) body(i);
        return;
    }
    int n = threads <= 0 ? hardwareThreads() : threads;
    // More threads than cores is allowed (results never depend on it); lift TBB's default
    // limit for the duration of the call instead of letting it warn and ignore the request.
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(std::max(n, hardwareThreads())));
    tbb::task_arena arena(n);
    arena.execute([&] {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, count, 1), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
        });
    });
}

std::size_t peakRssBytes() {
    std::FILE* f = std::fopen("/proc/self/status", "r");
    if (!f) return 0;
    char line[256];
    std::size_t kb = 0;
    while (std::fgets(line, sizeof line, f)) {
        if (std::sscanf(line, "VmHWM: %zu kB", &kb) == 1) break;
    }
    std::fclose(f);
    return kb * 1024;
}

}  // namespace octrace
