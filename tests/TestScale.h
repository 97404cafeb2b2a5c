#pragma once
// How much work the heavy tests do. OCTRACE_TEST_SCALE (a factor in (0, 1], default 1) scales
// their ray counts down: scripts/test-sanitizers.sh sets 0.2, where AddressSanitizer makes
// every ray several times slower. Scaled tests still check hundreds of thousands of rays.
#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace octrace::testutil {

inline double testScale() {
    const char* s = std::getenv("OCTRACE_TEST_SCALE");
    if (!s || !*s) return 1.0;
    char* end = nullptr;
    double v = std::strtod(s, &end);
    return (*end == '\0' && v > 0.0 && v <= 1.0) ? v : 1.0;
}

/// `n` times the test scale, at least `minimum` (and never more than `n`).
inline long scaledCount(long n, long minimum = 1000) {
    return std::min(n, std::max(minimum, std::lround(double(n) * testScale())));
}

}  // namespace octrace::testutil
