#!/usr/bin/env bash
# Issue 27's "`--depth auto` choices listed in `info` for every shared data file": runs
# `octrace info` on every input of ../shared/data/README.md (headsq_raw: its header) and writes
# what it says `depth` auto picks, one table row a file, into docs/user/first-pictures.md between
# its depth-auto markers (paths relative to the data folder).
#
#   scripts/depth_auto_table.sh [OCTRACE]
#
# OCTRACE defaults to build/app/octrace; OCTRACE_SHARED_DATA to ../shared/data.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
OCTRACE="${1:-$ROOT/build/app/octrace}"
DATA="$(cd "${OCTRACE_SHARED_DATA:-$ROOT/../shared/data}" && pwd)"
DOC="$ROOT/docs/user/first-pictures.md"
TABLE="$(mktemp)"
trap 'rm -f "$TABLE"' EXIT

{
  echo "| file | depth auto |"
  echo "|---|---|"
  (cd "$DATA" && ls -d */* | sort) | while read -r rel; do
    case "$rel" in *.md) continue ;; medical/headsq_raw) rel=medical/headsq_raw/quarter.nhdr ;; esac
    if out="$("$OCTRACE" info "$DATA/$rel" 2>&1)"; then
      line="$(printf '%s\n' "$out" | grep -m1 'depth auto' | sed 's/^ *//; s/^depth auto: //')" || line="none listed"
    else
      line="refused: $(printf '%s\n' "$out" | tail -1)"
    fi
    line="${line//$DATA\//}"
    echo "| \`$rel\` | ${line//|/\\|} |"
  done
} >"$TABLE"

/usr/bin/python3 - "$DOC" "$TABLE" <<'PY'
import sys
doc, table = sys.argv[1], open(sys.argv[2]).read()
begin, end = "<!-- depth-auto table: scripts/depth_auto_table.sh -->", "<!-- end of depth-auto table -->"
text = open(doc).read()
i, j = text.index(begin) + len(begin), text.index(end)
open(doc, "w").write(text[:i] + "\n" + table + text[j:])
PY
echo "depth_auto_table: $(($(wc -l <"$TABLE") - 2)) files written to $DOC" >&2
