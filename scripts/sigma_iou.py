#!/usr/bin/python3
"""Mask agreement of a terrain-following file's isosurface with the regular atlas's (issue 25).

    /usr/bin/python3 scripts/sigma_iou.py [--octrace build/app/octrace] [--images DIR] [--json FILE]

Renders the 10 degC isotherm of Levitus 1982 (../shared/data/ocean/levitus_climatology.cdf,
TEMP on z-levels) and of tests/data/netcdf/roms_g2_nwatlantic.nc (the same temperatures
interpolated onto 20 ROMS s-levels over ETOPO20, ocean_s_coordinate_g2; made by
tests/data/netcdf/make_sigma.py) over the same region, with one camera and one vertical scale,
on a magenta background. A pixel is hit where it is not magenta. Prints JSON: pixels hit
by each, by both, by either, and their intersection over union (the issue asks for >= 0.9).
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
REGION = "-80,-56,30,47"
MASK_BACKGROUND = (1, 0, 1)  # magenta: no colour of the thermal map or of its shading
VIEW = ["--region", REGION, "--vertical-scale", "300", "--iso", "10", "--depth", "8", "--size", "640x480",
        "--camera-pos", "1500,-2400,700", "--look-at", "0,0,-200", "--colormap", "thermal",
        "--colour-range=-900,0"]
INPUTS = {
    "levitus": [os.path.join(SHARED, "ocean", "levitus_climatology.cdf"), "--var", "TEMP"],
    "roms_g2": [os.path.join(ROOT, "tests", "data", "netcdf", "roms_g2_nwatlantic.nc"), "--var", "temp",
                "--time", "0"],
}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--octrace", default=os.path.join(ROOT, "build", "app", "octrace"))
    ap.add_argument("--images", default=os.path.join(ROOT, "docs", "images"))
    ap.add_argument("--json", default=None, help="also write the JSON here")
    args = ap.parse_args()
    masks, commands = {}, {}
    for name, inp in INPUTS.items():
        out = os.path.join(args.images, f"sigma-{name}-temp10.png")
        for background, path in (("1,1,1", out), (",".join(map(str, MASK_BACKGROUND)), out + ".mask.png")):
            cmd = [args.octrace, "render", *inp, *VIEW, "--background", background, "-o", path]
            subprocess.run(cmd, check=True, capture_output=True, text=True)
        masks[name] = np.any(read_png(out + ".mask.png") != np.array(MASK_BACKGROUND) * 255, axis=2)
        os.remove(out + ".mask.png")
        commands[name] = " ".join(os.path.relpath(c, ROOT) if os.path.isabs(c) and c.startswith(ROOT) else c
                                  for c in cmd[:-2])
    a, b = masks["levitus"], masks["roms_g2"]
    both, either = int(np.sum(a & b)), int(np.sum(a | b))
    result = {
        "region": REGION,
        "iso": 10,
        "pixels_levitus": int(a.sum()),
        "pixels_roms_g2": int(b.sum()),
        "pixels_both": both,
        "pixels_either": either,
        "iou": round(both / either, 4) if either else None,
        "commands": commands,
    }
    text = json.dumps(result, indent=2)
    print(text)
    if args.json:
        with open(args.json, "w") as f:
            f.write(text + "\n")
    return 0 if result["iou"] is not None and result["iou"] >= 0.9 else 1


if __name__ == "__main__":
    sys.exit(main())
