#!/usr/bin/env bash
# Makes the virtual environment the Python package is built and tested in: .venv beside this
# folder, from Debian's python3 (python3-venv, python3-dev: scripts/setup.sh), with the pinned
# packages of app/python/requirements.txt from PyPI. Idempotent: an environment whose
# requirements are unchanged is kept. Prints the environment's python on its last line.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="${OCTRACE_VENV:-$ROOT/.venv}"
REQ="$ROOT/app/python/requirements.txt"
STAMP="$VENV/.octrace-requirements"
if [ ! -x "$VENV/bin/python" ]; then
  echo "python-env: creating $VENV" >&2
  /usr/bin/python3 -m venv "$VENV"
fi
if ! cmp -s "$REQ" "$STAMP"; then
  echo "python-env: installing app/python/requirements.txt from PyPI" >&2
  "$VENV/bin/python" -m pip install -q --disable-pip-version-check -r "$REQ" >&2
  cp "$REQ" "$STAMP"
fi
echo "$VENV/bin/python"
