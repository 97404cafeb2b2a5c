#!/usr/bin/env python3
"""Records octrace's default framing of each Table 1 scene (bench/scenes/*.json with "table1")
into bench/scenes/default_framing.json: the camera `octrace render` picks when given no camera
option, at the scene's size and deepest depth, read back from the stats JSON (camera_pos,
look_at, up, fov) with the rays that meet the scene cube. Issue 23's targets for the default
view are stated against the framing of commit 5923210; the framing code (Camera::framing,
core/src/render/Camera.cpp, and model::frameCamera) is unchanged since then, so today's build
gives those cameras. Run it once; the benchmarks read the file, so that later changes of the
default framing do not move the target.

Usage: bench/default_framing.py [--octrace PATH] [--data DIR] [--write-dicom PATH]
"""
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import benchcommon  # noqa: E402
import table1  # noqa: E402

OUT = os.path.join(benchcommon.ROOT, "bench", "scenes", "default_framing.json")


def framing(args, scene, depth):
    """The stats JSON of one render with no camera option (renderer full, for the rays that
    meet the scene cube; the camera does not depend on the renderer)."""
    stats = os.path.join(args.tmp, "framing_%s.json" % scene["key"])
    cmd = [args.octrace, "render", table1.scene_input(args, scene)]
    for key, opt in (("var", "--var"), ("iso", "--iso"), ("region", "--region")):
        if key in scene:
            cmd += [opt, str(scene[key])]
    cmd += [scene.get("depth_option", "--depth"), str(depth)] + scene.get("args", [])
    cmd += ["--size", scene["size"], "--renderer", "full", "--threads", "2", "--stats", stats, "--quiet",
            "-o", os.path.join(args.tmp, "framing_%s.png" % scene["key"])]
    subprocess.run(cmd, check=True)
    full = dict(cmd=cmd)
    with open(stats) as f:
        full.update(json.load(f))
    return full


def main():
    ap = benchcommon.parser(__doc__)
    ap.add_argument("--write-dicom", default=os.path.join(benchcommon.ROOT, "build", "octrace_write_dicom"))
    args = ap.parse_args()
    args.written = set()
    args.tmp = "/tmp/octrace-framing"
    os.makedirs(args.tmp, exist_ok=True)
    out = {"note": "octrace's default framing (no camera option) of each Table 1 scene at its size and deepest "
                   "depth, as of commit 5923210 (framing code unchanged since); written by bench/default_framing.py",
           "scenes": {}}
    for scene in table1.table1_scenes():
        depth = max(scene["depths"])
        st = framing(args, scene, depth)
        out["scenes"][scene["key"]] = {"depth": depth, "size": scene["size"], "camera_pos": st["camera_pos"],
                                       "look_at": st["look_at"], "up": st["up"], "fov": st["fov"],
                                       "rays": st.get("rays")}
        print(scene["key"], out["scenes"][scene["key"]], flush=True)
    with open(OUT, "w") as f:
        json.dump(out, f, indent=2)
        f.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
