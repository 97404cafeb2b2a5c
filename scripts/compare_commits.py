#!/usr/bin/env python3
"""Builds octrace at two commits and checks that they draw the same bytes.

    python3 scripts/compare_commits.py BEFORE AFTER [--renderers full,area+colour,direct,samet]
                                       [--size 640x480] [--work DIR] [--json OUT.json]

For a change that must not change what octrace draws (a refactor): each commit is exported
with `git archive` into WORK/src-SHA and its `octrace` executable built in WORK/build-SHA
(Release, no tests, no studio; kept, so that a second comparison against the same commit does
not build it again). Then every scene of Paper A's Table 1 (bench/scenes/*.json with "table1": the
ocean T, V and S isosurfaces, CT bone and skin, the two city scenes, the molecule) at its
shallowest depth, with the scene's own camera at --size, plus a CT (the LIDC chest at iso 100)
and a city (Delft) framed by default, are rendered by both executables with each renderer to
PNG and to EXR, and the files are compared byte for byte. The CT scenes of Table 1 are written as
a DICOM series first, as bench/table1.py does (by the AFTER commit's octrace_write_dicom), and the
molecule is voxelized (--octree voxel) so that every renderer draws it.

Prints one line per image and a summary; with --json writes every comparison. Exit 0 when every
pair is byte-identical, 1 when any differs or failed, 2 for a usage error.
"""
import argparse
import filecmp
import glob
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def sha_of(commit):
    return subprocess.run(["git", "-C", ROOT, "rev-parse", "--verify", commit + "^{commit}"], check=True,
                          capture_output=True, text=True).stdout.strip()


def build(sha, work):
    """The octrace executable of commit `sha`, built once into WORK/build-SHA."""
    src = os.path.join(work, "src-" + sha[:12])
    out = os.path.join(work, "build-" + sha[:12])
    exe = os.path.join(out, "app", "octrace")
    if not os.path.isdir(src):
        os.makedirs(src)
        archive = subprocess.Popen(["git", "-C", ROOT, "archive", sha], stdout=subprocess.PIPE)
        subprocess.run(["tar", "-x", "-C", src], stdin=archive.stdout, check=True)
        if archive.wait() != 0:
            raise SystemExit("compare: git archive %s failed" % sha)
    print("compare: building %s in %s (nothing to do when it was built before)" % (sha[:12], out), flush=True)
    if not os.path.exists(os.path.join(out, "build.ninja")):
        subprocess.run(["cmake", "-S", src, "-B", out, "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                        "-DOCTRACE_BUILD_TESTS=OFF", "-DOCTRACE_BUILD_STUDIO=OFF", "-DOCTRACE_BUILD_BENCH=OFF"],
                       check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["ninja", "-C", out, "octrace", "octrace_write_dicom"], check=True)
    return exe


def scene_input(data, scene, writer, work):
    """The scene's input; a scene with "write_dicom" (Table 1's CT rows) is written as a DICOM
    series first by the project's writer, as bench/table1.py does, so that its values are HU."""
    source = os.path.join(data, scene["input"])
    w = scene.get("write_dicom")
    if not w:
        return source
    folder = os.path.join(work, "dicom_%s_%s" % (os.path.basename(scene["input"]), w.get("rescale", "1,0").replace(",", "_")))
    if not os.path.isdir(folder):
        subprocess.run([writer, source, folder, "--modality", w.get("modality", "CT"), "--rescale", w.get("rescale", "1,0")],
                       check=True, stdout=subprocess.DEVNULL)
    return folder


def scenes(data, size, writer, work):
    """(name, octrace render arguments without -o and --renderer)."""
    out = []
    for path in sorted(glob.glob(os.path.join(ROOT, "bench", "scenes", "*.json"))):
        with open(path) as f:
            s = json.load(f)
        if not s.get("table1"):
            continue
        depth = min(s["depths"])
        args = [scene_input(data, s, writer, work)]
        if s["input"].endswith((".pdb", ".cif")):
            args += ["--octree", "voxel"]  # Table 1 draws the molecule voxelized, with every renderer
        for key in ("var", "iso", "region"):
            if key in s:
                args += ["--" + key, str(s[key])]
        args += [s.get("depth_option", "--depth"), str(depth)] + s.get("args", [])
        args += ["--camera-pos", s["camera_pos"], "--look-at", s["look_at"], "--up", s["up"], "--fov", str(s["fov"])]
        out.append(("%s_d%d" % (s["key"], depth), args + ["--size", size]))
    out.append(("ct-chest", [os.path.join(data, "medical", "lidc2_chest_ct.nrrd"), "--iso", "100", "--size", size]))
    out.append(("city-delft", [os.path.join(data, "city", "delft.json"), "--depth", "9", "--size", size]))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("before")
    ap.add_argument("after")
    ap.add_argument("--renderers", default="full,area+colour,direct,samet")
    ap.add_argument("--size", default="640x480")
    ap.add_argument("--threads", default="2")
    ap.add_argument("--data", default=os.path.join(ROOT, "..", "shared", "data"))
    ap.add_argument("--work", default=os.path.join(os.path.expanduser("~"), ".cache", "octrace-compare"))
    ap.add_argument("--json", help="write every comparison here")
    args = ap.parse_args()
    if not os.path.isdir(args.data):
        ap.error("no data folder %s (give --data)" % args.data)
    try:
        before, after = sha_of(args.before), sha_of(args.after)
    except subprocess.CalledProcessError as e:
        ap.error("not a commit: %s" % e.stderr.strip())
    os.makedirs(args.work, exist_ok=True)
    exes = {before: build(before, args.work), after: build(after, args.work)}
    images = os.path.join(args.work, "images-%s-%s" % (before[:12], after[:12]))
    os.makedirs(images, exist_ok=True)
    results = []
    writer = os.path.join(os.path.dirname(os.path.dirname(exes[after])), "octrace_write_dicom")
    for name, scene_args in scenes(args.data, args.size, writer, args.work):
        for renderer in args.renderers.split(","):
            for ext in ("png", "exr"):
                files, failed = {}, None
                for sha in (before, after):
                    out = os.path.join(images, "%s_%s_%s.%s" % (name, renderer.replace("+", "_"), sha[:12], ext))
                    cmd = [exes[sha], "render"] + scene_args + ["--renderer", renderer, "--threads", args.threads,
                                                                "--quiet", "-o", out]
                    r = subprocess.run(cmd, capture_output=True, text=True)
                    if r.returncode != 0:
                        failed = "%s exit %d: %s" % (sha[:12], r.returncode, (r.stderr.strip().splitlines() or [""])[0])
                        break
                    files[sha] = out
                same = failed is None and filecmp.cmp(files[before], files[after], shallow=False)
                results.append({"scene": name, "renderer": renderer, "format": ext, "identical": same,
                                "error": failed, "bytes": os.path.getsize(files[after]) if same else None})
                print("%-22s %-12s %-4s %s" % (name, renderer, ext, "identical" if same else failed or "DIFFERENT"),
                      flush=True)
    differing = [r for r in results if not r["identical"]]
    print("compare: %s -> %s: %d images, %d identical, %d differ or failed" % (
        before[:12], after[:12], len(results), len(results) - len(differing), len(differing)))
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"before": before, "after": after, "size": args.size, "renderers": args.renderers.split(","),
                       "images": results}, f, indent=1)
    return 1 if differing else 0


if __name__ == "__main__":
    sys.exit(main())
