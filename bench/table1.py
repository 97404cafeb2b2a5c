#!/usr/bin/env python3
"""Generates docs/benchmarks/table1.md: paper A's Table 1 reproduced with octrace's discrete
renderers on the scenes of bench/scenes/ (fixed cameras), at 1600x1200, single-thread and on
2 threads, with every raw stats JSON kept in docs/benchmarks/table1/.

Each cell is `octrace render ... --repeat R` (render_ms = fastest of R renders in one process);
the single-thread runs also pass --verify, which counts the pixels whose hit voxel differs from
the exact reference (`mismatched_pixels`) and the image difference (PSNR). Speed-ups are
against `full` rendered alternately in the same process (`--baseline full`).

A scene is a JSON file in bench/scenes/ with "table1": true: "key" (row key, e.g. T), "name",
"input" (relative to --data), "depths", "size", camera ("camera_pos", "look_at", "up", "fov"),
and the input's options: "var", "iso", "region", "depth_option" (default "--depth": the option
that takes the depth) and "args" (any further options). A scene with "write_dicom"
({"modality": "CT", "rescale": "SLOPE,INTERCEPT"}) renders its input written as a DICOM series
by the project's writer (octrace_write_dicom, beside the octrace executable: the input's values
are stored values, the series' real values value * SLOPE + INTERCEPT), in a temporary folder,
once per run. `--scenes K1,K2` runs only those rows
(and `--renderers R1,R2` only those columns) and takes the others from the raw JSON already in docs/benchmarks/table1/ (each row is still
one invocation per cell, so its ratios stay within one run); a scene not asked for whose raw JSON is
incomplete is listed as not measured yet.

Usage: bench/table1.py [--octrace PATH] [--data DIR] [--repeat R] [--quick] [--scenes K,...]
                       [--renderers R,...] [--write-dicom PATH]
"""
import argparse
import glob
import json
import os
import shutil
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RENDERERS = ["full", "linear", "area", "area+colour", "linear-exact", "area-exact"]
DIRECT = ["direct", "direct-f2b"]  # object-order renderers: no rays, so no us per ray
CROSSOVER_DEPTHS = [7, 8, 9, 10, 11]  # scene T, single thread: where does ray casting win?
# Paper A, Table 1 (Athlon 1800): seconds (us per ray) for full, linear, area, area+colour, direct.
PAPER = {
    ("T", 7): (107632, "1.73 (2.52)", "1.34 (1.95)", "1.14 (1.66)", "0.88 (1.28)", "0.19"),
    ("T", 8): (434982, "1.95 (2.84)", "1.53 (2.23)", "1.34 (1.95)", "1.00 (1.46)", "0.34"),
    ("T", 9): (1751387, "2.25 (3.21)", "1.76 (2.57)", "1.66 (2.42)", "1.14 (1.66)", "0.95"),
    ("S", 7): (148687, "1.94 (2.83)", "1.32 (1.92)", "1.11 (1.62)", "0.95 (1.39)", "0.50"),
    ("S", 8): (614339, "2.20 (3.21)", "1.49 (2.17)", "1.31 (1.91)", "1.04 (1.52)", "0.72"),
    ("S", 9): (1489524, "2.52 (3.67)", "1.73 (2.52)", "1.61 (2.35)", "1.23 (1.79)", "1.60"),
    ("V", 7): (134747, "2.06 (3.00)", "1.44 (2.10)", "1.20 (1.74)", "1.00 (1.46)", "0.25"),
    ("V", 8): (560410, "2.36 (3.43)", "1.67 (2.44)", "1.45 (2.11)", "1.13 (1.65)", "0.45"),
    ("V", 9): (1280668, "2.74 (4.00)", "1.95 (2.84)", "1.81 (2.64)", "1.32 (1.92)", "1.25"),
    ("molecule", 9): (675672, "4.69 (3.17)", "2.36 (1.60)", "1.97 (1.33)", "2.14 (1.45)", "–"),
}
# The paper's image area (rays) per scene key; the isosurfaces' otherwise.
PAPER_RAYS = {"molecule": 1477514, "city": 1639389}
# Rows of the paper's table whose source does not exist yet: shown as pending unless a scene
# with that key is present.
PENDING = {"V": "isosurface V (sound speed: ocean issue)", "city": "city 7-9 .. 10-12 (city issue)",
           "molecule": "molecule (paper B issue)"}


