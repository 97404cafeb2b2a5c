#!/usr/bin/env python3
"""Measures smooth surfaces (docs/dev/smooth-surfaces.md) against the analytic surface.

    python3 scripts/smooth_targets.py [--octrace build/app/octrace] [--out docs/dev/smooth-targets.json]

Two fields of disjoint spheres (FIELDS), f = max_i (r_i - |p - c_i|), sampled every 0.5 units on
65^3 points over [0, 32]^3, are written as NRRD and rendered by the CLI at its default renderer and
depth at a fixed camera, with `--surface voxel` and `--surface smooth` (and with the smooth
reference). Each EXR's Z channel is compared pixel by pixel with an analytic ray cast of the
same spheres through the same pinhole camera (core/src/render/Camera.cpp: pixel centres at
+0.5, row 0 at the top):
  - depth error over the pixels both hit, in sample spacings: median, p99, max;
  - silhouette agreement: IoU of the hit masks.
Then the cost per frame: render_ms of each mode, fastest of `--repeat` renders, the two modes
alternated three times (separate processes: the CLI has no way to render one frame twice with
two surface modes). Writes the JSON and prints it.
"""
import argparse
import json
import os
import struct
import subprocess
import sys
import tempfile
import zlib

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SPACING = 0.5
N = 65
# Two fields of disjoint spheres (> 2 samples apart), centre and radius in world units: radii of
# 6 to 12 samples, as the tests' sphere (radius 0.7 on a spacing of 1/16: 11 samples), and one
# with smaller spheres too (radii down to 3.4 samples), where the trilinear interpolant of the
# samples itself departs further from the spheres.
FIELDS = {
    "spheres": [((9.0, 9.0, 9.0), 5.0), ((22.5, 10.0, 12.0), 4.2), ((11.0, 22.0, 20.0), 3.1),
                ((23.0, 23.0, 22.0), 6.0), ((16.0, 15.0, 27.0), 3.0), ((26.5, 6.5, 25.5), 3.0)],
    "small spheres": [((9.0, 9.0, 9.0), 5.0), ((22.5, 10.0, 12.0), 4.2), ((11.0, 22.0, 20.0), 3.1),
                      ((23.0, 23.0, 22.0), 6.0), ((16.2, 16.4, 26.5), 2.3), ((26.0, 6.0, 25.0), 1.7)],
}
CAMERA = dict(pos=(52.0, -30.0, 38.0), look=(16.0, 16.0, 16.0), up=(0.0, 0.0, 1.0), fov=30.0, w=640, h=480)


def sphere_field(spheres):
    x = np.arange(N) * SPACING
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    f = np.full(X.shape, -1e9, dtype=np.float64)
    for (cx, cy, cz), r in spheres:
        f = np.maximum(f, r - np.sqrt((X - cx) ** 2 + (Y - cy) ** 2 + (Z - cz) ** 2))
    return f.astype(np.float32)


def write_nrrd(path, f):
    header = ("NRRD0004\n# spheres for scripts/smooth_targets.py\ntype: float\ndimension: 3\nspace dimension: 3\n"
              f"sizes: {N} {N} {N}\nspace directions: ({SPACING},0,0) (0,{SPACING},0) (0,0,{SPACING})\n"
              "kinds: domain domain domain\nendian: little\nencoding: raw\nspace origin: (0,0,0)\ncontent: spheres\n\n")
    with open(path, "wb") as o:
        o.write(header.encode())
        # NRRD is x fastest: the array is indexed [x, y, z], so write it in Fortran order.
        o.write(np.asfortranarray(f).tobytes(order="F"))


def read_exr_z(path):
    """The Z channel of an OpenEXR scanline file (no or ZIP/ZIPS compression), as float32 rows."""
    b = open(path, "rb").read()
    assert b[:4] == b"\x76\x2f\x31\x01", "not an OpenEXR file"
    p, attrs = 8, {}
    while b[p] != 0:
        name_end = b.index(b"\0", p)
        type_end = b.index(b"\0", name_end + 1)
        size = struct.unpack_from("<i", b, type_end + 1)[0]
        attrs[b[p:name_end].decode()] = b[type_end + 5:type_end + 5 + size]
        p = type_end + 5 + size
    p += 1
    chans, q, cl = [], 0, attrs["channels"]
    while cl[q] != 0:
        e = cl.index(b"\0", q)
        chans.append((cl[q:e].decode(), struct.unpack_from("<i", cl, e + 1)[0]))
        q = e + 17
    xmin, ymin, xmax, ymax = struct.unpack("<4i", attrs["dataWindow"])
    w, h = xmax - xmin + 1, ymax - ymin + 1
    comp = attrs["compression"][0]
    lines = {0: 1, 2: 1, 3: 16}[comp]
    nchunks = (h + lines - 1) // lines
    offsets = struct.unpack_from(f"<{nchunks}Q", b, p)
    size_of = {1: 2, 2: 4, 0: 4}
    z = np.zeros((h, w), dtype=np.float32)
    for off in offsets:
        y, n = struct.unpack_from("<ii", b, off)
        data = b[off + 8:off + 8 + n]
        rows = min(lines, ymax + 1 - y)
        raw = sum(size_of[t] for _, t in chans) * w * rows
        if comp != 0 and n < raw:
            raw_t = np.frombuffer(zlib.decompress(data), dtype=np.uint8).astype(np.int64)
            # Undo the predictor: t[i] = t[i-1] + t[i] - 128 (mod 256).
            t = ((raw_t[0] + np.cumsum(np.concatenate(([0], raw_t[1:] - 128)))) % 256).astype(np.uint8)
            half = (len(t) + 1) // 2
            data = np.empty(len(t), dtype=np.uint8)
            data[0::2], data[1::2] = t[:half], t[half:]
            data = data.tobytes()
        pos = 0
        for r in range(rows):
            for name, typ in sorted(chans):
                k = size_of[typ] * w
                if name == "Z":
                    z[y - ymin + r] = np.frombuffer(data[pos:pos + k], dtype="<f4" if typ == 2 else "<f2")
                pos += k
    return z


