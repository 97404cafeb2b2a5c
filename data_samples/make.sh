#!/usr/bin/env bash
# Regenerates the sample fields in this folder with octrace itself (analytic, known surfaces).
# Usage: data_samples/make.sh [path/to/octrace]
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
OCTRACE="${1:-$HERE/../build/app/octrace}"
"$OCTRACE" sample sphere --samples 33 -o "$HERE/sphere.nrrd"
"$OCTRACE" sample torus --samples 33 -o "$HERE/torus.nrrd"