def use_scratch(args, tmp):
    """Sets the folder scene_input writes DICOM series into (created) and forgets what it wrote."""
    args.written = set()
    args.tmp = tmp
    os.makedirs(tmp, exist_ok=True)


def scene_input(args, scene):
    """The path octrace renders: the data file, or the DICOM series written from it (write_dicom)."""
    source = os.path.join(args.data, scene["input"])
    w = scene.get("write_dicom")
    if not w:
        return source
    folder = os.path.join(args.tmp, "dicom_%s_%s_%s" % (os.path.basename(scene["input"]), w.get("modality", "CT"),
                                                         w.get("rescale", "1,0")))
    if folder not in args.written:
        shutil.rmtree(folder, ignore_errors=True)
        subprocess.run([args.write_dicom, source, folder, "--modality", w.get("modality", "CT"),
                        "--rescale", w.get("rescale", "1,0")], check=True)
        args.written.add(folder)
    return folder


def run(args, scene, depth, renderer, threads, verify, outdir, extra=(), tag_suffix=""):
    """One cell: its stats JSON (rendered unless a row not asked for). `extra`: further options
    (e.g. bench/branch_up.py's --branch-up), with `tag_suffix` added to the file names."""
    tag = "%s_d%d_%s_t%d%s" % (scene["key"], depth, renderer.replace("+", "_"), threads, tag_suffix)
    stats = os.path.join(outdir, tag + ".json")
    if (args.only and scene["key"] not in args.only) or (args.renderers and renderer not in args.renderers):
        if not os.path.exists(stats):
            return None  # a row not asked for and never measured: left out of the table
        with open(stats) as f:
            return json.load(f)
    cmd = [args.octrace, "render", scene_input(args, scene)]
    for key, opt in (("var", "--var"), ("iso", "--iso"), ("region", "--region")):
        if key in scene:
            cmd += [opt, str(scene[key])]
    cmd += [scene.get("depth_option", "--depth"), str(depth)] + scene.get("args", [])
    cmd += ["--size", scene["size"], "--camera-pos", scene["camera_pos"], "--look-at", scene["look_at"],
           "--up", scene["up"], "--fov", str(scene["fov"]), "--renderer", renderer,
           "--threads", str(threads), "--repeat", str(args.repeat), "--stats", stats, "--quiet",
           "-o", os.path.join(args.tmp, tag + ".png")] + list(extra)
    if verify:
        cmd.append("--verify")
    if renderer != "full":
        cmd += ["--baseline", "full"]
    subprocess.run(cmd, check=True)
    with open(stats) as f:
        return json.load(f)


