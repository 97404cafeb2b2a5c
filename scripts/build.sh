#!/usr/bin/env bash
# Configures and builds octrace (Release) into build/, with the Python module (app/python) when
# the virtual environment of scripts/python-env.sh exists or OCTRACE_PYTHON=1 asks for it
# (scripts/test.sh does). Usage: scripts/build.sh [ninja targets...]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
PYTHON_ARGS=(-DOCTRACE_PYTHON=OFF)
if [ "${OCTRACE_PYTHON:-}" = "1" ] || [ -x "$ROOT/.venv/bin/python" ]; then
  PY="$(bash "$ROOT/scripts/python-env.sh" | tail -n 1)"
  PYTHON_ARGS=(-DOCTRACE_PYTHON=ON "-DPython_EXECUTABLE=$PY")
fi
LAUNCHER=()
if command -v ccache >/dev/null 2>&1; then LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache); fi
# The test binaries use a precompiled header (tests/CMakeLists.txt): ccache caches their objects
# only with these two relaxations, which its manual names for precompiled headers.
export CCACHE_SLOPPINESS="${CCACHE_SLOPPINESS:-pch_defines,time_macros}"
cmake -S "$ROOT" -B "$ROOT/build" -G Ninja -DCMAKE_BUILD_TYPE=Release "${PYTHON_ARGS[@]}" "${LAUNCHER[@]}" >/dev/null
ninja -C "$ROOT/build" "$@"
