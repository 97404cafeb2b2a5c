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
import subprocess
import sys
import tempfile

import numpy as np

from exr import read_exr

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
# A torus about the z axis through TORUS_CENTRE (radii in world units: ring 9, tube 4, i.e. 8
# samples): a surface that curves two ways (a saddle on its inner side), as the tests' torus.
# Measured as the spheres are, without the breakdown (whose casters march shells of spheres).
TORUS_CENTRE, TORUS_RING, TORUS_TUBE = (16.0, 16.0, 16.0), 9.0, 4.0
CAMERA = dict(pos=(52.0, -30.0, 38.0), look=(16.0, 16.0, 16.0), up=(0.0, 0.0, 1.0), fov=30.0, w=640, h=480)


def sphere_field(spheres):
    x = np.arange(N) * SPACING
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    f = np.full(X.shape, -1e9, dtype=np.float64)
    for (cx, cy, cz), r in spheres:
        f = np.maximum(f, r - np.sqrt((X - cx) ** 2 + (Y - cy) ** 2 + (Z - cz) ** 2))
    return f.astype(np.float32)


def torus_distance(p):
    """Signed distance of the points p[..., 3] to the torus, positive inside (the field)."""
    q = p - np.array(TORUS_CENTRE)
    ring = np.sqrt(q[..., 0] ** 2 + q[..., 1] ** 2) - TORUS_RING
    return TORUS_TUBE - np.sqrt(ring ** 2 + q[..., 2] ** 2)


def torus_field():
    x = np.arange(N) * SPACING
    X, Y, Z = np.meshgrid(x, x, x, indexing="ij")
    return torus_distance(np.stack([X, Y, Z], axis=-1)).astype(np.float32)


def torus_depth():
    """The analytic ray cast of the torus: sphere tracing of its exact distance function, to 1e-10
    (inf where a ray misses)."""
    eye, d = camera_rays()
    D = d.reshape(-1, 3)
    t = np.zeros(len(D))
    depth = np.full(len(D), np.inf)
    live = np.arange(len(D))
    for _ in range(100000):
        if not len(live):
            break
        dist = -torus_distance(eye + t[live, None] * D[live])
        hit = dist < 1e-10
        depth[live[hit]] = t[live[hit]]
        t[live] += np.maximum(dist, 0.0)
        live = live[~hit & (t[live] < 200.0)]
    return depth.reshape(d.shape[:2])


def write_nrrd(path, f):
    header = ("NRRD0004\n# spheres for scripts/smooth_targets.py\ntype: float\ndimension: 3\nspace dimension: 3\n"
              f"sizes: {N} {N} {N}\nspace directions: ({SPACING},0,0) (0,{SPACING},0) (0,0,{SPACING})\n"
              "kinds: domain domain domain\nendian: little\nencoding: raw\nspace origin: (0,0,0)\ncontent: spheres\n\n")
    with open(path, "wb") as o:
        o.write(header.encode())
        # NRRD is x fastest: the array is indexed [x, y, z], so write it in Fortran order.
        o.write(np.asfortranarray(f).tobytes(order="F"))


def read_exr_z(path):
    """The Z channel of an OpenEXR file as float32 rows."""
    return read_exr(path, ("Z",))["Z"]


def camera_rays():
    """The eye and the unit direction of every pixel's ray, rows from the top."""
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
    return eye, d


def sphere_span(eye, d, centre, r):
    """Entry and exit distance of each ray through the sphere (NaN where it misses)."""
    oc = eye - np.array(centre)
    bq = (d * oc).sum(-1)
    disc = bq * bq - (oc @ oc - r * r)
    root = np.sqrt(np.where(disc >= 0, disc, np.nan))
    return -bq - root, -bq + root


def analytic_depth(spheres):
    eye, d = camera_rays()
    depth = np.full(d.shape[:2], np.inf)
    for centre, r in spheres:
        t, _ = sphere_span(eye, d, centre, r)
        depth = np.where(np.isfinite(t) & (t > 0) & (t < depth), t, depth)
    return depth


# ---- Where the depth error comes from (the "breakdown" of each field) ----
# Two more casters of the same rays, in float64 numpy, independent of octrace:
#   "interpolant": the trilinear interpolant of the samples themselves (no octree, no
#     quantization): what an exact renderer of the sampled field draws; its error against the
#     spheres is the sampling's, not the renderer's;
#   "quantized corners": the same with, in each voxel of octrace's lattice, the trilinear
#     interpolant of its 8 corner values quantized as encodeCorners does (Octree.cpp): what the
#     renderer is asked to draw from its 8 bytes per voxel.
# Both march each ray in steps of MARCH_STEP world units through a shell around each sphere
# (from radius r + 0.1 to r - 0.3: the interpolant of this concave field lies inside the sphere
# by less than 0.1) and bisect the first step that ends inside (value >= 0) to 1e-9.
MARCH_STEP = 0.001


