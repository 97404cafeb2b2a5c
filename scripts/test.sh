#!/usr/bin/env bash
# Installs what is needed, builds everything, and runs every test (CTest); then the same tests
# built with AddressSanitizer + UndefinedBehaviorSanitizer (build-asan), then each fuzz target
# for a short smoke run (build-fuzz; OCTRACE_FUZZ_SECONDS, default 15 s per target). Exits
# non-zero when any test fails, any sanitizer reports or a fuzz target crashes. Tests that need
# ../shared/data say so and are skipped without it.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$ROOT/scripts/setup.sh" --fuzz
bash "$ROOT/scripts/build.sh"
(cd "$ROOT/build" && ctest --output-on-failure -j 2 --timeout 1500)
echo "test: sanitizer build (ASan + UBSan)"
bash "$ROOT/scripts/test-sanitizers.sh"
echo "test: fuzz smoke run"
bash "$ROOT/tests/fuzz/run.sh" "${OCTRACE_FUZZ_SECONDS:-15}"
