#!/usr/bin/env bash
# Installs what is needed, builds everything, and runs every test (CTest). Exits non-zero
# when any test fails. Tests that need ../shared/data say so and are skipped without it.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$ROOT/scripts/setup.sh"
bash "$ROOT/scripts/build.sh"
cd "$ROOT/build"
ctest --output-on-failure -j 2 --timeout 1500
