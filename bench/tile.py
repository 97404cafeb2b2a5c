#!/usr/bin/env python3
"""Generates docs/benchmarks/tile.md: the exact tile renderer (`--renderer tile`, issue 23)
against `full` on Table 1's deepest scenes, at Table 1's camera (bench/scenes/*.json) and at
octrace's default framing as of commit 5923210 (bench/scenes/default_framing.json, written by
bench/default_framing.py), 1600x1200. Raw stats JSON of every run in docs/benchmarks/tile/.

Per scene, camera and surface mode (`--surface voxel`, the boxes of the boundary voxels, as the
papers draw them; and `--surface smooth`, the field's interpolant, octrace's default for fields,
only where the octree has the field's corner values), two invocations of `octrace render`:
- 2 threads: `--renderer tile --baseline full --repeat R`: tile and full rendered alternately
  in one process, fastest of R each (render_ms, baseline_render_ms, speedup_over_baseline);
  baseline_differing_pixels counts pixels whose hit differs from full's;
- 1 thread, the same with `--verify`: us per ray of both, and mismatched_pixels against the
  exact reference.
The load average (1 minute) is read before and after each invocation; absolute times on this
shared 2-core machine move with it, the ratios much less.

With --from-raw nothing is rendered: the table is written from the raw JSON already in
docs/benchmarks/tile/ (the cells that have it; the others are listed as not measured).

Usage: bench/tile.py [--octrace PATH] [--data DIR] [--repeat R] [--scenes K,...] [--surfaces voxel,smooth] [--write-dicom PATH] [--from-raw]
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import benchcommon  # noqa: E402
import table1  # noqa: E402

SCENES = ["T", "CT-skin", "CT-bone", "city-t10", "molecule"]  # Table 1's deepest: ocean T 9, CT 9, city 10-12, molecule
# Issue 23's ratios over full (full's 2-thread time at 5923210 / 50 ms); other cells need full / 50 ms.
TARGETS = {("T", "default"): 3.6, ("T", "table1"): 1.18, ("CT-skin", "table1"): 3.6, ("CT-bone", "table1"): 2.9,
           ("city-t10", "table1"): 2.5, ("molecule", "table1"): 5.1}
TARGET_MS = 50.0
SURFACES = ("voxel", "smooth")


def render(args, scene, camera, threads, tag, outdir, surface):
    stats = os.path.join(outdir, tag + ".json")
    depth = max(scene["depths"])
    cmd = [args.octrace, "render", table1.scene_input(args, scene)]
    for key, opt in (("var", "--var"), ("iso", "--iso"), ("region", "--region")):
        if key in scene:
            cmd += [opt, str(scene[key])]
    cmd += [scene.get("depth_option", "--depth"), str(depth)] + scene.get("args", [])
    cmd += ["--size", scene["size"], "--camera-pos", camera["camera_pos"], "--look-at", camera["look_at"],
            "--up", camera["up"], "--fov", str(camera["fov"]), "--renderer", "tile", "--baseline", "full",
            "--threads", str(threads), "--repeat", str(args.repeat), "--surface", surface, "--stats", stats, "--quiet",
            "-o", os.path.join(args.tmp, tag + ".png")]
    if threads == 1:
        cmd.append("--verify")
    return benchcommon.run_recording_load(cmd, stats)


def main():
    ap = benchcommon.parser(__doc__)
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--scenes", default=",".join(SCENES))
    ap.add_argument("--two-threads-only", action="store_true",
                    help="only the 2-thread runs (no single-thread us per ray, no --verify): cells already measured keep theirs")
    ap.add_argument("--from-raw", action="store_true", help="write the table from the raw JSON only")
    ap.add_argument("--surfaces", default=",".join(SURFACES),
                    help="the surface modes to render; the others' cells come from the raw JSON already there")
    ap.add_argument("--write-dicom", default=os.path.join(benchcommon.ROOT, "build", "octrace_write_dicom"))
    args = ap.parse_args()
    table1.use_scratch(args, "/tmp/octrace-tile")
    outdir = benchcommon.raw_dir("tile")
    scenes = {s["key"]: s for s in table1.table1_scenes()}
    framing = benchcommon.load(os.path.join(benchcommon.ROOT, "bench", "scenes", "default_framing.json"))["scenes"]
    rows = []
    missing = []
    for key in [k for k in args.scenes.split(",") if k]:
        s = scenes[key]
        for cam_name, cam in (("table1", s), ("default", framing[key])):
            for surface in SURFACES:
                tag = "%s_%s_%s" % (key, cam_name, surface)
                if args.from_raw or surface not in args.surfaces.split(","):
                    paths = [os.path.join(outdir, tag + t + ".json") for t in ("_t2", "_t1")]
                    if not os.path.exists(paths[0]):
                        if surface == "voxel":
                            missing.append("%s, depth %d, %s camera" % (s["name"], max(s["depths"]), cam_name))
                        continue
                    two = benchcommon.load(paths[0])
                    one = benchcommon.load(paths[1]) if os.path.exists(paths[1]) else None
                else:
                    two = render(args, s, cam, 2, tag + "_t2", outdir, surface)
                    if two.get("surface") != surface:
                        os.remove(os.path.join(outdir, tag + "_t2.json"))
                        continue  # no corner values: smooth draws the voxels' boxes, as voxel did
                    p1 = os.path.join(outdir, tag + "_t1.json")
                    if args.two_threads_only:
                        one = benchcommon.load(p1) if os.path.exists(p1) else None
                    else:
                        one = render(args, s, cam, 1, tag + "_t1", outdir, surface)
                rows.append((s, cam_name, two, one))
                if one is None:
                    print("%s %s %s: tile %.1f ms, full %.1f ms (%.2fx)" % (key, cam_name, surface, two["render_ms"],
                          two["baseline_render_ms"], two["speedup_over_baseline"]), flush=True)
                    continue
                print("%s %s %s: tile %.1f ms, full %.1f ms (%.2fx), 1 thread %.3f vs %.3f us/ray, mismatched %s" % (
                    key, cam_name, surface, two["render_ms"], two["baseline_render_ms"], two["speedup_over_baseline"],
                    one["us_per_ray"], one["baseline_render_ms"] * 1000.0 / max(one["rays"], 1),
                    one.get("mismatched_pixels")), flush=True)

    rep = rows[0][2].get("repeat", args.repeat) if rows else args.repeat
    L = ["# The exact tile renderer against full\n",
         "Generated by `bench/tile.py` (do not edit by hand); raw stats JSON of every run in [`tile/`](tile/).",
         "1600x1200, Table 1's deepest depth of each scene, at Table 1's camera (`bench/scenes/`) and at",
         "octrace's default framing as of 5923210 (`bench/scenes/default_framing.json`). Each time is the",
         "fastest of %d renders in one process, `tile` and `full` alternating (`--baseline full`)." % rep,
         "`differing` counts pixels whose hit differs from `full`'s, `mismatched` (single thread, `--verify`)",
         "those whose hit differs from the exact reference. Load average: the 1-minute load before and",
         "after the invocation (2 cores, shared).\n",
         "Targets (issue 23): <= %.0f ms at 2 threads on an idle machine, and a ratio over `full` of at" % TARGET_MS,
         "least the one given (from `full`'s time at 5923210, which drew voxels; where none is given, `full`'s",
         "time here / 50 ms, which a loaded machine overstates). Both surface modes count (issue 23); in",
         "smooth mode `full` tests the interpolant on the first boundary voxel and, when the ray passes it,",
         "traverses again from the root, where `tile` tests inside its own traversal (docs/dev/tile-renderer.md).\n",
         "## 2 threads\n",
         "| scene | camera | surface | rays | full ms | tile ms | full / tile | target ratio | differing | load avg |",
         "|---|---|---|---|---|---|---|---|---|---|"]
    for s, cam_name, two, one in rows:
        target = TARGETS.get((s["key"], cam_name))
        need = "%.2f" % target if target else "%.2f (full / 50 ms)" % (two["baseline_render_ms"] / TARGET_MS)
        L.append("| %s, depth %d | %s | %s | %s | %.1f | %.1f | %.2f | %s | %d | %.2f / %.2f |" % (
            s["name"], max(s["depths"]), cam_name, two.get("surface", "voxel"), format(two["rays"], ","), two["baseline_render_ms"], two["render_ms"],
            two["speedup_over_baseline"], need, two["baseline_differing_pixels"], two["load_avg_1min"][0],
            two["load_avg_1min"][1]))
    L += ["", "## Single thread, us per ray\n",
          "| scene | camera | surface | full us/ray | tile us/ray | full / tile | nodes per ray (tile) | mismatched | load avg |",
          "|---|---|---|---|---|---|---|---|---|"]
    for s, cam_name, two, one in rows:
        if one is None:
            L.append("| %s, depth %d | %s | %s | not measured | | | | | |" % (s["name"], max(s["depths"]), cam_name,
                                                                    two.get("surface", "voxel")))
            continue
        full_us = one["baseline_render_ms"] * 1000.0 / max(one["rays"], 1)
        L.append("| %s, depth %d | %s | %s | %.3f | %.3f | %.2f | %.2f | %s | %.2f / %.2f |" % (
            s["name"], max(s["depths"]), cam_name, one.get("surface", "voxel"), full_us, one["us_per_ray"], one["speedup_over_baseline"],
            one["nodes_per_ray"], one.get("mismatched_pixels"), one["load_avg_1min"][0], one["load_avg_1min"][1]))
    L.append("")
    if missing:
        L.append("Not measured in this run: %s.\n" % "; ".join(missing))
    with open(os.path.join(benchcommon.ROOT, "docs", "benchmarks", "tile.md"), "w") as f:
        f.write("\n".join(L))
    return 0


if __name__ == "__main__":
    sys.exit(main())
