#!/usr/bin/env bash
# Installs the Debian (bookworm) packages octrace builds and tests with. Idempotent; needs root
# (or sudo). Nothing is downloaded at build time: these packages are everything.
# Usage: scripts/setup.sh [--fuzz]   (--fuzz: also clang and libFuzzer, for tests/fuzz/run.sh)
set -euo pipefail
# qt6-base-dev ... libgl1-mesa-dri: octrace-studio (optional: without Qt 6 only the CLI builds);
# xvfb, xauth and Mesa's llvmpipe (libgl1-mesa-dri) run its tests without a display.
# libavcodec-dev ... libswscale-dev: MP4 videos of `octrace animate` (H.264 through libx264); ffmpeg: its
# ffprobe, which the animate tests use to count and decode the frames.
# gmt-gshhg-low, gmt-gshhg-high: GSHHG's shorelines (GMT's binned netCDF), the coastlines of map figures.
# libudunits2-dev, libudunits2-data: UDUNITS-2 and its unit database (vertical axes in cm or km, `--iso 10degC`).
# libgdcm-tools: Debian's GDCM CMake package (libgdcm-dev) imports its tools and fails without them.
# gdal-bin: gdalmdimtranslate, with which tests/data/zarr/make_zarr_stores.py writes GDAL's Zarr
# stores of the Levitus atlas at test time.
# python3-matplotlib: the benchmark plots (bench/figure5.py, bench/figure5_2d.py, drawn by the system
# /usr/bin/python3, not the virtual environment) and their CTest BenchPlots.*.
PACKAGES=(
  cmake ninja-build g++ pkg-config python3-dev python3-venv
  libgdal-dev gdal-bin libgdcm-dev libgdcm-tools libvtk9-dev libopenexr-dev libglm-dev libtbb-dev
  libgtest-dev libbenchmark-dev libpng-dev libtiff-dev libzstd-dev zlib1g-dev nlohmann-json3-dev libfreetype-dev fonts-dejavu-core
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev ffmpeg
  gmt-gshhg-low gmt-gshhg-high
  libudunits2-dev libudunits2-data
  python3-matplotlib
  qt6-base-dev libqt6opengl6-dev libgl-dev libxkbcommon-dev xvfb xauth libgl1-mesa-dri
)
if [ "${1:-}" = "--fuzz" ]; then
  PACKAGES+=(clang libclang-rt-14-dev)
fi
missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "setup: installing ${missing[*]}"
$SUDO apt-get update -q
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends "${missing[@]}"
