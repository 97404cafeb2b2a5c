#!/usr/bin/env bash
# Builds the libraries and every unit/CLI test with AddressSanitizer + UndefinedBehaviorSanitizer
# (gcc, -O1, OCTRACE_SANITIZE=ON) into build-asan/ and runs them. Any sanitizer report fails:
# the runtime options below make the first report abort the test. Heavy tests run scaled down
# (OCTRACE_TEST_SCALE). Usage: scripts/test-sanitizers.sh [ctest args...]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="$ROOT/build-asan"

# Exported for the build too: gtest_discover_tests runs each test binary once at build time.
# Stack use after return is checked only with OCTRACE_ASAN_STACK=1 (the long runs of
# docs/dev/reliability.md): its fake stack frames double the suite's time (measured on
# Lod.* and Csg.*: 14.4 s -> 7.8 s and 25.1 s -> 13.1 s of CPU without them).
STACK_UAR="${OCTRACE_ASAN_STACK:-0}"
export ASAN_OPTIONS="halt_on_error=1:abort_on_error=0:detect_leaks=1:detect_stack_use_after_return=$STACK_UAR:strict_string_checks=1:check_initialization_order=1:strict_init_order=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
# Leaks inside third-party libraries only (GDAL, VTK, ...); see the file's comments.
export LSAN_OPTIONS="suppressions=$ROOT/tests/sanitizers/lsan.supp:print_suppressions=0"
# The million-ray traversal tests run a fifth of their rays (still hundreds of thousands).
export OCTRACE_TEST_SCALE="${OCTRACE_TEST_SCALE:-0.2}"

LAUNCHER=()
if command -v ccache >/dev/null 2>&1; then LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache); fi
export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-pch_defines,time_macros}"
cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DOCTRACE_SANITIZE=ON -DOCTRACE_BUILD_BENCH=OFF -DOCTRACE_BUILD_STUDIO=OFF \
  "${LAUNCHER[@]}" >/dev/null
ninja -C "$BUILD"
cd "$BUILD"
ctest --output-on-failure -j 2 --timeout 1500 "$@"
