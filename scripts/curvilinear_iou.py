#!/usr/bin/env python3
"""Mask agreement of curvilinear-grid renders with the regular Levitus file's (issue 25).

For each curvilinear test file (tests/data/netcdf/make_curvilinear.py) and the regular Levitus
atlas, renders a temperature isosurface (10 degC; 0 degC in the Arctic) with the same region, vertical scale, octree
depth and camera, with a transparent background, and prints JSON: per file the intersection
over union of the pixels where a surface is hit (alpha > 0) in the two images.

Usage: curvilinear_iou.py [--octrace BUILD/app/octrace] [--levitus FILE] [--out DIR] [--check]
(CTest runs it with --check: tests/CMakeLists.txt, Curvilinear.MaskAgreesWithTheRegularAtlas.)
The renders stay in DIR (default: a temporary folder) as CASE_curvilinear.png and CASE_regular.png.
"""
import argparse
import json
import os
import struct
import subprocess
import sys
import tempfile
import zlib

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# The least IoU `--check` accepts per case: the 0.9 for the two files; the Arctic strip is
# a stress case of the lon x cos(lat0) mapping (docs/dev/ocean.md), held at 0.85.
# The same Arctic in the polar stereographic mapping (chosen by `--map-projection auto` there) is
# held at the 0.9.
MIN_IOU = {"rotated_natl": 0.9, "tripolar_global": 0.9, "tripolar_arctic": 0.85, "tripolar_arctic_polar": 0.9}

POLAR_CAMERA, POLAR_LOOK_AT = "0,-4200,3800", "0,0,-400"

# name: (file, variable, iso, region, vertical scale, camera position, look-at, map projection)
CASES = {
    "rotated_natl": ("tests/data/netcdf/rotated_natl.nc", "temp", 10, "-70,-10,20,55", 300,
                     "0,-5200,4200", "0,-300,-600", "auto"),
    "tripolar_global": ("tests/data/netcdf/tripolar_global.nc", "temp", 10, "-180,180,-75,88", 600,
                        "0,-26000,26000", "0,0,-1000", "auto"),
    # The Arctic under the tripolar fold (the grid poles sit on land at 60 N): 0 degC, which lies
    # a few hundred metres down there. Kept on the lon x cos(lat0) mapping (what auto chose
    # before the polar mapping existed), as the "before" of the next case.
    "tripolar_arctic": ("tests/data/netcdf/tripolar_global.nc", "temp", 0, "-180,180,66,88", 1500,
                        "0,-3500,3000", "0,0,-500", "lonlat"),
    # The Arctic up to the pole in the polar stereographic mapping, which auto chooses there.
    "tripolar_arctic_polar": ("tests/data/netcdf/tripolar_global.nc", "temp", 0, "-180,180,65,90", 1500,
                              POLAR_CAMERA, POLAR_LOOK_AT, "auto"),
}


def png_alpha(path):
    """Alpha channel of an 8-bit RGBA, non-interlaced PNG, as rows of bytes."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", path
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or colour != 6 or interlace:
                sys.exit(f"{path}: expected 8-bit RGBA non-interlaced PNG")
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = width * 4
    rows, prev = [], bytearray(stride)
    for y in range(height):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for x in range(stride):
            a = line[x - 4] if x >= 4 else 0
            b = prev[x]
            c = prev[x - 4] if x >= 4 else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line[3::4]))
        prev = line
    return rows


def render(octrace, path, var, iso, region, scale, pos, look, projection, out, depth, size):
    cmd = [octrace, "render", path, "--var", var, "--iso", str(iso), "--region", region, "--vertical-scale", str(scale),
           "--map-projection", projection,
           "--depth", str(depth), "--camera-pos", pos, "--look-at", look, "--up", "0,0,1", "--fov", "40",
           "--size", size, "--background", "0,0,0,0", "-o", out]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--octrace", default=os.path.join(ROOT, "build/app/octrace"))
    ap.add_argument("--levitus", default=os.path.join(ROOT, "../shared/data/ocean/levitus_climatology.cdf"))
    ap.add_argument("--out", default=None)
    ap.add_argument("--depth", type=int, default=8)
    ap.add_argument("--size", default="640x360")
    ap.add_argument("--check", action="store_true", help="exit 1 when an IoU is below MIN_IOU")
    a = ap.parse_args()
    out = a.out or tempfile.mkdtemp(prefix="curvi_iou_")
    os.makedirs(out, exist_ok=True)
    result = {"depth": a.depth, "size": a.size, "files": {}}
    for name, (path, var, iso, region, scale, pos, look, projection) in CASES.items():
        cur = os.path.join(out, name + "_curvilinear.png")
        reg = os.path.join(out, name + "_regular.png")
        render(a.octrace, os.path.join(ROOT, path), var, iso, region, scale, pos, look, projection, cur, a.depth, a.size)
        render(a.octrace, a.levitus, "TEMP", iso, region, scale, pos, look, projection, reg, a.depth, a.size)
        inter = union = hit_c = hit_r = 0
        for rc, rr in zip(png_alpha(cur), png_alpha(reg)):
            for x, y in zip(rc, rr):
                inter += x > 0 and y > 0
                union += x > 0 or y > 0
                hit_c += x > 0
                hit_r += y > 0
        result["files"][name] = {"file": path, "iso": iso, "region": region, "vertical_scale": scale, "camera_pos": pos,
                                 "look_at": look, "map_projection": projection, "pixels_curvilinear": hit_c, "pixels_regular": hit_r,
                                 "iou": round(inter / union, 4) if union else None}
    print(json.dumps(result, indent=2))
    low = [n for n, r in result["files"].items() if r["iou"] is None or r["iou"] < MIN_IOU[n]]
    if a.check and low:
        sys.exit("IoU below " + ", ".join(f"{n}: {result['files'][n]['iou']} < {MIN_IOU[n]}" for n in low))


if __name__ == "__main__":
    main()
