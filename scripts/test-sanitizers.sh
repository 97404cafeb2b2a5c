#!/usr/bin/env bash
# Builds the libraries and every unit/CLI test with AddressSanitizer + UndefinedBehaviorSanitizer
# (gcc, -O1, OCTRACE_SANITIZE=ON) into build-asan/ and runs them. Any sanitizer report fails:
# the runtime options below make the first report abort the test. Heavy tests run scaled down
# (OCTRACE_TEST_SCALE). Usage: scripts/test-sanitizers.sh [ctest args...]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build-asan"

# Exported for the build too: gtest_discover_tests runs each test binary once at build time.
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1:detect_stack_use_after_return=1:strict_string_checks=1:check_initialization_order=1:strict_init_order=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# Leaks inside third-party libraries only (GDAL, VTK, ...); see the file's comments.
export LSAN_OPTIONS="suppressions=$ROOT/tests/sanitizers/lsan.supp:print_suppressions=0"
# The million-ray traversal tests run a fifth of their rays (still hundreds of thousands).
export OCTRACE_TEST_SCALE="${OCTRACE_TEST_SCALE:-0.2}"

cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DOCTRACE_SANITIZE=ON -DOCTRACE_BUILD_BENCH=OFF -DOCTRACE_BUILD_STUDIO=OFF >/dev/null
ninja -C "$BUILD"
cd "$BUILD"
ctest --output-on-failure -j 2 --timeout 1500 "$@"