def table1_scenes():
    """The scene files of bench/scenes/ marked "table1", each with its "file" (relative path)."""
    scenes = []
    for path in sorted(glob.glob(os.path.join(ROOT, "bench", "scenes", "*.json"))):
        with open(path) as f:
            s = json.load(f)
        if s.get("table1"):
            s["file"] = os.path.relpath(path, ROOT)
            scenes.append(s)
    return scenes


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--octrace", default=os.path.join(ROOT, "build", "app", "octrace"))
    ap.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data"))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--quick", action="store_true", help="depth 7 only (a smoke run; does not write the table)")
    ap.add_argument("--scenes", default="", help="comma-separated scene keys to run (default: all)")
    ap.add_argument("--renderers", default="",
                    help="comma-separated renderers to run (default: all); the others' cells are read from the raw JSON")
    ap.add_argument("--write-dicom", default=os.path.join(ROOT, "build", "octrace_write_dicom"),
                    help="the DICOM series writer, for scenes with write_dicom")
    args = ap.parse_args()
    args.written = set()
    args.only = [k for k in args.scenes.split(",") if k]
    args.renderers = [r for r in args.renderers.split(",") if r]
    args.tmp = "/tmp/octrace-table1"
    os.makedirs(args.tmp, exist_ok=True)
    outdir = os.path.join(ROOT, "docs", "benchmarks", "table1")
    os.makedirs(outdir, exist_ok=True)

    scenes = table1_scenes()
    order = {k: i for i, k in enumerate(["T", "V", "S"])}
    scenes.sort(key=lambda s: (order.get(s["key"], len(order)), s["key"]))

    results = {}
    unmeasured = []
    for s in list(scenes):
        cells = [(depth, r, threads) for depth in ([7] if args.quick else s["depths"]) for threads in (1, 2)
                 for r in RENDERERS + DIRECT]
        if (args.only and s["key"] not in args.only or args.renderers) and not all(
                os.path.exists(os.path.join(outdir, "%s_d%d_%s_t%d.json" % (s["key"], d, r.replace("+", "_"), t)))
                for d, r, t in cells):
            unmeasured.append(s["name"])
            scenes.remove(s)
            continue
        for depth in ([7] if args.quick else s["depths"]):
            for threads in (1, 2):
                for r in RENDERERS + DIRECT:
                    results[(s["key"], depth, r, threads)] = run(args, s, depth, r, threads, threads == 1, outdir)
                    print("%s depth %d %-13s threads %d: %.1f ms" % (s["key"], depth, r, threads,
                          results[(s["key"], depth, r, threads)]["render_ms"]), flush=True)
    crossover = {}
    for s in scenes:
        if s["key"] != "T" or args.quick:
            continue
        for depth in CROSSOVER_DEPTHS:
            for r in DIRECT:
                crossover[(depth, r)] = (results.get((s["key"], depth, r, 1)) or
                                         run(args, s, depth, r, 1, False, outdir))
                print("crossover depth %d %s: %.2fx over full" % (depth, r, crossover[(depth, r)]["speedup_over_baseline"]),
                      flush=True)
    if args.quick:
        return 0

    L = []
    L.append("# Paper A's Table 1, reproduced\n")
    L.append("Generated by `bench/table1.py` (do not edit by hand); raw stats JSON of every run in")
    L.append("[`table1/`](table1/). Scenes and fixed cameras (`bench/scenes/`), 1600x1200:\n")
    for sc in scenes:
        L.append("- %s (`%s`): %s" % (sc["name"], sc["file"], sc.get("description", "")))
    L.append("")
    L.append("Rays meeting the scene cube: for the ocean scenes about the paper's 685,729 (its city and")
    L.append("molecule images: 1,639,389 and 1,477,514). Each time is the fastest of %d renders in one process (`--repeat %d`); the machine is a" % (args.repeat, args.repeat))
    L.append("shared 2-core VM, so read the ratios to `full` (same scene, depth, thread count, same")
    L.append("invocation) rather than the absolute times. Paper: Athlon 1800, 2006.\n")
    if args.renderers:
        L.append("The last run (`--renderers %s`) measured only %s, each against `full` in its own" % (
            ",".join(args.renderers), ", ".join("`%s`" % r for r in args.renderers)))
        L.append("process; the other cells are those of the raw JSON of an earlier run.\n")
    for threads in (1, 2):
        L.append("## %s\n" % ("Single thread" if threads == 1 else "2 threads"))
        L.append("Time in seconds (us per ray). Paper's figures in the second line of each row.\n")
        L.append("| scene | depth | boundary voxels | rays | " + " | ".join(RENDERERS + DIRECT) + " |")
        L.append("|---|---|---|---|" + "---|" * len(RENDERERS + DIRECT))
        for s in scenes:
            for depth in s["depths"]:
                first = results[(s["key"], depth, "full", threads)]
                cells = []
                for r in RENDERERS:
                    d = results[(s["key"], depth, r, threads)]
                    cells.append("%.3f (%.3f)" % (d["render_ms"] / 1000.0, d["us_per_ray"]))
                for r in DIRECT:
                    cells.append("%.3f" % (results[(s["key"], depth, r, threads)]["render_ms"] / 1000.0))
                L.append("| %s | %d | %s | %s | %s |" % (s["name"], depth, format(first["boundary_voxels"], ","),
                         format(first["rays"], ","), " | ".join(cells)))
                p = PAPER.get((s["key"], depth))
                if p:
                    L.append("| *paper* | | *%s* | *%s* | *%s* | *%s* | *%s* | *%s* | | | *%s* | |" % (
                        format(p[0], ","), format(PAPER_RAYS.get(s["key"], 685729), ","), p[1], p[2], p[3], p[4], p[5]))
        L.append("")
        L.append("Speed-up over `full`: `full` rendered alternately with the renderer in the same process")
        L.append("(`--baseline full`), fastest of each, full / renderer:\n")
        L.append("| scene | depth | " + " | ".join(RENDERERS[1:] + DIRECT) + " |")
        L.append("|---|---|" + "---|" * (len(RENDERERS) - 1 + len(DIRECT)))
        for s in scenes:
            for depth in s["depths"]:
                L.append("| %s | %d | %s |" % (s["name"], depth, " | ".join(
                    "%.2fx" % results[(s["key"], depth, r, threads)]["speedup_over_baseline"]
                    for r in RENDERERS[1:] + DIRECT)))
        L.append("")
    L.append("## Exactness (single-thread runs, `--verify`)\n")
    L.append("`mismatched` = traced pixels whose hit voxel differs from the exact reference (the same as")
    L.append("`full`); for `area+colour` the colour-filled pixels are judged by the image difference instead.")
    L.append("`certified` = exact variants: rays whose start at the branch node was proven safe (the tile")
    L.append("frontier certificate of docs/dev/coherence.md, since 2026-11-28; before, only the structural")
    L.append("test). `miss-filled` = pixels taken as background because both partners missed (miss")
    L.append("coherence): untraced by the approximate variants (`--miss-coherence`), and by the exact ones")
    L.append("only where the tile frontier proves the miss (since 2026-11-28); - = measured before it existed.")
    L.append("PSNR against the reference image (inf = identical).\n")
    L.append("`hit agreement` = of the pixels that either hits, the share both hit; `depth error` = largest")
    L.append("depth difference where both hit, in voxel diagonals.\n")
    L.append("| scene | depth | renderer | common-path rays | fallbacks | certified | colour-filled | miss-filled | mismatched (%) | PSNR dB | max channel error | hit agreement | depth error |")
    L.append("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for s in scenes:
        for depth in s["depths"]:
            for r in RENDERERS + DIRECT:
                d = results[(s["key"], depth, r, 1)]
                psnr = d.get("psnr_db")
                L.append("| %s | %d | %s | %s | %s | %s | %s | %s | %d (%.4f%%) | %s | %d | %.6f | %.3f |" % (
                    s["name"], depth, r, format(d["rays_common_path"], ","), format(d["fallbacks"], ","),
                    format(d["rays_certified"], ","), format(d["colour_filled"], ","),
                    format(d["miss_filled"], ",") if "miss_filled" in d else "-", d["mismatched_pixels"],
                    100.0 * d["mismatched_pixels"] / d["pixels"], "inf" if psnr is None else "%.1f" % psnr,
                    d["max_channel_error"], d["hit_agreement"], d["depth_max_error_voxel_diagonals"]))
    L.append("")
    if crossover:
        L.append("## Direct against ray casting by depth (scene T, single thread)\n")
        L.append("Speed-up of the direct renderers over `full` (alternating in one process); below 1 ray")
        L.append("casting wins. The direct renderers draw every boundary voxel (back to front) or every")
        L.append("unoccluded one (front to back), so their time grows with the voxel count, about 4x per")
        L.append("level, while a ray's cost grows by one node per level.\n")
        L.append("| depth | boundary voxels | full s | direct s | direct-f2b s | direct / full | direct-f2b / full |")
        L.append("|---|---|---|---|---|---|---|")
        cross = {r: None for r in DIRECT}
        for depth in CROSSOVER_DEPTHS:
            a, b = crossover[(depth, "direct")], crossover[(depth, "direct-f2b")]
            for r, d in (("direct", a), ("direct-f2b", b)):
                if cross[r] is None and d["speedup_over_baseline"] < 1.0:
                    cross[r] = depth
            L.append("| %d | %s | %.3f | %.3f | %.3f | %.2fx | %.2fx |" % (
                depth, format(a["boundary_voxels"], ","), a["baseline_render_ms"] / 1000.0, a["render_ms"] / 1000.0,
                b["render_ms"] / 1000.0, a["speedup_over_baseline"], b["speedup_over_baseline"]))
        L.append("")
        for r in DIRECT:
            L.append("- `%s`: %s" % (r, "ray casting (`full`) is faster from depth %d on." % cross[r] if cross[r]
                                      else "faster than `full` at every depth measured (up to %d)." % CROSSOVER_DEPTHS[-1]))
        L.append("")
    pending = [text for key, text in PENDING.items() if not any(s["key"].startswith(key) for s in scenes)]
    pending += ["%s (scene file present, not measured yet)" % n for n in unmeasured]
    if pending:
        L.append("Rows not reproduced yet: " + "; ".join(pending) + ".")
    with open(os.path.join(ROOT, "docs", "benchmarks", "table1.md"), "w") as f:
        f.write("\n".join(L) + "\n")
    print("wrote docs/benchmarks/table1.md")
    return 0


if __name__ == "__main__":
    sys.exit(main())
