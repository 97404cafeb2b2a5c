#!/usr/bin/env bash
# The figure-text before/after images of docs/dev/figures.md ("Figure text"): 480x360 figures
# where issue 27 found text colliding, cut or wrong (SIZE sets another size). OCTRACE: the binary (default
# build/app/octrace); OUT: the folder (default docs/images/figtext); PREFIX: after_ or before_.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OCTRACE="${OCTRACE:-$ROOT/build/app/octrace}"
OUT="${OUT:-$ROOT/docs/images/figtext}"
PREFIX="${PREFIX:-after_}"
SIZE="${SIZE:-480x360}"
DATA="${OCTRACE_SHARED_DATA:-$ROOT/../shared/data}"
LEV="$DATA/ocean/levitus_climatology.cdf"
mkdir -p "$OUT"
"$OCTRACE" render "$LEV" --var TEMP --iso 10 --region 120,260,0,65 --depth 6 --projection ortho \
  --camera-pos 0,0,100000 --look-at 0,0,0 --up 0,1,0 --colormap thermal --figure --size "$SIZE" -o "$OUT/${PREFIX}top.png"
"$OCTRACE" render "$LEV" --var SALT --iso 34.5 --colour-by sound_speed --region 120,260,0,65 --depth 6 --floor \
  --figure --size "$SIZE" -o "$OUT/${PREFIX}ss.png"
"$OCTRACE" render "$DATA/medical/lidc2_chest_ct.nrrd" --iso 100 --depth 7 --figure --size "$SIZE" -o "$OUT/${PREFIX}ct.png"
"$OCTRACE" render "$DATA/city/delft.json" --depth 7 --scale-bar --figure --size "$SIZE" -o "$OUT/${PREFIX}city.png"
"$OCTRACE" slice "$LEV" --var TEMP --plane z --at 500 --region 120,180,10,60 --figure --size "$SIZE" -o "$OUT/${PREFIX}slice.png"