def trilinear_at(values, origin, step, p):
    """Trilinear interpolation of the grid `values` (indexed [x, y, z], point i at origin + i
    step) at the points p[..., 3], clamped to the grid's cells."""
    g = (p - origin) / step
    i0 = np.clip(np.floor(g).astype(np.int64), 0, np.array(values.shape) - 2)
    t = g - i0
    out = 0.0
    for q in range(8):
        o = ((q >> 2) & 1, (q >> 1) & 1, q & 1)
        w = 1.0
        for a in range(3):
            w = w * (t[..., a] if o[a] else 1.0 - t[..., a])
        out = out + w * values[i0[..., 0] + o[0], i0[..., 1] + o[1], i0[..., 2] + o[2]]
    return out


def lattice_values(f, origin, side, depth):
    """The field's trilinear values at the corners of the depth-`depth` voxel lattice of the cube
    (origin, side), in float32 as the builder's FieldSampler::corner gives them."""
    n = (1 << depth) + 1
    out = f.astype(np.float64)
    for a in range(3):
        g = np.clip((origin[a] + np.arange(n) * side / (1 << depth)) / SPACING, 0, N - 1)
        i0 = np.minimum(np.floor(g).astype(np.int64), N - 2)
        t = g - i0
        shape = [1, 1, 1]
        shape[a] = n
        t = t.reshape(shape)
        out = np.take(out, i0, axis=a) * (1 - t) + np.take(out, i0 + 1, axis=a) * t
    return out.astype(np.float32)


def quantized_at(lattice, origin, voxel, p):
    """The interpolant octrace draws: in the voxel holding p, the trilinear interpolant of its 8
    corner values minus the iso value (0), quantized as encodeCorners (scaled by the largest
    magnitude to +-127, rounded half away from zero, a negative corner never 0)."""
    g = (p - origin) / voxel
    v0 = np.clip(np.floor(g).astype(np.int64), 0, lattice.shape[0] - 2)
    u = g - v0
    corners = [lattice[v0[..., 0] + ((q >> 2) & 1), v0[..., 1] + ((q >> 1) & 1), v0[..., 2] + (q & 1)].astype(np.float64)
               for q in range(8)]
    m = np.max(np.abs(corners), axis=0)
    m = np.where(m > 0, m, 1.0)
    out = 0.0
    for q, c in enumerate(corners):
        x = 127.0 * c / m
        k = np.sign(x) * np.floor(np.abs(x) + 0.5)
        k = np.where((c < 0) & (k == 0), -1.0, k)
        w = 1.0
        for a, bit in enumerate(((q >> 2) & 1, (q >> 1) & 1, q & 1)):
            w = w * (u[..., a] if bit else 1.0 - u[..., a])
        out = out + w * k
    return out


def march_depth(spheres, value):
    """The distance along each pixel's ray to the first point where value(p) >= 0 in a shell
    around one of the spheres (inf: none)."""
    eye, d = camera_rays()
    D = d.reshape(-1, 3)
    depth = np.full(len(D), np.inf)
    for centre, r in spheres:
        a, b = sphere_span(eye, D, centre, r + 0.1)
        inner, _ = sphere_span(eye, D, centre, r - 0.3)
        b = np.where(np.isfinite(inner), inner, b)
        idx = np.nonzero(np.isfinite(a) & (b > 0))[0]
        a, b, Di = np.maximum(a[idx], 0.0), b[idx], D[idx]
        lo, hi = a.copy(), np.full(len(idx), np.nan)
        live = np.arange(len(idx))
        k = 0
        while len(live):
            k += 1
            t = np.minimum(a[live] + k * MARCH_STEP, b[live])
            inside = value(eye + t[:, None] * Di[live]) >= 0
            hi[live[inside]] = t[inside]
            lo[live[~inside]] = t[~inside]
            live = live[~inside & (t < b[live])]
        found = np.nonzero(np.isfinite(hi))[0]
        lo, hi = lo[found], hi[found]
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            inside = value(eye + mid[:, None] * Di[found]) >= 0
            hi = np.where(inside, mid, hi)
            lo = np.where(inside, lo, mid)
        cell = idx[found]
        depth[cell] = np.minimum(depth[cell], hi)
    return depth.reshape(d.shape[:2])


