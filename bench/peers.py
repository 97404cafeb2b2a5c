#!/usr/bin/env python3
"""Peers on octrace's own scenes: runs VTK and OpenVDB on the same fields, cameras and image size
as octrace, in the same run, and writes docs/benchmarks/peers.md (generated; every run's raw JSON
and the images beside it in docs/benchmarks/peers/), with the ratios peer time / octrace time.

Install the peers (Debian bookworm packages, as root):

    apt-get update
    apt-get install -y python3-numpy python3-netcdf4 python3-vtk9 xvfb python3-openvdb libopenvdb-tools \
                       libembree-dev zlib1g-dev g++

Usage: bench/peers.py [--octrace PATH] [--data DIR] [--python /usr/bin/python3] [--depth D]
                      [--scenes levitus_T,levitus_S,spheres]

Scenes: bench/scenes/NAME.json, each at its deepest depth unless --depth is given. The ocean
scenes (levitus_T, levitus_S; depth 9) read a NetCDF file of the data folder; `spheres` (issue
23's scene of many spheres of different sizes: octrace's analytic field `spheres` on 192^3 samples,
depth 8, at octrace's default framing) is an analytic input, whose samples the peers read from the
NRRD that `octrace sample` writes (bench/peers/field.py).

Every program's render time is its fastest frame of 7 after a first (octrace: the fastest of 8
renders in one process; its first pays the frame's allocation), so that the noise of a shared
machine slows none of them more than the others.

* octrace: `octrace render ... --renderer full --threads N --repeat 8 --stats` for N = 1, 2;
  render_ms = the fastest of the 8 renders (build excluded, reported separately). `full` draws
  the boundary voxels' boxes (`--surface voxel`, the papers' renderers' default); the same with
  `--surface smooth` (the field's trilinear interpolant, docs/dev/smooth-surfaces.md) is run too,
  and the default renderer `tile` in both surface modes (smooth is its default for fields).
* VTK (python3-vtk9, xvfb): flying edges on the field, then VTK's OpenGL renderer on Mesa's
  llvmpipe (a CPU rasterizer) under Xvfb; two fields: the file's samples themselves ("native")
  and the field octrace classifies, the trilinear field at the corners of its depth-N voxel
  lattice ("lattice"). Threads: vtkSMPTools and LP_NUM_THREADS = N. Render time = the fastest of 7
  frames after the first, each ended by glFinish (the median is kept in the raw JSON). bench/peers/vtk_peer.py, isomesh.py.
* OpenVDB (python3-openvdb, libopenvdb-tools): the lattice isosurface mesh turned into a narrow-band
  level set with voxels of octrace's size (pyopenvdb createLevelSetFromPolygons; built pinned to
  N CPUs with taskset, as pyopenvdb has no thread setting), written as .vdb and drawn by
  `vdb_render` with `-cpus N`; render time = vdb_render's own ray-tracing time
  (`-v`), the fastest of 3 runs. bench/peers/vdb_peer.py.
* Embree 3 (libembree-dev, needs VTK for the mesh): bench/peers/embree_peer.cpp, compiled here
  with the system C++ compiler, traces VTK's lattice mesh (dumped by vtk_peer.py) at the same
  camera with rtcIntersect16 packets of 4x4 pixels (coherent context) over 8x8-pixel tiles on N
  threads; BVH build (quality high) = preparation; render = the fastest of 7 frames after a first.
* Normals (needs VTK): the normal each program shades every pixel with, octrace's (voxel and
  smooth: six frames lit from six camera-space directions, --ambient 0 --colour 1,1,1, EXR) against
  VTK's (the flying-edges mesh coloured by its interpolated point normals), and the angle between
  them over the pixels both draw as surface. bench/peers/normals.py.
The Python helpers run under Debian's /usr/bin/python3 (the interpreter the Debian modules are
installed for), whatever interpreter runs this script. A peer that is not installed is skipped,
and peers.md says which and why.
"""
import argparse
import datetime
import hashlib
import json
import math
import os
import platform
import re
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HERE = os.path.join(ROOT, "bench", "peers")
APT = "apt-get install -y python3-numpy python3-netcdf4 python3-vtk9 xvfb python3-openvdb libopenvdb-tools libembree-dev zlib1g-dev g++"
EMBREE_FRAMES = 7
THREADS = (1, 2)
OCTRACE_REPEAT = 8  # the first render and 7 more: the peers' frames after a first
VDB_REPEAT = 3
VTK_FRAMES = 7
TASKSET = shutil.which("taskset")


def log(msg):
    print("peers: " + msg, file=sys.stderr, flush=True)


def run(cmd, env=None, check=True):
    t = time.perf_counter()
    p = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t
    if check and p.returncode != 0:
        raise RuntimeError("command failed (%d): %s\n%s%s" % (p.returncode, " ".join(cmd), p.stdout[-3000:],
                                                             p.stderr[-3000:]))
    return p, wall


