#!/usr/bin/env bash
# Regenerates the screenshots of docs/user/studio.md: runs the studio's QTests under Xvfb with
# OCTRACE_STUDIO_SCREENSHOTS pointing at docs/user/images (the tests save the window there at
# the steps they drive). Needs a build with the studio (scripts/build.sh). With arguments, only
# those test executables (e.g. octrace_studioocean_tests). With pngquant (apt-get install
# pngquant) the pictures this run wrote are then reduced to 256 colours (each stays well under
# 400 KB).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
mkdir -p "$ROOT/docs/user/images"
TESTS=("$@")
[ ${#TESTS[@]} -gt 0 ] || TESTS=(octrace_studio_tests octrace_studioocean_tests)
ninja -C "$ROOT/build" "${TESTS[@]}" octrace
stamp="$(mktemp)"  # the pictures written after it are this run's
trap 'rm -f "$stamp"' EXIT
cd "$ROOT"  # the messages name the input as given: data_samples/torus.nrrd, ../shared/data/...
for t in "${TESTS[@]}"; do
  OCTRACE_STUDIO_SCREENSHOTS="$ROOT/docs/user/images" xvfb-run -a -s "-screen 0 1920x1200x24" "build/tests/$t"
done
if command -v pngquant >/dev/null; then
  # Only this run's pictures: a picture quantized once is not quantized again.
  find "$ROOT/docs/user/images" -name 'studio-*.png' -newer "$stamp" | while read -r png; do
    pngquant --quality 85-100 --speed 1 --skip-if-larger --force --ext .png "$png" || true
  done
else
  echo "pngquant not found: the pictures are left as Qt wrote them" >&2
fi
ls -l "$ROOT"/docs/user/images/studio-*.png