def breakdown(spheres, f, truth, rendered, reference, stats):
    """Splits the smooth renderer's depth error (docs/dev/smooth-surfaces.md, Measurements)."""
    origin = np.array([float(v) for v in str(stats["cube_origin"]).split(",")])
    side, depth = float(stats["cube_side"]), int(stats["depth"])
    voxel = side / (1 << depth)
    samples = f.astype(np.float64)
    interp = march_depth(spheres, lambda p: trilinear_at(samples, np.zeros(3), SPACING, p))
    lattice = lattice_values(f, origin, side, depth)
    quant = march_depth(spheres, lambda p: quantized_at(lattice, origin, voxel, p))
    hit_t = np.isfinite(truth)

    def errors(z, against):
        both = np.isfinite(z) & np.isfinite(against) & hit_t
        return np.abs(z[both] - against[both]) / SPACING

    def summary(z):
        e = errors(z, truth)
        both = np.isfinite(z) & hit_t
        return {"pixels_hit": int(np.isfinite(z).sum()),
                "depth_error_median_spacings": float(np.median(e)),
                "depth_error_p99_spacings": float(np.percentile(e, 99)),
                "silhouette_iou": float(both.sum() / (np.isfinite(z) | hit_t).sum()),
                "pixels_over_1_spacing": int((e > 1).sum()),
                "pixels_over_0.2_spacing": int((e > 0.2).sum())}

    def agreement(z, other):
        e = errors(z, other) * SPACING / voxel
        return {"pixels_compared": int(len(e)), "pixels_hit_differently": int((np.isfinite(z) != np.isfinite(other)).sum()),
                "depth_difference_p99_voxels": float(np.percentile(e, 99)),
                "depth_difference_max_voxels": float(e.max()),
                "pixels_over_1e-3_voxel": int((e > 1e-3).sum())}

    # The pixels the renderer gets wrong by more than the target: what the interpolant of the
    # samples does there.
    with np.errstate(invalid="ignore"):  # inf - inf where neither hits
        e_r = np.abs(rendered - truth) / SPACING
        e_i = np.abs(interp - truth) / SPACING
    bad = np.isfinite(rendered) & hit_t & (e_r > 0.2)
    return {
        "voxel_size": voxel, "march_step": MARCH_STEP,
        "interpolant_of_the_samples": summary(interp),
        "quantized_corners": summary(quant),
        "renderer": summary(rendered),
        "renderer_vs_quantized_corners": agreement(rendered, quant),
        "reference_vs_quantized_corners": agreement(reference, quant),
        "quantized_corners_vs_interpolant": agreement(quant, interp),
        "renderer_over_0.2": {
            "pixels": int(bad.sum()),
            "interpolant_also_over_0.2": int((bad & (e_i > 0.2)).sum()),
            "interpolant_also_over_0.1": int((bad & (e_i > 0.1)).sum()),
            "renderer_on_another_surface": int((bad & (e_r > 1)).sum()),
            "interpolant_on_another_surface": int((bad & (e_i > 1)).sum()),
        },
    }


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
            f = sphere_field(spheres)
            write_nrrd(field, f)
            runs = [("voxel", "voxel", ()), ("smooth", "smooth", ()),
                    ("smooth reference", "smooth", ("--renderer", "reference"))]
            depths = {}
            for label, surface, extra in runs:
                out = os.path.join(tmp, label.replace(" ", "_") + ".exr")
                st = render(args.octrace, field, out, surface, extra)
                depths[label] = read_exr_z(out).astype(np.float64)
                m = measure(depths[label], truth)
                m.update(renderer=st.get("renderer"), depth=st.get("depth"), bytes_per_voxel=st.get("bytes_per_voxel"),
                         boundary_voxels=st.get("boundary_voxels"))
                entry["modes"][label] = m
                stats = st
            entry["breakdown"] = breakdown(spheres, f, truth, depths["smooth"], depths["smooth reference"], stats)
            result["fields"][name] = entry
        # The torus: the same modes and measures, no breakdown.
        truth = torus_depth()
        entry = {"torus": {"centre": TORUS_CENTRE, "ring_radius": TORUS_RING, "tube_radius": TORUS_TUBE}, "modes": {}}
        field = os.path.join(tmp, "torus.nrrd")
        write_nrrd(field, torus_field())
        for label, surface, extra in [("voxel", "voxel", ()), ("smooth", "smooth", ()),
                                      ("smooth reference", "smooth", ("--renderer", "reference"))]:
            out = os.path.join(tmp, label.replace(" ", "_") + ".exr")
            st = render(args.octrace, field, out, surface, extra)
            m = measure(read_exr_z(out).astype(np.float64), truth)
            m.update(renderer=st.get("renderer"), depth=st.get("depth"), bytes_per_voxel=st.get("bytes_per_voxel"),
                     boundary_voxels=st.get("boundary_voxels"))
            entry["modes"][label] = m
        result["fields"]["torus"] = entry
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
