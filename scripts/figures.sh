#!/usr/bin/env bash
# Generates the example figure of docs/dev/figures.md from the Levitus climatology:
# the salinity 34.5 isohaline over the North Pacific (Sea of Japan included), coloured by
# temperature, over the sea floor, as a 180 x 120 mm figure at 200 dpi.
# Usage: scripts/figures.sh [BUILD_DIR]   (default build); needs ../shared/data/ocean.
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${1:-$ROOT/build}"
DATA="${OCTRACE_SHARED_DATA:-$ROOT/../shared/data}"
LEV="$DATA/ocean/levitus_climatology.cdf"
if [ ! -f "$LEV" ]; then echo "figures: $LEV not found" >&2; exit 1; fi
mkdir -p "$ROOT/docs/images"
"$BUILD/app/octrace" render "$LEV" --var SALT --iso 34.5 --colour-by TEMP --floor \
  --region 120,260,0,65 --depth 9 --vertical-scale 200 \
  --figure --title "Levitus (1982) annual mean: the 34.5 isohaline, North Pacific" \
  --dpi 200 --print-size 180x120mm --verify \
  -o "$ROOT/docs/images/levitus_salt34.5_by_temp.png"
