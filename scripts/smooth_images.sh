#!/usr/bin/env bash
# Before/after images of smooth surfaces (docs/dev/smooth-surfaces.md): the same frame drawn as
# voxel boxes (--surface voxel) and as the field's interpolant (--surface smooth), at a depth
# coarse enough that the voxels show, written to docs/images/smooth-*.png.
# Usage: scripts/smooth_images.sh [path/to/octrace]
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OCTRACE="${1:-$ROOT/build/app/octrace}"
DATA="${OCTRACE_SHARED_DATA:-$ROOT/../shared/data}"
OUT="$ROOT/docs/images"
for mode in voxel smooth; do
  # Ocean: the 10 degC isotherm of the Levitus atlas off the US east coast (Gulf Stream), depth 6.
  "$OCTRACE" render "$DATA/ocean/levitus_climatology.cdf" --var TEMP --iso 10 --region -75,-35,25,50 --depth 6 \
    --surface "$mode" --size 480x360 -o "$OUT/smooth-levitus-temp10-$mode.png"
  # CT bone: the VTK CT head (64 x 64 x 93 samples, 3.2 x 3.2 x 1.5 mm) at 1150, depth 7.
  "$OCTRACE" render "$DATA/medical/headsq_raw/quarter.nhdr" --iso 1150 --depth 7 \
    --surface "$mode" --size 480x360 -o "$OUT/smooth-ct-bone-$mode.png"
done
