#!/usr/bin/python3
"""CTest BenchPlots.*: the benchmark plots are redrawn from the committed raw JSON alone.

For bench/figure5.py, bench/figure5_2d.py and bench/molecules.py: `--plot-only` into a temporary folder must exit 0
and write a PNG whose plot shows both scenes' colours and whose caption band holds text, and a
Markdown identical to the committed one (the committed page is what its committed JSON gives).
A raw folder without its JSON must be refused, naming the missing file.
Runs with the interpreter that has matplotlib (Debian's python3-matplotlib: /usr/bin/python3).

Usage: check_plots.py figure5|figure5_2d|molecules"""
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BENCH = os.path.join(ROOT, "bench")
DOCS = os.path.join(ROOT, "docs", "benchmarks")
# script, its raw folder, the page it writes, the raw JSON whose absence must be refused
CASES = {"figure5": ("figure5.py", "figure5", "figure5", "sphereflake_s4.json"),
         "figure5_2d": ("figure5_2d.py", "figure5-2d", "figure5-2d", "figure5_2d.json"),
         "molecules": ("molecules.py", "molecules", "molecules", "4hhb_s4.json")}
SCENE_COLOURS = ["#c0392b", "#1f5fb4"]  # bench/benchplot.py's first two


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def plot_only(script, raw, out):
    return subprocess.run([sys.executable, os.path.join(BENCH, script), "--plot-only", "--raw", raw, "--out", out],
                          capture_output=True, text=True)


def check_png(path):
    import numpy as np
    from matplotlib import image
    with open(path, "rb") as f:
        if f.read(8) != b"\x89PNG\r\n\x1a\n":
            fail("%s is not a PNG" % path)
    rgb = (image.imread(path)[:, :, :3] * 255).round().astype(int)
    h, w, _ = rgb.shape
    if w < 800 or h < 400:
        fail("%s is %dx%d, expected at least 800x400" % (path, w, h))
    for c in SCENE_COLOURS:
        want = np.array([int(c[i:i + 2], 16) for i in (1, 3, 5)])
        n = int((np.abs(rgb - want).max(axis=2) <= 8).sum())
        if n < 500:
            fail("%s: only %d pixels of the scene colour %s: a series is missing" % (path, n, c))
    caption = rgb[int(h * 0.94):, :, :]
    dark = int((caption.max(axis=2) < 100).sum())
    if dark < 200:
        fail("%s: the caption band (bottom 6%%) holds %d dark pixels: no caption line" % (path, dark))
    print("ok: %s (%dx%d)" % (path, w, h))


def main():
    if len(sys.argv) != 2 or sys.argv[1] not in CASES:
        fail("usage: check_plots.py " + "|".join(CASES))
    script, raw_name, page, one_json = CASES[sys.argv[1]]
    raw = os.path.join(DOCS, raw_name)
    with tempfile.TemporaryDirectory() as out:
        r = plot_only(script, raw, out)
        if r.returncode != 0:
            fail("%s --plot-only exited %d: %s" % (script, r.returncode, r.stderr.strip()))
        check_png(os.path.join(out, page + ".png"))
        with open(os.path.join(out, page + ".md")) as f, open(os.path.join(DOCS, page + ".md")) as g:
            if f.read() != g.read():
                fail("docs/benchmarks/%s.md differs from what %s --plot-only writes from the committed JSON: "
                     "regenerate it with bench/%s --plot-only" % (page, script, script))
        print("ok: docs/benchmarks/%s.md is what the committed JSON gives" % page)

        broken = os.path.join(out, "raw")
        shutil.copytree(raw, broken)
        os.remove(os.path.join(broken, one_json))
        r = plot_only(script, broken, os.path.join(out, "broken"))
        if r.returncode == 0 or one_json not in r.stderr:
            fail("%s --plot-only without %s: exit %d, stderr %r; expected a refusal naming the file" % (
                script, one_json, r.returncode, r.stderr))
        print("ok: refused without %s: %s" % (one_json, r.stderr.strip()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