def probe(python, code):
    try:
        p = subprocess.run([python, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    except OSError as e:
        return False, str(e)
    if p.returncode == 0:
        return True, p.stdout.strip()
    last = (p.stderr.strip().splitlines() or ["failed"])[-1]
    return False, last


def detect(python):
    """Which peers can run: {name: (ok, reason or version)}."""
    have = {}
    if not os.path.exists(python):
        reason = "%s not found (Debian's python3)" % python
        return {"vtk": (False, reason), "openvdb": (False, reason), "embree": (False, reason)}, {}
    ok_np, why_np = probe(python, "import numpy, netCDF4; print(numpy.__version__, netCDF4.__version__)")
    ok_vtk, why_vtk = probe(python, "import vtk; print(vtk.vtkVersion.GetVTKVersion())")
    ok_vdb, why_vdb = probe(python, "import pyopenvdb as v; print('.'.join(map(str, v.LIBRARY_VERSION)))")
    xvfb = shutil.which("xvfb-run")
    vdb_render = shutil.which("vdb_render")
    versions = {"numpy_netCDF4": why_np if ok_np else None, "vtk": why_vtk if ok_vtk else None,
                "pyopenvdb": why_vdb if ok_vdb else None}
    missing = []
    if not ok_np:
        missing.append("python3-numpy/python3-netcdf4 (%s)" % why_np)
    if not ok_vtk:
        missing.append("python3-vtk9 (%s)" % why_vtk)
    if not xvfb:
        missing.append("xvfb (xvfb-run not on PATH)")
    have["vtk"] = (not missing, "; ".join(missing) if missing else "VTK " + why_vtk)
    missing = []
    if not ok_np:
        missing.append("python3-numpy/python3-netcdf4 (%s)" % why_np)
    if not ok_vtk:
        missing.append("python3-vtk9, which makes the mesh the level set is built from (%s)" % why_vtk)
    if not ok_vdb:
        missing.append("python3-openvdb (%s)" % why_vdb)
    if not vdb_render:
        missing.append("libopenvdb-tools (vdb_render not on PATH)")
    have["openvdb"] = (not missing, "; ".join(missing) if missing else "OpenVDB " + why_vdb)
    missing = []
    if not (ok_np and ok_vtk and xvfb):
        missing.append("VTK, which makes the mesh Embree traces (%s)" % have["vtk"][1])
    if not os.path.exists("/usr/include/embree3/rtcore.h"):
        missing.append("libembree-dev (/usr/include/embree3/rtcore.h not found)")
    if not shutil.which("c++"):
        missing.append("a C++ compiler (g++) to build bench/peers/embree_peer.cpp")
    embree_version = None
    if not missing:
        with open("/usr/include/embree3/rtcore_config.h") as f:
            m = re.search(r'RTC_VERSION_STRING "([^"]+)"', f.read())
            embree_version = m.group(1) if m else "3"
    versions["embree"] = embree_version
    have["embree"] = (not missing, "; ".join(missing) if missing else "Embree " + str(embree_version))
    return have, versions


SURFACES = ("voxel", "smooth")
# Camera-space light directions of the normals step (bench/peers/normals.py).
NORMAL_LIGHTS = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (1, 0, 1), (0, 1, 1)]


def is_analytic(scene):
    return scene["input"].startswith("analytic:")


def scene_input(scene, data):
    """octrace's INPUT for a scene: a file of the data folder, or an analytic field as it is."""
    return scene["input"] if is_analytic(scene) else os.path.join(data, scene["input"])


def scene_depth(args, scene):
    """--depth if given, else the scene's deepest depth (bench/scenes/*.json "depths")."""
    return args.depth if args.depth else max(scene["depths"])


def write_analytic_nrrd(octrace, scene, tmp):
    """The samples of an analytic scene (analytic:NAME[:N]) for the peers, written by `octrace sample`
    as NRRD: the same float32 samples octrace generates for that input (default seed)."""
    parts = scene["input"].split(":")
    path = os.path.join(tmp, "%s.nrrd" % parts[1])
    run([octrace, "sample", parts[1], "-o", path] + (["--samples", parts[2]] if len(parts) > 2 else []))
    return path


def octrace_cmd(octrace, scene, data, depth, threads, stats, png, surface="voxel", repeat=OCTRACE_REPEAT, extra=(),
                renderer="full"):
    fieldopts = [x for key, opt in (("var", "--var"), ("region", "--region")) if key in scene for x in (opt, str(scene[key]))]
    return [octrace, "render", scene_input(scene, data), *fieldopts, "--iso", str(scene["iso"]),
            "--depth", str(depth), "--size", scene["size"],
            "--camera-pos", scene["camera_pos"], "--look-at", scene["look_at"], "--up", scene["up"],
            "--fov", str(scene["fov"]), "--renderer", renderer, "--surface", surface, "--threads", str(threads),
            "--repeat", str(repeat), "--stats", stats, "-o", png, "--quiet", *extra]


def native_label(scene):
    """What the peers' "native" rows mesh: the file's own samples."""
    if is_analytic(scene):
        parts = scene["input"].split(":")
        return "the field's %s^3 samples" % (parts[2] if len(parts) > 2 else "65")
    return "NetCDF samples"


def km(scene):
    """The world unit of a scene's numbers: km for the ocean scenes, none for an analytic field."""
    return "" if is_analytic(scene) else " km"


def hfov_for_vdb(vfov_deg, width, height):
    """vdb_render's -fov is horizontal: its PerspectiveCamera spans tan(hfov/2) = aperture/(2 focal)
    across the image width and that times height/width across the height (RayTracer.h)."""
    return 2.0 * math.degrees(math.atan(math.tan(math.radians(vfov_deg) / 2.0) * width / height))


def fmt_ms(v):
    if v is None:
        return "-"
    return "%.0f" % v if v >= 100 else ("%.1f" % v if v >= 1 else "%.2f" % v)


def fmt_ratio(v):
    if v is None:
        return "-"
    return "%.2f" % v if v < 10 else "%.1f" % v


def run_vtk(args, scene_name, scene, spec, sr, images, outdir, tmp):
    w, h = [int(v) for v in scene["size"].split("x")]
    for grid in ("native", "lattice"):
        for n in THREADS:
            spec_path = os.path.join(tmp, "spec.json")
            mesh_out = os.path.join(tmp, "%s_lattice.mesh" % scene_name) if grid == "lattice" and n == THREADS[0] else None
            with open(spec_path, "w") as f:
                json.dump(dict(spec, grid=grid, threads=n, mesh_out=mesh_out), f)
            out_json = os.path.join(outdir, "%s_vtk_%s_threads%d.json" % (scene_name, grid, n))
            out_png = os.path.join(tmp, "%s_vtk_%s.png" % (scene_name, grid))
            env = dict(os.environ, LP_NUM_THREADS=str(n))
            run(["xvfb-run", "-a", "-s", "-screen 0 %dx%dx24" % (w, h), args.python,
                 os.path.join(HERE, "vtk_peer.py"), spec_path, out_json, out_png], env=env)
            with open(out_json) as f:
                r = json.load(f)
            sr["runs"]["vtk_%s_threads%d" % (grid, n)] = r
            log("%s vtk %s threads %d: extract %.1f ms, render %.1f ms (%d triangles)" % (
                scene_name, grid, n, r["extract_ms"], r["render_ms"], r["triangles"]))
        images["vtk_" + grid] = {"png": out_png, "background": [255, 255, 255]}


def build_embree_peer(tmp):
    exe = os.path.join(tmp, "embree_peer")
    run(["c++", "-O3", "-std=c++17", "-o", exe, os.path.join(HERE, "embree_peer.cpp"), "-lembree3", "-lz", "-lpthread"])
    return exe


def run_embree(args, scene_name, scene, spec, sr, images, outdir, tmp):
    mesh = os.path.join(tmp, "%s_lattice.mesh" % scene_name)
    if not os.path.exists(mesh):
        raise RuntimeError("no lattice mesh from the VTK step to trace")
    exe = os.path.join(tmp, "embree_peer")
    if not os.path.exists(exe):
        build_embree_peer(tmp)
    png = os.path.join(tmp, scene_name + "_embree.png")
    for n in THREADS:
        out_json = os.path.join(outdir, "%s_embree_threads%d.json" % (scene_name, n))
        run([exe, mesh, out_json, png, "--pos", scene["camera_pos"], "--look", scene["look_at"], "--up", scene["up"],
             "--fov", str(scene["fov"]), "--size", scene["size"], "--threads", str(n), "--frames", str(EMBREE_FRAMES)])
        with open(out_json) as f:
            r = json.load(f)
        sr["runs"]["embree_threads%d" % n] = r
        log("%s embree threads %d: BVH %.0f ms, render %.1f ms (%d triangles)" % (
            scene_name, n, r["bvh_build_ms"], r["render_ms"], r["triangles"]))
    images["embree"] = {"png": png, "background": [255, 255, 255]}


def run_helper(args, tmp, helper, job, out_json):
    """Runs bench/peers/HELPER JOB.json OUT.json under the peers' Python; returns OUT's JSON."""
    job_path = os.path.join(tmp, "job.json")
    with open(job_path, "w") as f:
        json.dump(job, f)
    run([args.python, os.path.join(HERE, helper), job_path, out_json])
    with open(out_json) as f:
        return json.load(f)


def run_normals(args, scene_name, scene, spec, sr, outdir, tmp):
    """The normals step: octrace's shading normals in both surface modes against VTK's."""
    w, h = [int(v) for v in scene["size"].split("x")]
    exrs = {}
    for surface in SURFACES:
        exrs[surface] = []
        for k, light in enumerate(NORMAL_LIGHTS):
            exr = os.path.join(tmp, "%s_normals_%s_%d.exr" % (scene_name, surface, k))
            run(octrace_cmd(args.octrace, scene, args.data, scene_depth(args, scene), 2, exr + ".json", exr, surface, 1,
                            ("--ambient", "0", "--colour", "1,1,1", "--light", ",".join(map(str, light)))))
            exrs[surface].append(exr)
    pngs = {}
    for grid in ("native", "lattice"):
        spec_path = os.path.join(tmp, "spec.json")
        with open(spec_path, "w") as f:
            json.dump(dict(spec, grid=grid, threads=2, normals=True), f)
        pngs[grid] = os.path.join(tmp, "%s_vtk_%s_normals.png" % (scene_name, grid))
        run(["xvfb-run", "-a", "-s", "-screen 0 %dx%dx24" % (w, h), args.python, os.path.join(HERE, "vtk_peer.py"),
             spec_path, os.path.join(tmp, "vtk_normals.json"), pngs[grid]])
    job = {"camera_pos": scene["camera_pos"], "look_at": scene["look_at"], "up": scene["up"], "lights": NORMAL_LIGHTS,
           "octrace": exrs, "vtk": pngs, "thumb_dir": outdir, "prefix": scene_name, "thumb_width": 480}
    out = os.path.join(outdir, "%s_normals.json" % scene_name)
    sr["normals"] = run_helper(args, tmp, "normals.py", job, out)
    sr["normals"]["json"] = os.path.basename(out)
    for key, v in sr["normals"]["pairs"].items():
        log("%s normals %s: mean %.2f deg over %d pixels" % (scene_name, key, v["mean_deg"], v["pixels_both"]))


def parse_vdb_trace_ms(stdout):
    lines = stdout.splitlines()
    for i, line in enumerate(lines):
        if "ray-tracing" in line:
            for later in lines[i + 1:]:
                mm = re.search(r"completed in ([0-9.eE+-]+) sec", later)
                if mm:
                    return float(mm.group(1)) * 1e3
            break
    raise RuntimeError("vdb_render printed no ray-tracing time:\n" + stdout)


def run_vdb(args, scene_name, scene, spec, sr, images, outdir, tmp):
    w, h = [int(v) for v in scene["size"].split("x")]
    spec_path = os.path.join(tmp, "spec.json")
    with open(spec_path, "w") as f:
        json.dump(spec, f)
    vdb_path = os.path.join(tmp, scene_name + ".vdb")
    cpus = sorted(os.sched_getaffinity(0))
    # pyopenvdb has no thread setting; TBB sizes its pool from the CPU affinity mask, so the
    # level set is built pinned to N CPUs with taskset for the N-thread rows.
    for n in THREADS:
        ls_json = os.path.join(outdir, "%s_openvdb_levelset_threads%d.json" % (scene_name, n))
        pin = ["taskset", "-c", ",".join(str(c) for c in cpus[:n])] if TASKSET and n < len(cpus) else []
        run(pin + [args.python, os.path.join(HERE, "vdb_peer.py"), spec_path, ls_json, vdb_path])
        with open(ls_json) as f:
            ls = json.load(f)
        ls["cpus"] = n if (pin or n == len(cpus)) else len(cpus)
        ls["pinned_with"] = " ".join(pin) if pin else None
        with open(ls_json, "w") as f:
            json.dump(ls, f, indent=2)
        sr["runs"]["openvdb_levelset_threads%d" % n] = ls
        log("%s openvdb level set on %d CPU(s): %.0f ms, %d active voxels" % (
            scene_name, ls["cpus"], ls["levelset_ms"], ls["active_voxels"]))
    hfov = hfov_for_vdb(float(scene["fov"]), w, h)
    vdb_png = os.path.join(tmp, scene_name + "_openvdb.png")
    for n in THREADS:
        cmd = ["vdb_render", vdb_path, vdb_png, "-res", "%dx%d" % (w, h), "-translate", scene["camera_pos"],
               "-lookat", scene["look_at"], "-up", scene["up"], "-fov", "%.10f" % hfov,
               "-isovalue", "%.10g" % ls["isovalue"], "-shader", "diffuse", "-cpus", str(n), "-v"]
        reps = []
        for _ in range(VDB_REPEAT):
            p, wall = run(cmd)
            reps.append({"render_ms": parse_vdb_trace_ms(p.stdout), "process_wall_ms": wall * 1e3})
        r = {"peer": "vdb_render", "threads": n,
             "command": " ".join(os.path.basename(c) if c in (vdb_path, vdb_png) else c for c in cmd),
             "hfov_deg": hfov, "vertical_fov_deg": float(scene["fov"]), "repeats": reps,
             "render_ms": min(x["render_ms"] for x in reps),
             "process_wall_ms": min(x["process_wall_ms"] for x in reps),
             "stdout_last_run": p.stdout.splitlines()}
        with open(os.path.join(outdir, "%s_openvdb_render_threads%d.json" % (scene_name, n)), "w") as f:
            json.dump(r, f, indent=2)
        sr["runs"]["openvdb_threads%d" % n] = r
        log("%s vdb_render threads %d: %.0f ms" % (scene_name, n, r["render_ms"]))
    images["openvdb"] = {"png": vdb_png, "background": [0, 0, 0]}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--octrace", default=os.path.join(ROOT, "build", "app", "octrace"))
    ap.add_argument("--data", default=os.path.normpath(os.path.join(ROOT, "..", "shared", "data")))
    ap.add_argument("--python", default="/usr/bin/python3")
    ap.add_argument("--depth", type=int, default=None, help="octree depth of every scene (default: each scene's deepest)")
    ap.add_argument("--scenes", default="levitus_T,levitus_S,spheres")
    args = ap.parse_args()
    t_start = time.perf_counter()
    load_start = list(os.getloadavg())
    if not os.path.exists(args.octrace):
        sys.exit("peers: octrace not found at %s (build it first)" % args.octrace)
    outdir = os.path.join(ROOT, "docs", "benchmarks", "peers")
    os.makedirs(outdir, exist_ok=True)
    for name in os.listdir(outdir):  # this script's own output of an earlier run
        if name.endswith((".json", ".png")):
            os.remove(os.path.join(outdir, name))
    failed = {}
    tmp = tempfile.mkdtemp(prefix="octrace-peers-")
    have, versions = detect(args.python)
    for k, (ok, why) in have.items():
        log("%s: %s" % (k, ("run (" + why + ")") if ok else ("SKIPPED: " + why)))
    octrace_version = run([args.octrace, "--version"])[0].stdout.strip()
    with open(args.octrace, "rb") as f:
        octrace_sha256 = hashlib.sha256(f.read()).hexdigest()

    results = []
    for scene_name in args.scenes.split(","):
        with open(os.path.join(ROOT, "bench", "scenes", scene_name + ".json")) as f:
            scene = json.load(f)
        w, h = [int(v) for v in scene["size"].split("x")]
        input_path = scene_input(scene, args.data)
        if not is_analytic(scene) and not os.path.exists(input_path):
            sys.exit("peers: %s not found (the scenes need ../shared/data)" % input_path)
        sr = {"name": scene_name, "scene": scene, "runs": {}, "notes": []}
        results.append(sr)

        # ---- octrace ----
        oct_png = {}
        for surface in SURFACES:
            oct_png[surface] = os.path.join(tmp, "%s_octrace_%s.png" % (scene_name, surface))
            key = "octrace" if surface == "voxel" else "octrace_smooth"
            for n in THREADS:
                stats = os.path.join(outdir, "%s_%s_threads%d.json" % (scene_name, key, n))
                p, wall = run(octrace_cmd(args.octrace, scene, args.data, scene_depth(args, scene), n, stats, oct_png[surface], surface))
                with open(stats) as f:
                    s = json.load(f)
                sr["runs"]["%s_threads%d" % (key, n)] = s
                log("%s octrace %s threads %d: render %.1f ms, build %.1f ms" % (
                    scene_name, surface, n, s["render_ms"], s["build_ms"]))
        # The default renderer, tile, in both modes (its smooth is the default look of a field).
        for surface in SURFACES:
            key = "octrace_tile" if surface == "voxel" else "octrace_tile_smooth"
            for n in THREADS:
                stats = os.path.join(outdir, "%s_%s_threads%d.json" % (scene_name, key, n))
                run(octrace_cmd(args.octrace, scene, args.data, scene_depth(args, scene), n, stats, os.path.join(tmp, "tile.png"), surface,
                                renderer="tile"))
                with open(stats) as f:
                    sr["runs"]["%s_threads%d" % (key, n)] = json.load(f)
                log("%s octrace tile %s threads %d: render %.1f ms" % (
                    scene_name, surface, n, sr["runs"]["%s_threads%d" % (key, n)]["render_ms"]))
        s1 = sr["runs"]["octrace_threads1"]
        m = re.search(r"vertical scale ([0-9.eE+-]+)", s1.get("geographic", ""))
        octrace_vscale = float(m.group(1)) if m else None

        spec = {"iso": scene["iso"], "depth": scene_depth(args, scene), "size": scene["size"], "camera_pos": scene["camera_pos"],
                "look_at": scene["look_at"], "up": scene["up"], "fov": scene["fov"], "frames": VTK_FRAMES}
        if is_analytic(scene):
            spec.update(input=write_analytic_nrrd(args.octrace, scene, tmp), format="nrrd")
        else:
            spec.update(input=input_path, format="netcdf", var=scene["var"], region=scene["region"])
        images = {"octrace": {"png": oct_png["voxel"], "background": [255, 255, 255]},
                  "octrace_smooth": {"png": oct_png["smooth"], "background": [255, 255, 255]}}

        for peer, fn in (("vtk", run_vtk), ("openvdb", run_vdb), ("embree", run_embree)):
            if not have[peer][0]:
                continue
            try:
                fn(args, scene_name, scene, spec, sr, images, outdir, tmp)
            except Exception as e:  # a peer that fails is reported, the others still run
                msg = [m for m in str(e).strip().splitlines() if m.strip()] or [type(e).__name__]
                short = msg[0] if len(msg) == 1 else "%s ... %s" % (msg[0], msg[-1])
                failed.setdefault(peer, []).append("%s: %s" % (scene_name, short))
                log("%s %s FAILED: %s" % (scene_name, peer, e))
        if have["vtk"][0]:
            try:
                run_normals(args, scene_name, scene, spec, sr, outdir, tmp)
            except Exception as e:
                failed.setdefault("normals", []).append("%s: %s" % (scene_name, str(e).strip().splitlines()[0]))
                log("%s normals FAILED: %s" % (scene_name, e))
        if "vtk_lattice_threads1" in sr["runs"]:
            lat = sr["runs"]["vtk_lattice_threads1"]
            sr["field_check"] = {
                "octrace_boundary_voxels": s1["boundary_voxels"], "peer_lattice_boundary_cells": lat["boundary_cells"],
                "octrace_vertical_scale": octrace_vscale, "peer_vertical_scale": lat["vertical_scale"],
                "octrace_cube_origin": s1["cube_origin"], "octrace_cube_side": s1["cube_side"],
                "peer_cube_origin": lat["cube_origin"], "peer_cube_side": lat["cube_side"]}

        # ---- images: thumbnails and mask comparison (need VTK's PNG reader/writer) ----
        if have["vtk"][0] or have["openvdb"][0] or have["embree"][0]:
            job = {"reference": "octrace", "also_against": ["octrace_smooth"], "images": images, "thumb_dir": outdir,
                   "prefix": scene_name, "thumb_width": 480}
            img_json = os.path.join(outdir, "%s_images.json" % scene_name)
            im = run_helper(args, tmp, "images.py", job, img_json)
            for v in im["images"].values():  # relative paths in the committed JSON
                for k in ("png", "thumb", "maskdiff"):
                    if k in v:
                        v[k] = os.path.basename(v[k])
            with open(img_json, "w") as f:
                json.dump(im, f, indent=2)
            sr["images"] = im
        else:
            shutil.copy(oct_png["voxel"], os.path.join(outdir, scene_name + "_octrace_full.png"))
            sr["octrace_full_png"] = scene_name + "_octrace_full.png"

    total_s = time.perf_counter() - t_start
    cpu = ""
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    run_info = {"date_utc": datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M"), "octrace": octrace_version,
                "cpu": cpu, "cores": os.cpu_count(), "platform": platform.platform(), "peers": {
                    k: {"ran": ok, "detail": why} for k, (ok, why) in have.items()}, "versions": versions,
                "total_seconds": total_s, "depth": args.depth, "scene_depths": {sr["name"]: sr["runs"]["octrace_threads1"]["depth"] for sr in results},
                "apt": APT,
                "loadavg_start": load_start, "loadavg_end": list(os.getloadavg()),
                "octrace_binary": os.path.relpath(args.octrace, ROOT), "octrace_sha256": octrace_sha256,
                "failed": failed}
    with open(os.path.join(outdir, "run.json"), "w") as f:
        json.dump(run_info, f, indent=2)
    write_md(results, run_info, have, failed)
    shutil.rmtree(tmp, ignore_errors=True)
    log("wrote docs/benchmarks/peers.md in %.0f s" % total_s)


def write_md(results, info, have, failed):
    L = []
    a = L.append
    a("# Peers: octrace next to VTK, OpenVDB and Embree on the same scenes\n")
    a("Generated by `bench/peers.py` (do not edit by hand) on %s UTC, %s, %s (%d cores); raw JSON of every" % (
        info["date_utc"], info["octrace"], info["cpu"] or "unknown CPU", info["cores"] or 0))
    a("run and the images in [`peers/`](peers/). Whole run: %.0f s. The machine is a shared VM (load average" % info["total_seconds"])
    a("%.2f at the start of the run, %.2f at its end, with %d cores: other work on the machine slows every" % (
        info["loadavg_start"][0], info["loadavg_end"][0], info["cores"] or 0))
    a("program and flattens 2-thread speed-ups): compare ratios within this run rather than absolute times.\n")
    a("Install the peers (Debian bookworm, as root), then run `python3 bench/peers.py`:\n")
    a("```\napt-get update\n%s\n```\n" % info["apt"])
    ran = [k for k, (ok, _) in have.items() if ok]
    skipped = [(k, why) for k, (ok, why) in have.items() if not ok]
    a("Peers run: %s." % (", ".join("%s (%s)" % (k, have[k][1]) for k in ran) or "none"))
    if skipped:
        a("**Skipped:** " + "; ".join("**%s**: not installed: %s" % (k, why) for k, why in skipped) + " (the apt-get line above installs them).")
    else:
        a("Skipped: none.")
    for k, msgs in failed.items():
        a("**Failed: %s** (installed, but the run broke off; its rows are missing): %s." % (k, "; ".join(msgs)))
    a("")
    a("**Ratio** = peer time / octrace time on the same scene and thread count (above 1: octrace is")
    a("faster). Render times exclude loading and preparing; preparation is shown beside them:")
    a("octrace's octree build, VTK's isosurface extraction, OpenVDB's mesh-to-level-set conversion.\n")
    write_summary_md(a, results)

    for sr in results:
        sc = sr["scene"]
        R = sr["runs"]
        o1, o2 = R["octrace_threads1"], R["octrace_threads2"]
        if is_analytic(sc):
            a("## %s: %s, iso %s of `%s`, %s\n" % (sr["name"], sc["name"], sc["iso"], sc["input"], sc["size"]))
        else:
            a("## %s: %s %s isosurface, %s\n" % (sr["name"], sc["var"], sc["iso"], sc["size"]))
        if sc.get("description") and is_analytic(sc):
            a(sc["description"] + "\n")
        a("`%s`%s, octrace depth %d (%s boundary voxels of %.4g%s), camera `--camera-pos %s --look-at %s "
          "--up %s --fov %s` (vertical), %s pixels, of which %s rays meet octrace's scene cube.\n" % (
              sc["input"], (", region " + sc["region"]) if "region" in sc else "", o1["depth"], format(o1["boundary_voxels"], ","),
              o1["cube_side"] / (1 << o1["depth"]), km(sc), sc["camera_pos"], sc["look_at"], sc["up"], sc["fov"],
              format(o1["pixels"], ","), format(o1["rays"], ",")))
        a("| program | surface drawn | threads | preparation ms | render ms | render ratio | prep + render ratio |")
        a("|---|---|---|---|---|---|---|")
        oct_by_n = {1: o1, 2: o2}
        rows = []
        for n in THREADS:
            o = oct_by_n[n]
            a("| octrace `full` | %s boundary voxels, depth %d | %d | %s (build) | **%s** | 1 | 1 |" % (
                format(o["boundary_voxels"], ","), o["depth"], n, fmt_ms(o["build_ms"]), fmt_ms(o["render_ms"])))
        for n in THREADS:
            r = R.get("octrace_smooth_threads%d" % n)
            if r:
                o = oct_by_n[n]
                a("| octrace `full --surface smooth` | the same voxels' trilinear interpolant (%s bytes per voxel) | %d | "
                  "%s (build) | %s | %s | %s |" % (
                      fmt_ratio(r["bytes_per_voxel"]), n, fmt_ms(r["build_ms"]), fmt_ms(r["render_ms"]),
                      fmt_ratio(r["render_ms"] / o["render_ms"]),
                      fmt_ratio((r["build_ms"] + r["render_ms"]) / (o["build_ms"] + o["render_ms"]))))
        for key, label, drawn in (("octrace_tile", "octrace `tile` (the default renderer)", "the same boundary voxels (exact: `full`'s image)"),
                                  ("octrace_tile_smooth", "octrace `tile --surface smooth` (the default look)", "the same voxels' trilinear interpolant")):
            for n in THREADS:
                r = R.get("%s_threads%d" % (key, n))
                if r:
                    o = oct_by_n[n]
                    a("| %s | %s | %d | %s (build) | %s | %s | %s |" % (
                        label, drawn, n, fmt_ms(r["build_ms"]), fmt_ms(r["render_ms"]), fmt_ratio(r["render_ms"] / o["render_ms"]),
                        fmt_ratio((r["build_ms"] + r["render_ms"]) / (o["build_ms"] + o["render_ms"]))))
        for grid, label in (("native", native_label(sc)), ("lattice", "octrace's depth-%d lattice" % o1["depth"])):
            for n in THREADS:
                r = R.get("vtk_%s_threads%d" % (grid, n))
                if not r:
                    continue
                o = oct_by_n[n]
                a("| VTK flying edges + OpenGL (llvmpipe) | %s triangles, %s (%s) | %d | %s (extract) | %s | %s | %s |" % (
                    format(r["triangles"], ","), label, "x".join(map(str, r["grid_dims"])), n, fmt_ms(r["extract_ms"]),
                    fmt_ms(r["render_ms"]), fmt_ratio(r["render_ms"] / o["render_ms"]),
                    fmt_ratio((r["extract_ms"] + r["render_ms"]) / (o["build_ms"] + o["render_ms"]))))
        for n in THREADS:
            r = R.get("openvdb_threads%d" % n)
            ls = R.get("openvdb_levelset_threads%d" % n)
            if not r:
                continue
            o = oct_by_n[n]
            a("| OpenVDB `vdb_render` | level set, %s active voxels of %.4g%s (from the lattice mesh) | %d | %s (level set%s) | %s | %s | %s |" % (
                format(ls["active_voxels"], ","), ls["voxel_size_km"], km(sc), n, fmt_ms(ls["levelset_ms"]),
                "" if ls.get("cpus") == n else ", every CPU",
                fmt_ms(r["render_ms"]), fmt_ratio(r["render_ms"] / o["render_ms"]),
                fmt_ratio((ls["levelset_ms"] + r["render_ms"]) / (o["build_ms"] + o["render_ms"]))))
        for n in THREADS:
            r = R.get("embree_threads%d" % n)
            if not r:
                continue
            o = oct_by_n[n]
            a("| Embree %s (`rtcIntersect16`, coherent 4x4 packets) | %s triangles, octrace's depth-%d lattice (VTK's mesh) | %d | %s (BVH) | %s | %s | %s |" % (
                r["embree_version"], format(r["triangles"], ","), o1["depth"], n, fmt_ms(r["bvh_build_ms"]), fmt_ms(r["render_ms"]),
                fmt_ratio(r["render_ms"] / o["render_ms"]),
                fmt_ratio((r["bvh_build_ms"] + r["render_ms"]) / (o["build_ms"] + o["render_ms"]))))
        a("")
        extra = []
        for n in THREADS:
            t, ts = R.get("octrace_tile_threads%d" % n), R.get("octrace_tile_smooth_threads%d" % n)
            peers = [(name, R.get(k)) for name, k in (("VTK lattice", "vtk_lattice_threads%d" % n), ("Embree", "embree_threads%d" % n))]
            if t and ts:
                extra.append("against the default renderer, %d thread%s: " % (n, "" if n == 1 else "s") + "; ".join(
                    "%s / `tile` %s, / `tile --surface smooth` %s" % (name, fmt_ratio(r["render_ms"] / t["render_ms"]),
                                                                        fmt_ratio(r["render_ms"] / ts["render_ms"]))
                    for name, r in peers if r) + " (above 1: octrace faster)")
        for n in THREADS:
            for grid in ("native", "lattice"):
                r = R.get("vtk_%s_threads%d" % (grid, n))
                if r:
                    extra.append("VTK %s, %d thread%s: first frame %s ms (shader compilation and upload), median frame %s ms" % (
                        grid, n, "" if n == 1 else "s", fmt_ms(r["first_frame_ms"]), fmt_ms(r["render_ms_median"])))
        for n in THREADS:
            r = R.get("openvdb_threads%d" % n)
            if r:
                extra.append("vdb_render, %d thread%s: whole process (read .vdb, trace, write PNG) %s ms" % (
                    n, "" if n == 1 else "s", fmt_ms(r["process_wall_ms"])))
        for n in THREADS:
            o = oct_by_n[n]
            extra.append("octrace, %d thread%s: %.3f us per ray, median of the %d renders %s ms" % (
                n, "" if n == 1 else "s", o["us_per_ray"], o.get("repeat", 1), fmt_ms(o.get("render_ms_median"))))
        for n in THREADS:
            r = R.get("vtk_lattice_threads%d" % n)
            if r:
                extra.append("reading the %s and resampling it to octrace's lattice in numpy (bench/peers/field.py, " % (
                    "NRRD of `octrace sample`" if is_analytic(sc) else "NetCDF region") +
                             "not counted for any program), %d thread%s: %s ms" % (n, "" if n == 1 else "s", fmt_ms(r["load_ms"])))
                break
        if extra:
            a("Also measured:\n")
            for e in extra:
                a("* " + e)
            a("")
        fc = sr.get("field_check")
        if fc:
            same = fc["octrace_boundary_voxels"] == fc["peer_lattice_boundary_cells"]
            vs = ("Vertical scale: peers %.6f, octrace `%s`; " % (fc["peer_vertical_scale"], fc["octrace_vertical_scale"])
                  if fc["peer_vertical_scale"] is not None else "")
            a("Same field? The peers' reader, mapping and lattice resampling (bench/peers/field.py) find %s cells "
              "on octrace's depth-%d lattice that straddle the iso value with 8 valid corners; octrace reports %s "
              "boundary voxels (%s). %sscene cube: peers origin (%s) side %.6f, "
              "octrace (%s) side %.6f.\n" % (
                  format(fc["peer_lattice_boundary_cells"], ","), o1["depth"], format(fc["octrace_boundary_voxels"], ","),
                  "identical" if same else "**they differ**", vs,
                  ", ".join("%.6f" % v for v in fc["peer_cube_origin"]), fc["peer_cube_side"], fc["octrace_cube_origin"],
                  fc["octrace_cube_side"]))
        if sr.get("octrace_full_png"):
            a("No peer image to compare with; octrace's frame: ![octrace](peers/%s)\n" % sr["octrace_full_png"])
        im = sr.get("images")
        if im:
            names = [k for k in ("octrace", "octrace_smooth", "vtk_native", "vtk_lattice", "openvdb", "embree") if k in im["images"]]
            titles = {"octrace": "octrace (full, depth %d)" % o1["depth"],
                      "octrace_smooth": "octrace (full --surface smooth)", "vtk_native": "VTK, " + native_label(sc),
                      "vtk_lattice": "VTK, octrace's lattice", "openvdb": "OpenVDB vdb_render",
                      "embree": "Embree, octrace's lattice"}
            x0, y0, x1, y1 = im["crop"]
            a("Images (each program's own %dx%d frame, all cropped to the same window x %d..%d, y %d..%d and scaled "
              "down; vdb_render's black background shown white). Second row: where each peer's surface covers the "
              "same pixels as octrace's (grey), only octrace's (red), only the peer's (blue); *agreement* = "
              "pixels both cover / pixels either covers; after it the same against octrace's smooth surface, the trilinear "
              "interpolant the peers' lattice meshes approximate, where octrace's voxel image draws the voxels' boxes, "
              "which stand out of a curved surface by up to a voxel.\n" % (im["images"]["octrace"]["width"],
                                                                 im["images"]["octrace"]["height"], x0, x1, y0, y1))
            a("| " + " | ".join(titles[k] for k in names) + " |")
            a("|" + "---|" * len(names))
            a("| " + " | ".join("![%s](peers/%s)" % (k, im["images"][k]["thumb"]) for k in names) + " |")
            cells = []
            for k in names:
                e = im["images"][k]
                if k == "octrace":
                    cells.append("%s surface pixels" % format(e["foreground_pixels"], ","))
                elif k == "octrace_smooth":
                    v = e["vs_reference"]
                    cells.append("![%s mask difference](peers/%s)<br>agreement with voxel %.3f (%s only voxel, %s only smooth)" % (
                        k, e["maskdiff"], v["agreement"], format(v["only_reference"], ","), format(v["only_this"], ",")))
                else:
                    v = e["vs_reference"]
                    vs = e.get("vs_octrace_smooth")
                    cells.append("![%s mask difference](peers/%s)<br>agreement %.3f (%s only octrace, %s only peer)%s" % (
                        k, e["maskdiff"], v["agreement"], format(v["only_reference"], ","), format(v["only_this"], ","),
                        "; with octrace smooth %.3f (%s only octrace, %s only peer)" % (
                            vs["agreement"], format(vs["only_reference"], ","), format(vs["only_this"], ",")) if vs else ""))
            a("| " + " | ".join(cells) + " |")
            a("")
        nm = sr.get("normals")
        if nm:
            write_normals_md(a, nm, sc)

    a("## How each program was driven\n")
    a("* **octrace**: `octrace render INPUT [--var V --region R] --iso I --depth D --size 1600x1200 --camera-pos ... "
      "--look-at ... --up ... --fov ... --renderer full --threads N --repeat %d --stats F.json`; *render* = "
      "`render_ms`, the fastest of the %d renders in the process; *preparation* = `build_ms` (octree build from "
      "the field). The same with `--renderer tile` (the default renderer, exact: its hits are `full`'s) in "
      "both surface modes." % (OCTRACE_REPEAT, OCTRACE_REPEAT))
    a("* **Depth** D: each scene's deepest depth of `bench/scenes/*.json` (`--depth` sets one for all).")
    a("* **Field for the peers, ocean scenes** (`bench/peers/field.py`): the NetCDF variable read with `netCDF4`, "
      "`missing_value`/`_FillValue` masked, the region selected and mapped as octrace does (ARCHITECTURE.md, "
      "Coordinates): km, x = R (lon - lon0) cos(lat0), y = R (lat - lat0), z = -depth_km x vertical scale, "
      "R = 6371, (lon0, lat0) = the region's centre, vertical scale by octrace's default rule (a quarter of the "
      "larger horizontal extent over the depth range), checked above against the scale octrace states in "
      "`--stats` (`geographic`). *Native* = the NetCDF samples as they are (1 degree x 1 degree x 20 uneven "
      "levels: the peers' own resolution, much coarser than octrace's voxels). *Lattice* = the trilinear "
      "field at the corners of octrace's depth-D voxel lattice over its scene cube, computed the way octrace's "
      "builder computes it; a corner is masked when any sample its stencil uses is masked.")
    a("* **Field for the peers, analytic scenes** (`analytic:NAME:N`): `octrace sample NAME --samples N` writes the "
      "N^3 float32 samples octrace generates for that input as NRRD; field.py reads them (origin and spacing from "
      "the header, uniform axes). *Native* = those samples; *lattice* = the trilinear field at the corners of the "
      "depth-D lattice, as above (a uniform axis located by dividing by the spacing, as octrace's FieldSampler "
      "does). The count of straddling cells checks it against octrace's boundary voxels.")
    a("* **Masked samples** (land, sea floor): octrace never forms a surface in a cell with a masked corner. For "
      "flying edges the masked samples are set to iso - (value range) - 1, and afterwards every triangle whose "
      "cell has a masked corner is removed (its cell found from its centroid in index space), so the walls the "
      "fill value makes along coasts and the sea floor are gone and the same cells as octrace's carry surface.")
    a("* **VTK** (`bench/peers/vtk_peer.py`, `isomesh.py`): `vtkFlyingEdges3D` on a `vtkImageData`. Flying edges "
      "needs uniform spacing and the depth axis is uneven, so on the native grid it runs in index space along "
      "depth and each vertex's z is then mapped through the level depths piecewise linearly: marching-cubes "
      "vertices lie on cell edges and that map is affine within a cell, so the triangles are those "
      "`vtkContourFilter` would give on the `vtkRectilinearGrid`. The lattice is uniform and goes straight in. "
      "Normals by `vtkPolyDataNormals` (counted in *extract*). Drawn by `vtkPolyDataMapper` into a %s offscreen "
      "`vtkRenderWindow` (no multisampling) under `xvfb-run -a`, on Mesa (GL renderer `%s`), camera position, focal "
      "point = look-at, view up, view angle = octrace's vertical fov; one light fixed to the camera in "
      "octrace's default direction, two-sided lighting, ambient 0.15 + diffuse 0.85, octrace's default colour, "
      "white background. Threads N: `vtkSMPTools::Initialize(N)` and `LP_NUM_THREADS=N` (llvmpipe's "
      "rasterizer threads). *Render* = the fastest of %d `Render()` calls after the first, each followed by "
      "`WaitForCompletion()` (glFinish), timed in the Python process (their median is in the raw JSON); the first frame (shader compilation, "
      "buffer upload) is listed separately." % (
          results[0]["scene"]["size"] if results else "", first(results, "vtk_native_threads1", "gl_renderer") or "not run this time",
          VTK_FRAMES))
    a("* **OpenVDB** (`bench/peers/vdb_peer.py`): the lattice isosurface mesh (as for VTK) turned into a "
      "narrow-band level set by `pyopenvdb.FloatGrid.createLevelSetFromPolygons` (OpenVDB's meshToVolume; "
      "voxel size = octrace's voxel, half width 4 voxels, index origin at the world origin, so the world "
      "coordinates are octrace's), written as .vdb. The ocean isosurfaces are open sheets (they end at the "
      "region's sides, coasts and sea floor) and meshToVolume can only sign closed surfaces: every value "
      "comes out positive, an unsigned distance to the sheet, whose zero set a level-set ray tracer cannot "
      "find. So `vdb_render` draws the iso-value one voxel (`-isovalue`): a closed shell two voxels thick "
      "around the sheet, which from the camera looks like the sheet (octrace's boundary voxels are one voxel "
      "thick). Half a voxel leaves dark seams where the intersector's linear search steps over the thin shell. "
      "A closed surface (the spheres) comes out signed, and its zero is drawn (`-isovalue 0`). "
      "pyopenvdb has no thread setting and TBB sizes its pool from the CPU affinity mask, so the level set is "
      "built twice: pinned to one CPU with `taskset -c 0` for the 1-thread rows, unpinned for the 2-thread rows.")
    hf = first(results, "openvdb_threads1", "hfov_deg")
    a("* **vdb_render camera**: `-translate` = camera position, `-lookat` = look-at, `-up` = up, `-res %s`, "
      "`-shader diffuse` (its headlight: |n . ray|, grey), `-cpus N` (1 = unthreaded; vdb_render has no "
      "`-threads` option). Its `-fov` is *horizontal*: `vdb_render` turns it into a focal length for the "
      "default 41.2136 mm aperture, and its PerspectiveCamera spans tan(hfov/2) across the image width and "
      "tan(hfov/2) x height/width across the height, with pixel centres at +0.5 as octrace's. So the vertical "
      "fov f of octrace's scene becomes hfov = 2 atan(tan(f/2) x width/height) = %s degrees for 30 degrees at "
      "4:3. *Render* = the time vdb_render prints with `-v` for ray-tracing (its `tbb::tick_count`, "
      "excluding reading the .vdb and writing the image), the fastest of %d runs." % (
          results[0]["scene"]["size"] if results else "", ("%.6f" % hf) if hf else "-", VDB_REPEAT))
    a("* **Embree** (`bench/peers/embree_peer.cpp`, built with `c++ -O3`): VTK's lattice mesh (the same "
      "triangles and point normals as the VTK lattice rows) in one triangle geometry, BVH built with "
      "`RTC_BUILD_QUALITY_HIGH` on N Embree threads (*preparation*); primary rays of octrace's pinhole camera "
      "(vertical fov, pixel centres at +0.5) traced with `rtcIntersect16` as 4x4-pixel packets with "
      "`RTC_INTERSECT_CONTEXT_FLAG_COHERENT`, 8x8-pixel tiles handed to N `std::thread`s; shaded as VTK's rows "
      "(camera light, two-sided, interpolated point normals). *Render* = the fastest of %d frames after a "
      "first, timed in the program around the whole frame." % EMBREE_FRAMES)
    a("")
    a("## Reading the numbers\n")
    a("* The programs do not draw the same representation. octrace ray-casts the boundary voxels (blocky "
      "at one voxel; with `--surface smooth` the trilinear interpolant of the field inside them); VTK rasterizes a smooth triangle mesh, whose cost grows with its triangles, and the "
      "native mesh of the ocean scenes has a few thousand because the NetCDF grid is coarse (the spheres' 192^3 samples give "
      "half a million); vdb_render ray-marches a narrow-band "
      "level set with the same voxel size as octrace. Only the lattice rows are at octrace's resolution.")
    a("* llvmpipe is a CPU rasterizer: the same two cores do all the work in every row. On a GPU, VTK's "
      "frame time would be a small fraction of these numbers.")
    a("* *Preparation* differs in kind too: octrace's build samples the field at its lattice itself, while "
      "the peers' lattice (numpy, listed under *Also measured*) is counted for none of them; OpenVDB's "
      "preparation is only the mesh-to-level-set conversion (the mesh is VTK's lattice extraction).")
    with open(os.path.join(ROOT, "docs", "benchmarks", "peers.md"), "w") as f:
        f.write("\n".join(L) + "\n")


def write_summary_md(a, results):
    """Issue 23's peers targets, one row per scene and thread count: the default renderer `tile`
    (voxel and smooth surfaces) at least 2x faster than VTK on octrace's lattice mesh, and faster
    than Embree on the same mesh."""
    a("Issue 23's targets: octrace's default renderer (`tile`, either surface) at least 2x faster than VTK + "
      "llvmpipe drawing the lattice mesh (ratio VTK / tile >= 2) and faster than Embree tracing it (Embree / tile "
      "> 1). Render ms of this run:\n")
    a("| scene | threads | `full` | `tile` | `tile` smooth | VTK lattice | Embree | VTK / `tile` | VTK / `tile` smooth "
      "| Embree / `tile` | Embree / `tile` smooth |")
    a("|---|---|---|---|---|---|---|---|---|---|---|")

    def ms(r):
        return fmt_ms(r["render_ms"]) if r else "-"

    def ratio(peer, octrace):
        return fmt_ratio(peer["render_ms"] / octrace["render_ms"]) if peer and octrace else "-"

    for sr in results:
        R = sr["runs"]
        for n in THREADS:
            f, t, ts = (R.get("%s_threads%d" % (k, n)) for k in ("octrace", "octrace_tile", "octrace_tile_smooth"))
            v, e = R.get("vtk_lattice_threads%d" % n), R.get("embree_threads%d" % n)
            a("| %s | %d | %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                sr["name"], n, ms(f), ms(t), ms(ts), ms(v), ms(e), ratio(v, t), ratio(v, ts), ratio(e, t), ratio(e, ts)))
    a("")


def write_normals_md(a, nm, scene):
    """The normals step's table and images (bench/peers/normals.py)."""
    grids = [g for g in ("native", "lattice") if "vtk_" + g in nm["maps"]]
    modes = [m for m in SURFACES if "octrace_" + m in nm["maps"]]
    glabel = {"native": "VTK, " + native_label(scene), "lattice": "VTK, octrace's lattice"}
    a("Normals: the angle between the normal octrace shades a pixel with and the one VTK shades it with (its "
      "flying-edges mesh's point normals, interpolated per pixel as Phong shading does), over the pixels both draw "
      "as surface, in degrees: mean (median, 90th percentile) and the pixels compared. `voxel`: the boundary "
      "voxel's stored normal (the field's gradient at the voxel, octahedral code); `smooth`: the gradient of the "
      "trilinear interpolant at the hit. How: bench/peers/normals.py; raw: [`peers/%s`](peers/%s).\n" % (
          nm["json"], nm["json"]))
    a("| octrace | " + " | ".join(glabel[g] for g in grids) + " |")
    a("|---|" + "---|" * len(grids))
    for m in modes:
        cells = []
        for g in grids:
            v = nm["pairs"]["%s_vs_%s" % (m, g)]
            cells.append("**%.2f** (%.2f, %.2f), %s px" % (v["mean_deg"], v["median_deg"], v["p90_deg"],
                                                           format(v["pixels_both"], ",")))
        a("| `%s` | %s |" % (m, " | ".join(cells)))
    a("")
    names = ["octrace_" + m for m in modes] + ["vtk_" + g for g in grids]
    title = dict({"octrace_" + m: "octrace `%s`" % m for m in modes}, **{"vtk_" + g: glabel[g] for g in grids})
    a("Normal maps (camera space as RGB = (n + 1) / 2, turned towards the viewer; same crop for all), and under "
      "octrace's, the angle to VTK's on the lattice (white 0 degrees, black %g or more; red: only one program "
      "draws the pixel).\n" % nm["angle_black_deg"])
    a("| " + " | ".join(title[k] for k in names) + " |")
    a("|" + "---|" * len(names))
    a("| " + " | ".join("![%s normals](peers/%s)" % (k, nm["maps"][k]["thumb"]) for k in names) + " |")
    if "lattice" in grids:
        a("| " + " | ".join(("![angle](peers/%s)" % nm["pairs"]["%s_vs_lattice" % k[8:]]["thumb"])
                            if k.startswith("octrace_") else "" for k in names) + " |")
    a("")


def first(results, run, key):
    for sr in results:
        r = sr["runs"].get(run)
        if r and key in r:
            return r[key]
    return None


if __name__ == "__main__":
    sys.exit(main())
