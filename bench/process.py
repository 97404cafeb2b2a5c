#!/usr/bin/env python3
"""Generates docs/benchmarks/process.md: what a user of the command line waits for, the whole
`octrace render` process (start-up, reading, building, the frame, encoding and writing the PNG),
beside a baseline build of octrace in the same run. Raw JSON in docs/benchmarks/process/.

Each case is run --runs times per binary, the binaries alternating (which goes first alternates
too); each figure is the fastest run (the machine is shared). Per run: the wall time from the spawn to the exit, the process's
CPU time (user + system, from the kernel's accounting of the finished child), and the parts the
stats JSON reports (load_ms, build_ms, render_ms); `rest` is the wall time outside them: the
dynamic loader and the libraries' start-up, parsing, encoding and writing the image, the exit.

Cases: `octrace --version` (start-up alone); the Table 1 isosurface T from its depth-9 octree
file (written by `octrace build` first) at octrace's default view, 1600x1200, 2 threads; and the
same surface built from the Levitus NetCDF file (the first command of the README's tour).

Usage: bench/process.py [--octrace PATH] [--baseline PATH --baseline-label TEXT] [--data DIR] [--runs N]
"""
import json
import os
import resource
import subprocess
import tempfile
import time

from benchcommon import ROOT, field_args, load, parser, raw_dir


def timed(cmd):
    """Runs CMD; returns (wall seconds, CPU seconds of the child)."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - t
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def main():
    ap = parser(__doc__)
    ap.add_argument("--baseline", help="another octrace binary, run alternately with --octrace")
    ap.add_argument("--baseline-label", default="baseline", help="what the page calls the baseline (e.g. its commit)")
    ap.add_argument("--label", default="this tree's build", help="what the page calls --octrace")
    ap.add_argument("--runs", type=int, default=7)
    args = ap.parse_args()
    outdir = raw_dir("process")
    tmp = tempfile.mkdtemp(prefix="octrace-process-")
    scene = load(os.path.join(ROOT, "bench", "scenes", "levitus_T.json"))
    field = field_args(scene, args.data) + ["--depth", "9"]
    oct_file = os.path.join(tmp, "T9.oct")
    subprocess.run([args.octrace, "build"] + field + ["--quiet", "-o", oct_file], check=True)
    png = os.path.join(tmp, "out.png")
    common = ["--size", "1600x1200", "--threads", "2", "--quiet", "-o", png]
    cases = [("start-up (`octrace --version`)", "version", ["--version"]),
             ("T from its depth-9 octree file", "oct", ["render", oct_file] + common),
             ("T from the Levitus NetCDF file (depth 9)", "netcdf", ["render"] + field + common)]
    binaries = [(args.label, args.octrace)] + ([(args.baseline_label, args.baseline)] if args.baseline else [])
    if args.baseline and args.label == args.baseline_label:
        ap.error("--label and --baseline-label must differ")
    runs = {(c[1], b[0]): [] for c in cases for b in binaries}
    for r in range(args.runs):
        for _, key, argv in cases:
            # Alternating, and which goes first alternates too (the second run of a pair finds the
            # input warmer).
            for label, exe in (binaries if r % 2 == 0 else binaries[::-1]):
                stats = os.path.join(tmp, "stats.json")
                if os.path.exists(stats):
                    os.remove(stats)  # a run that wrote none must not read the one before's
                cmd = [exe] + argv + (["--stats", stats] if key != "version" else [])
                load0 = os.getloadavg()[0]
                wall, cpu = timed(cmd)
                rec = {"round": r + 1, "wall_ms": wall * 1e3, "cpu_ms": cpu * 1e3, "load_avg_1min": round(load0, 2)}
                if key != "version":
                    st = load(stats)
                    for k in ("load_ms", "build_ms", "render_ms"):
                        rec[k] = st.get(k, 0.0)
                    rec["rest_ms"] = rec["wall_ms"] - rec["load_ms"] - rec["build_ms"] - rec["render_ms"]
                    rec["png_bytes"] = os.path.getsize(png)
                runs[(key, label)].append(rec)
    fastest = {}
    for (key, label), recs in runs.items():
        best = min(recs, key=lambda x: x["wall_ms"])
        fastest[(key, label)] = {"fastest_wall": best, "min_cpu_ms": min(x["cpu_ms"] for x in recs)}
        with open(os.path.join(outdir, "%s_%s.json" % (key, "baseline" if label == args.baseline_label and args.baseline
                                                         else "octrace")), "w") as f:
            json.dump({"binary": dict(binaries)[label], "label": label, "runs": recs, **fastest[(key, label)]}, f, indent=2)
            f.write("\n")

    loads = [x["load_avg_1min"] for recs in runs.values() for x in recs]
    md = ["# The whole command: what a user of the CLI waits for", "",
          "Generated by `bench/process.py` (raw JSON in `docs/benchmarks/process/`); do not edit by hand.", "",
          "Each row is the fastest of %d runs of the whole process, the binaries alternating; CPU is the fastest run's"
          " user + system time. `load`, `build` and `render` are the stats JSON's; `rest` is the wall time outside them"
          " (start-up: the dynamic loader and the libraries' initialization; parsing; encoding and writing the PNG;"
          " the exit). 1600x1200, 2 threads, octrace's default view; 1-minute load average %.2f to %.2f." % (
              args.runs, min(loads), max(loads)), "",
          "| case | binary | wall | CPU | load | build | render | rest | PNG |", "|---|---|---|---|---|---|---|---|---|"]
    for title, key, _ in cases:
        for label, _ in binaries:
            f = fastest[(key, label)]
            b = f["fastest_wall"]
            part = (lambda k: "%.1f ms" % b[k]) if key != "version" else (lambda k: "-")
            md.append("| %s | %s | %.0f ms | %.0f ms | %s | %s | %s | %s | %s |" % (
                title, label, b["wall_ms"], b["cpu_ms"], part("load_ms"), part("build_ms"), part("render_ms"),
                part("rest_ms"), "%.0f KB" % (b["png_bytes"] / 1e3) if key != "version" else "-"))
    if args.baseline:
        md += ["", "Wall time, %s / %s (fastest runs):" % (args.baseline_label, args.label), ""]
        for title, key, _ in cases:
            a, b = fastest[(key, args.label)]["fastest_wall"], fastest[(key, args.baseline_label)]["fastest_wall"]
            md.append("* %s: %.0f ms / %.0f ms = %.2fx." % (title, b["wall_ms"], a["wall_ms"], b["wall_ms"] / a["wall_ms"]))
    with open(os.path.join(ROOT, "docs", "benchmarks", "process.md"), "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
