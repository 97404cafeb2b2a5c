#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, build-fuzz/) and runs each for SECONDS
# (default 20) on its committed seeds (tests/fuzz/corpus/TARGET) plus the inputs it found
# before (build-fuzz/corpus/TARGET, not committed). Exits non-zero when a target crashes, hangs
# (over 10 s on one input), leaks or runs out of memory (the others still run); the reproducer
# is in build-fuzz/findings/TARGET/. Needs clang (scripts/setup.sh --fuzz). See docs/dev/fuzzing.md.
# Usage: tests/fuzz/run.sh [SECONDS] [TARGET...]
# With OCTRACE_FUZZ_JSON=FILE each target's final counts are also appended to FILE, one JSON
# object per line (the raw record of a long run, docs/dev/fuzzing.md). With OCTRACE_FUZZ_SEED=N
# libFuzzer starts from that seed (-seed=N) instead of a random one, so a run from the same
# corpus tries the same inputs in the same order (CI sets it: scripts/test.sh).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
BUILD="$ROOT/build-fuzz"
SECONDS_PER_TARGET="${1:-20}"
shift || true
TARGETS=("$@")
if [ ${#TARGETS[@]} -eq 0 ]; then
  TARGETS=(fuzz_nrrd fuzz_netcdf_cf fuzz_netcdf_classic_header fuzz_cli_options fuzz_dicom fuzz_octree_file fuzz_molecule fuzz_cityjson fuzz_citygml fuzz_scene fuzz_footprints fuzz_session fuzz_metaimage fuzz_zarr_metadata fuzz_curvilinear_grid fuzz_formula_terms)
fi
if ! command -v clang++ >/dev/null; then
  echo "fuzz: clang++ not found; run scripts/setup.sh --fuzz" >&2
  exit 1
fi

LAUNCHER=()
if command -v ccache >/dev/null 2>&1; then LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache); fi
cmake -S "$ROOT" -B "$BUILD" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DOCTRACE_FUZZ=ON -DOCTRACE_BUILD_TESTS=OFF "${LAUNCHER[@]}" >/dev/null
ninja -C "$BUILD" "${TARGETS[@]}"

# Leaks inside third-party libraries only (the sanitizer build's list, see the file).
export LSAN_OPTIONS="suppressions=$ROOT/tests/sanitizers/lsan.supp:print_suppressions=0"
export ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"

# record TARGET LOG RESULT: one JSON line of libFuzzer's final counts into $OCTRACE_FUZZ_JSON.
record() {
  [ -n "${OCTRACE_FUZZ_JSON:-}" ] || return 0
  # The last value: a crash handler in a child process (the HDF5 guard's) prints stats too.
  stat() { grep -Eo "^stat::$1: *[0-9]+" "$2" | tail -1 | grep -Eo '[0-9]+$' || echo 0; }
  printf '{"date": "%s", "target": "%s", "seconds": %s, "result": "%s", "executions": %s, "exec_per_sec": %s, "new_units": %s, "peak_rss_mb": %s, "corpus_found": %s, "corpus_bytes": %s, "seeds": %s, "commit": "%s"}\n' \
    "$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$1" "$SECONDS_PER_TARGET" "$3" \
    "$(stat number_of_executed_units "$2")" "$(stat average_exec_per_sec "$2")" "$(stat new_units_added "$2")" \
    "$(stat peak_rss_mb "$2")" "$(ls "$BUILD/corpus/$1" | wc -l)" "$(du -sb "$BUILD/corpus/$1" | cut -f1)" \
    "$(ls "$ROOT/tests/fuzz/corpus/$1" | wc -l)" "$COMMIT" \
    >>"$OCTRACE_FUZZ_JSON"
}

# The commit the targets were built from (the tree may change while a long run goes on).
COMMIT="$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
passed=0
failed=0
for t in "${TARGETS[@]}"; do
  work="$BUILD/corpus/$t"
  findings="$BUILD/findings/$t"
  mkdir -p "$work" "$findings"
  args=(-max_total_time="$SECONDS_PER_TARGET" -timeout=10 -rss_limit_mb=2048 -max_len=16384
        -print_final_stats=1 -artifact_prefix="$findings/")
  [ -f "$ROOT/tests/fuzz/$t.dict" ] && args+=(-dict="$ROOT/tests/fuzz/$t.dict")
  [ -n "${OCTRACE_FUZZ_SEED:-}" ] && args+=(-seed="$OCTRACE_FUZZ_SEED")
  echo "fuzz: $t for ${SECONDS_PER_TARGET} s${OCTRACE_FUZZ_SEED:+, seed $OCTRACE_FUZZ_SEED}"
  log="$BUILD/$t.log"
  if "$BUILD/tests/fuzz/$t" "${args[@]}" "$work" "$ROOT/tests/fuzz/corpus/$t" >"$log" 2>&1; then
    grep -E "^stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb)" "$log" |
      sed "s/^/fuzz: $t: /"
    echo "fuzz: $t: corpus $(ls "$work" | wc -l) inputs found + $(ls "$ROOT/tests/fuzz/corpus/$t" | wc -l) seeds"
    passed=$((passed + 1))
    record "$t" "$log" passed
  else
    record "$t" "$log" failed
    echo "fuzz: $t FAILED; its log ($log) ends:" >&2
    tail -60 "$log" >&2
    echo "fuzz: reproducer(s) in $findings: $(ls "$findings")" >&2
    failed=$((failed + 1))
  fi
done
echo "fuzz: $passed passed, $failed failed"
[ "$failed" -eq 0 ]
