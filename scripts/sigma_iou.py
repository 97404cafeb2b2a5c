#!/usr/bin/python3
"""Mask agreement of a terrain-following file's isosurface with the regular atlas's (issue 25).

    /usr/bin/python3 scripts/sigma_iou.py [--octrace build/app/octrace] [--images DIR] [--json FILE]
                                          [--region W,E,S,N]

Renders the 10 degC isotherm of Levitus 1982 (../shared/data/ocean/levitus_climatology.cdf,
TEMP on z-levels), of tests/data/netcdf/roms_g2_nwatlantic.nc (the same temperatures
interpolated onto 20 ROMS s-levels over ETOPO20, ocean_s_coordinate_g2) and of
tests/data/netcdf/roms_curvilinear_nwatlantic.nc (the same on a curvilinear grid with 2-D
lat_rho/lon_rho; both made by tests/data/netcdf/make_sigma.py) over the same region, with one
camera and one vertical scale, on a magenta background. A pixel is hit where it is not
magenta. Prints JSON: pixels hit by each, by both, by either, and their intersection over
union with Levitus's, for each ROMS-like file (the issue asks for >= 0.9).

The default region, 79.5W-56.5W, 30.5N-46.5N, is the box Levitus's 1-degree samples cover
within the files' 80W-56W, 30N-47N: the atlas's points lie at half degrees, so over the whole
box it draws nothing in the outer half-degree strip, where the ROMS-like files (points on the
box's edges) and a curvilinear file's lattice (spanning the region asked for) do, and those
strips count against the agreement though they are no difference of the grids. `--region
-80,-56,30,47` gives the figures over the whole box.
PNG reading is VTK's (system python3, as bench/peers/images.py).
"""
import argparse
import json
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "bench", "peers"))
from images import read_png  # noqa: E402  VTK's PNG reader, RGB rows from the top

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.environ.get("OCTRACE_SHARED_DATA", os.path.join(os.path.dirname(ROOT), "shared", "data"))
if not os.path.isdir(SHARED):
    SHARED = "/work/shared/data"
REGION = "-79.5,-56.5,30.5,46.5"
MASK_BACKGROUND = (1, 0, 1)  # magenta: no colour of the thermal map or of its shading
VIEW = ["--vertical-scale", "300", "--iso", "10", "--depth", "8", "--size", "640x480",
        "--camera-pos", "1500,-2400,700", "--look-at", "0,0,-200", "--colormap", "thermal",
        "--colour-range=-900,0"]
INPUTS = {
    "levitus": [os.path.join(SHARED, "ocean", "levitus_climatology.cdf"), "--var", "TEMP"],
    "roms_g2": [os.path.join(ROOT, "tests", "data", "netcdf", "roms_g2_nwatlantic.nc"), "--var", "temp",
                "--time", "0"],
    "roms_curvilinear": [os.path.join(ROOT, "tests", "data", "netcdf", "roms_curvilinear_nwatlantic.nc"), "--var",
                         "temp", "--time", "0"],
}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--octrace", default=os.path.join(ROOT, "build", "app", "octrace"))
    ap.add_argument("--images", default=os.path.join(ROOT, "docs", "images"))
    ap.add_argument("--json", default=None, help="also write the JSON here")
    ap.add_argument("--region", default=REGION, help="W,E,S,N in degrees (default: Levitus's samples' box)")
    args = ap.parse_args()
    masks, commands = {}, {}
    for name, inp in INPUTS.items():
        out = os.path.join(args.images, f"sigma-{name}-temp10.png")
        for background, path in (("1,1,1", out), (",".join(map(str, MASK_BACKGROUND)), out + ".mask.png")):
            cmd = [args.octrace, "render", *inp, "--region", args.region, *VIEW, "--background", background, "-o", path]
            subprocess.run(cmd, check=True, capture_output=True, text=True)
        masks[name] = np.any(read_png(out + ".mask.png") != np.array(MASK_BACKGROUND) * 255, axis=2)
        os.remove(out + ".mask.png")
        commands[name] = " ".join(os.path.relpath(c, ROOT) if os.path.isabs(c) and c.startswith(ROOT) else c
                                  for c in cmd[:-2])
    def agreement(name):
        a, b = masks["levitus"], masks[name]
        both, either = int(np.sum(a & b)), int(np.sum(a | b))
        return int(b.sum()), both, either, round(both / either, 4) if either else None

    pixels, both, either, iou = agreement("roms_g2")
    result = {
        "region": args.region,
        "iso": 10,
        "pixels_levitus": int(masks["levitus"].sum()),
        "pixels_roms_g2": pixels,
        "pixels_both": both,
        "pixels_either": either,
        "iou": iou,
    }
    pixels, both, either, iou = agreement("roms_curvilinear")
    result["roms_curvilinear"] = {"pixels": pixels, "pixels_both": both, "pixels_either": either, "iou": iou}
    result["commands"] = commands
    text = json.dumps(result, indent=2)
    print(text)
    if args.json:
        with open(args.json, "w") as f:
            f.write(text + "\n")
    ious = [result["iou"], result["roms_curvilinear"]["iou"]]
    return 0 if all(v is not None and v >= 0.9 for v in ious) else 1


if __name__ == "__main__":
    sys.exit(main())
