#!/usr/bin/env bash
# The main job, from a fresh Debian machine: install, build, and render the Levitus 1982
# annual temperature 10 degC isosurface over the Northwest Pacific (incl. the Sea of Japan)
# to out/levitus_temp10.png. Uses ../shared/data/ocean/levitus_climatology.cdf when present,
# otherwise the same file from the Debian package ferret-datasets.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$ROOT/scripts/setup.sh"
bash "$ROOT/scripts/build.sh" octrace
DATA="$ROOT/../shared/data/ocean/levitus_climatology.cdf"
if [ ! -f "$DATA" ]; then
  CACHE="$ROOT/out/ferret-datasets"
  DATA="$CACHE/usr/share/ferret-vis/data/levitus_climatology.cdf"
  if [ ! -f "$DATA" ]; then
    echo "demo: ../shared/data not found; fetching the Levitus file from Debian's ferret-datasets"
    mkdir -p "$CACHE"
    (cd "$CACHE" && apt-get download ferret-datasets && dpkg-deb -x ferret-datasets_*.deb .)
  fi
fi
mkdir -p "$ROOT/out"
"$ROOT/build/app/octrace" render "$DATA" --var TEMP --iso 10 --region 120,180,10,60 --depth 9 \
  --colormap viridis --size 1600x1200 -o "$ROOT/out/levitus_temp10.png" --stats "$ROOT/out/levitus_temp10.json"
echo "demo: wrote $ROOT/out/levitus_temp10.png"
