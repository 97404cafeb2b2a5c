#!/usr/bin/env bash
# The first picture each input gives with no options (issue 27), for docs/user/first-pictures.md:
# renders each shared data input with `octrace render INPUT -o OUT.png` and nothing else (the CT
# presets add only --iso; Levitus only --var TEMP, which a file of several 3-D variables needs),
# writes a 400-pixel-wide copy as docs/user/images/first/NAME-LABEL.png,
# and (after) writes what `octrace info` says `--depth auto` picks for every shared data file
# into first-pictures.md (scripts/depth_auto_table.sh).
#
#   scripts/first_pictures.sh LABEL [OCTRACE] [WRITE_DICOM]
#
# LABEL names the pictures (before, after); OCTRACE defaults to build/app/octrace, WRITE_DICOM
# (the CT series writer, bench/WriteDicomSeries.cpp) to build/octrace_write_dicom. The chest CT
# is written as a CT series in HU (RescaleSlope 8, RescaleIntercept -1000, as bench/table1.py)
# with the soft-tissue window 40/400 stored in the file, as the issue's CT had. Needs
# /usr/bin/python3 with PIL (Debian python3-pil) for the small copies. ONLY="NAME ..." renders
# only those pictures (the molecule at depth auto 10 needs about 10 GiB and minutes).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
LABEL="${1:?usage: first_pictures.sh LABEL [OCTRACE] [WRITE_DICOM]}"
OCTRACE="${2:-$ROOT/build/app/octrace}"
WRITE_DICOM="${3:-$ROOT/build/octrace_write_dicom}"
DATA="${OCTRACE_SHARED_DATA:-$ROOT/../shared/data}"
OUT="$ROOT/docs/user/images/first"
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$OUT"

"$WRITE_DICOM" "$DATA/medical/lidc2_chest_ct.nrrd" "$TMP/ct" --modality CT --rescale 8,-1000 --window 40,400 >/dev/null

render() {  # NAME INPUT [OPTIONS...]; ONLY="NAME ..." renders those alone
  local name="$1" input="$2"
  shift 2
  if [ -n "${ONLY:-}" ] && [[ " $ONLY " != *" $name "* ]]; then return; fi
  echo "== $name: octrace render $(basename "$input") $* -o $name.png" >&2
  "$OCTRACE" render "$input" "$@" -o "$TMP/$name.png" 2>&1 | sed 's/^/   /' >&2
  /usr/bin/python3 - "$TMP/$name.png" "$OUT/$name-$LABEL.png" <<'PY'
import sys
from PIL import Image
im = Image.open(sys.argv[1])
w = 400
im.resize((w, round(im.height * w / im.width)), Image.LANCZOS).save(sys.argv[2], optimize=True)
PY
}

render levitus "$DATA/ocean/levitus_climatology.cdf" --var TEMP  # several 3-D variables: render asks for one
render ct-skin "$TMP/ct" --iso skin
render ct-bone "$TMP/ct" --iso bone
render mr "$DATA/medical/d2n_mr_sag_4slices_anatomical"
render mr-emri "$DATA/medical/emri_small.dcm"
render delft "$DATA/city/delft.json"
render molecule "$DATA/molecule/4HHB.pdb"

if [ "$LABEL" = after ]; then
  "$ROOT/scripts/depth_auto_table.sh" "$OCTRACE"  # the depth auto table of first-pictures.md
fi