def analytic_depth(spheres):
    c = CAMERA
    eye = np.array(c["pos"])
    back = eye - np.array(c["look"])
    back /= np.linalg.norm(back)
    right = np.cross(np.array(c["up"]), back)
    right /= np.linalg.norm(right)
    up = np.cross(back, right)
    half_h = np.tan(np.radians(c["fov"]) / 2)
    half_w = half_h * c["w"] / c["h"]
    xs = ((np.arange(c["w"]) + 0.5) / c["w"] * 2 - 1) * half_w
    ys = (1 - (np.arange(c["h"]) + 0.5) / c["h"] * 2) * half_h
    SX, SY = np.meshgrid(xs, ys)
    d = SX[..., None] * right + SY[..., None] * up - back
    d /= np.linalg.norm(d, axis=-1, keepdims=True)
    depth = np.full(SX.shape, np.inf)
    for centre, r in spheres:
        oc = eye - np.array(centre)
        bq = (d * oc).sum(-1)
        disc = bq * bq - (oc @ oc - r * r)
        t = -bq - np.sqrt(np.where(disc >= 0, disc, np.nan))
        depth = np.where((disc >= 0) & (t > 0) & (t < depth), t, depth)
    return depth


def render(octrace, field, out, surface, extra=(), repeat=1):
    c = CAMERA
    stats = out + ".json"
    cmd = [octrace, "render", field, "--iso", "0", "--surface", surface, "-o", out, "--stats", stats,
           "--camera-pos", ",".join(map(str, c["pos"])), "--look-at", ",".join(map(str, c["look"])),
           "--up", ",".join(map(str, c["up"])), "--fov", str(c["fov"]), "--size", f"{c['w']}x{c['h']}",
           "--repeat", str(repeat), *extra]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    return json.load(open(stats))


def measure(z, truth):
    hit, true_hit = np.isfinite(z), np.isfinite(truth)
    both = hit & true_hit
    err = np.abs(z[both] - truth[both]) / SPACING
    return {
        "pixels_hit": int(hit.sum()),
        "pixels_hit_analytic": int(true_hit.sum()),
        "depth_error_median_spacings": float(np.median(err)),
        "depth_error_p99_spacings": float(np.percentile(err, 99)),
        "depth_error_max_spacings": float(err.max()),
        "silhouette_iou": float(both.sum() / (hit | true_hit).sum()),
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--octrace", default=os.path.join(ROOT, "build", "app", "octrace"))
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "dev", "smooth-targets.json"))
    ap.add_argument("--repeat", type=int, default=5)
    args = ap.parse_args()
    result = {"sample_spacing": SPACING, "samples": [N, N, N], "camera": CAMERA, "fields": {}}
    with tempfile.TemporaryDirectory() as tmp:
        for name, spheres in FIELDS.items():
            truth = analytic_depth(spheres)
            entry = {"spheres": [{"centre": c, "radius": r} for c, r in spheres], "modes": {}}
            field = os.path.join(tmp, name.replace(" ", "_") + ".nrrd")
            write_nrrd(field, sphere_field(spheres))
            runs = [("voxel", "voxel", ()), ("smooth", "smooth", ()),
                    ("smooth reference", "smooth", ("--renderer", "reference"))]
            for label, surface, extra in runs:
                out = os.path.join(tmp, label.replace(" ", "_") + ".exr")
                st = render(args.octrace, field, out, surface, extra)
                m = measure(read_exr_z(out), truth)
                m.update(renderer=st.get("renderer"), depth=st.get("depth"), bytes_per_voxel=st.get("bytes_per_voxel"),
                         boundary_voxels=st.get("boundary_voxels"))
                entry["modes"][label] = m
            result["fields"][name] = entry
        # Cost per frame: the default renderer, each mode's fastest of `repeat`, alternated.
        field = os.path.join(tmp, "spheres.nrrd")
        best = {"voxel": float("inf"), "smooth": float("inf")}
        for _ in range(3):
            for surface in ("voxel", "smooth"):
                st = render(args.octrace, field, os.path.join(tmp, "t.png"), surface, ("--threads", "2"), args.repeat)
                best[surface] = min(best[surface], st["render_ms"])
        result["cost"] = {"field": "spheres", "renderer": st.get("renderer"), "threads": 2,
                          "size": f"{CAMERA['w']}x{CAMERA['h']}", "voxel_render_ms": best["voxel"],
                          "smooth_render_ms": best["smooth"], "ratio": best["smooth"] / best["voxel"],
                          "load_average": os.getloadavg()[0]}
    text = json.dumps(result, indent=1)
    with open(args.out, "w") as o:
        o.write(text + "\n")
    print(text)


if __name__ == "__main__":
    sys.exit(main())
