#!/usr/bin/env bash
# Installs what is needed, builds everything, and runs every test (CTest); then the same tests
# built with AddressSanitizer + UndefinedBehaviorSanitizer (build-asan), then each fuzz target
# for a short smoke run (build-fuzz; OCTRACE_FUZZ_SECONDS, default 15 s per target, from the
# fixed libFuzzer seed OCTRACE_FUZZ_SEED, default 1, so that a run on a fresh clone tries the
# inputs CI will try; the long runs of docs/dev/fuzzing.md explore with random seeds). Exits
# non-zero when any test fails, any sanitizer reports or a fuzz target crashes. Tests that need
# ../shared/data say so and are skipped without it.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$ROOT/scripts/setup.sh" --fuzz
OCTRACE_PYTHON=1 bash "$ROOT/scripts/build.sh"
LOG="$(mktemp)"
trap 'rm -f "$LOG"' EXIT
(cd "$ROOT/build" && ctest --output-on-failure -j 2 --timeout 1500) | tee "$LOG"
echo "test: sanitizer build (ASan + UBSan)"
bash "$ROOT/scripts/test-sanitizers.sh" | tee -a "$LOG"
echo "test: fuzz smoke run"
OCTRACE_FUZZ_SEED="${OCTRACE_FUZZ_SEED:-1}" bash "$ROOT/tests/fuzz/run.sh" "${OCTRACE_FUZZ_SECONDS:-15}" | tee -a "$LOG"
# One closing line over the three parts (each part already stopped the run if it failed).
total=$(grep -Eo 'tests failed out of [0-9]+' "$LOG" | awk '{s += $5} END {print s + 0}')
fuzz=$(grep -Eo '^fuzz: [0-9]+ passed' "$LOG" | awk '{s += $2} END {print s + 0}')
echo "all: $((total + fuzz)) passed, 0 failed"
