#!/usr/bin/env bash
# The cut-away demos of docs/user/cli.md (octrace csg, --cut, --clip), made from the shared
# data: the VTK CT head with a wedge removed, and the Levitus 10 degC isotherm's cold side
# clipped to a region. Usage: scripts/csg_demos.sh [OCTRACE] [DATA] [OUTDIR]
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
octrace=${1:-$here/build/app/octrace}
data=${2:-$here/../shared/data}
out=${3:-$here/docs/images}
# Skin (iso 500) of the head as a solid; the scan's last slice is capped, the wedge's faces
# take the box's normals. z runs from the crown to the chin: up is -z.
"$octrace" render "$data/medical/headsq_raw/quarter.nhdr" --iso 500 --depth 8 \
  --cut box:100.8,-1,-1,210,100.8,70 --size 500x500 \
  --camera-pos 420,-260,-180 --look-at 100,100,70 --up 0,0,-1 --verify -o "$out/csg_head_wedge.png"
# The same cut with the CT's grey (a display window): the cut faces show the tissue there.
"$octrace" render "$data/medical/headsq_raw/quarter.nhdr" --iso 500 --depth 8 --window 1200,2000 \
  --cut box:100.8,-1,-1,210,100.8,70 --size 500x500 \
  --camera-pos 420,-260,-180 --look-at 100,100,70 --up 0,0,-1 --verify -o "$out/csg_head_wedge_window.png"
# Water colder than 10 degC (--inside below) under the Northwest Pacific, kept inside a box:
# its top is the isotherm, its sides the box's faces, its bottom the sea floor's caps.
"$octrace" render "$data/ocean/levitus_climatology.cdf" --var TEMP --iso 10 --region 120,180,10,60 --depth 8 \
  --inside below --cut box:-1500,-1800,-2000,1800,1500,100 --clip --colormap viridis --size 640x480 \
  --verify -o "$out/csg_levitus_clip.png"
# The water column of the Northeast Atlantic (every sample at or above the region's coldest,
# 2.108 degC) extended down through the grid's sea-floor mask (--extend-down), minus the ETOPO20
# relief: the floor is the relief's, coloured by the temperature there; beside it the same
# water as the grid's own staircase floor. Seen from below, south-west.
view=(--var TEMP --iso 2.108 --region -25,5,40,60 --depth 8 --colour-by TEMP --colormap thermal --size 720x480
      --camera-pos -1500,-3000,-2600 --look-at 0,0,100 --up 0,0,1 --fov 40 --verify)
"$octrace" render "$data/ocean/levitus_climatology.cdf" "${view[@]}" --form volume -o "$out/csg_ocean_own_floor.png"
"$octrace" render "$data/ocean/levitus_climatology.cdf" "${view[@]}" --extend-down \
  --cut "relief:$data/ocean/etopo20.cdf" -o "$out/csg_ocean_minus_etopo20.png"
