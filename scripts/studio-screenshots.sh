#!/usr/bin/env bash
# Regenerates the screenshots of docs/user/studio.md: runs the studio's QTest under Xvfb with
# OCTRACE_STUDIO_SCREENSHOTS pointing at docs/user/images (the test saves the window there at
# the steps it drives). Needs a build with the studio (scripts/build.sh).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mkdir -p "$ROOT/docs/user/images"
ninja -C "$ROOT/build" octrace_studio_tests octrace
cd "$ROOT"  # the window shows the input as given: data_samples/torus.nrrd
OCTRACE_STUDIO_SCREENSHOTS="$ROOT/docs/user/images" xvfb-run -a -s "-screen 0 1920x1200x24" build/tests/octrace_studio_tests
