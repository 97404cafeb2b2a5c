#!/usr/bin/env bash
# Checks that `pip install .` works in one step in a fresh virtual environment on a machine
# prepared by scripts/setup.sh, that the package renders there, and that the wheel it builds
# installs into a second fresh environment. Slow (a full build of the module): not part of
# scripts/test.sh, which builds the module inside the CMake tree instead.
# OCTRACE_PIP_BUILD_DIR=DIR keeps scikit-build-core's CMake tree in DIR for both builds (the
# wheel's is then incremental; with CMAKE_CXX_COMPILER_LAUNCHER=ccache and DIR beside build/,
# ccache reuses that tree's objects).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
BUILD_DIR=()
if [ -n "${OCTRACE_PIP_BUILD_DIR:-}" ]; then BUILD_DIR=(--config-settings="build-dir=$OCTRACE_PIP_BUILD_DIR"); fi
/usr/bin/python3 -m venv "$WORK/a"
"$WORK/a/bin/pip" install -q --disable-pip-version-check "${BUILD_DIR[@]}" "$ROOT"
CHECK='
import numpy as np, octrace
axis = np.linspace(-1, 1, 32)
z, y, x = np.meshgrid(axis, axis, axis, indexing="ij")
img = octrace.Volume((x * x + y * y + z * z - 0.36).astype(np.float32)).surface(iso=0, depth=5).render(size=(64, 48))
assert np.asarray(img).shape == (48, 64, 4) and np.isfinite(img.depth).any()
print("octrace", octrace.__file__, "renders", img)
'
(cd "$WORK" && "$WORK/a/bin/python" -c "$CHECK")
"$WORK/a/bin/pip" wheel -q --disable-pip-version-check --no-deps "${BUILD_DIR[@]}" -w "$WORK/wheels" "$ROOT"
/usr/bin/python3 -m venv "$WORK/b"
"$WORK/b/bin/pip" install -q --disable-pip-version-check "$WORK"/wheels/octrace-*.whl
(cd "$WORK" && "$WORK/b/bin/python" -c "$CHECK")
echo "check-pip-install: pip install . and its wheel both work"
