#!/usr/bin/python3
"""Normal side of bench/peers.py: the normal each program shades every pixel with, and the angle
between octrace's and VTK's where both draw the surface.

    /usr/bin/python3 bench/peers/normals.py JOB.json OUT.json

JOB: {"camera_pos", "look_at", "up": "x,y,z" (the scene's camera),
      "lights": [[x, y, z], ...] (camera space, the directions octrace's EXRs were lit from),
      "octrace": {MODE: [EXR, ...] (one per light)}, "vtk": {GRID: PNG (vtk_peer.py's normals mode)},
      "thumb_dir": DIR, "prefix": TEXT, "thumb_width": 480}

* octrace: each EXR is a frame with --ambient 0 --colour 1,1,1 --light L, so its linear R is
  |n . l| (two-sided Lambert, Shading.cpp) for the normal n octrace shades the pixel with; from
  the lights x, y, z, x+y, x+z, y+z (camera space) come |n_x|, |n_y|, |n_z| and the products
  n_x n_y, n_x n_z, n_y n_z (2 I_ab^2 = n_a^2 + n_b^2 + 2 n_a n_b), which give the signs relative to
  the largest component: n up to its sign, which two-sided shading does not see either. Surface
  pixels: a finite Z.
* VTK: normalize(2 rgb / 255 - 1) in world space, turned to camera space; surface pixels: not
  the black background.
* The angle between two normals is that between the lines they span, acos |n1 . n2| (degrees):
  both programs light both sides alike. Mean, median, 90th and 99th percentile over the pixels
  both draw as surface.
Thumbnails: every normal map as RGB 255 (n + 1) / 2 in camera space (sign chosen with n_z >= 0,
towards the viewer), cropped to the common window of the surface pixels and scaled to
thumb_width, background white; and the angle of each octrace mode against each VTK grid as grey
(white 0 degrees, black 20 degrees or more), pixels only one program draws red.
"""
import json
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.dont_write_bytecode = True  # keep bench/peers/ free of __pycache__
sys.path.insert(0, HERE)
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from exr import read_exr  # noqa: E402
from images import read_png, write_png  # noqa: E402

LIGHTS = [(1, 0, 0), (0, 1, 0), (0, 0, 1), (1, 1, 0), (1, 0, 1), (0, 1, 1)]
ANGLE_BLACK_DEG = 20.0


def vec(text):
    return np.array([float(v) for v in str(text).split(",")])


def camera_basis(job):
    """right, up, back of octrace's camera (Camera::basis)."""
    eye, look, up = vec(job["camera_pos"]), vec(job["look_at"]), vec(job["up"])
    back = eye - look
    back /= np.linalg.norm(back)
    right = np.cross(up, back)
    right /= np.linalg.norm(right)
    return right, np.cross(back, right), back


def octrace_normals(exrs):
    """Camera-space normals (h, w, 3) and the surface mask from the six lit frames."""
    frames = [read_exr(p, ("R", "Z")) for p in exrs]
    mask = np.isfinite(frames[0]["Z"])
    i = [f["R"].astype(np.float64) for f in frames]
    a = np.stack([i[0], i[1], i[2]], axis=-1)  # |n_x|, |n_y|, |n_z|
    sq = a * a
    prod = {(0, 1): i[3] ** 2 - 0.5 * (sq[..., 0] + sq[..., 1]), (0, 2): i[4] ** 2 - 0.5 * (sq[..., 0] + sq[..., 2]),
            (1, 2): i[5] ** 2 - 0.5 * (sq[..., 1] + sq[..., 2])}  # n_a n_b, from 2 I_ab^2 = n_a^2 + n_b^2 + 2 n_a n_b
    ref = np.argmax(a, axis=-1)
    n = np.zeros_like(a)
    for r in range(3):
        sel = ref == r
        for c in range(3):
            if c == r:
                n[..., c][sel] = a[..., c][sel]
            else:
                p = prod[(min(r, c), max(r, c))]
                n[..., c][sel] = np.where(p[sel] < 0, -1.0, 1.0) * a[..., c][sel]
    length = np.linalg.norm(n, axis=-1, keepdims=True)
    mask &= length[..., 0] > 0.5  # |n| = 1 up to the half floats' rounding
    return n / np.where(length > 0, length, 1.0), mask


def vtk_normals(png, basis):
    rgb = read_png(png).astype(np.float64)
    mask = rgb.max(axis=-1) > 0
    w = rgb / 127.5 - 1.0
    c = np.stack([w @ b for b in basis], axis=-1)  # world -> camera
    length = np.linalg.norm(c, axis=-1, keepdims=True)
    mask &= length[..., 0] > 0.5
    return c / np.where(length > 0, length, 1.0), mask


def crop_box(masks):
    ys, xs = np.nonzero(np.logical_or.reduce(masks))
    h, w = masks[0].shape
    pad = int(0.02 * max(h, w))
    return max(0, xs.min() - pad), max(0, ys.min() - pad), min(w, xs.max() + pad + 1), min(h, ys.max() + pad + 1)


def main():
    job_path, out_json = sys.argv[1:3]
    with open(job_path) as f:
        job = json.load(f)
    assert [tuple(l) for l in job["lights"]] == LIGHTS, "the lights must be x, y, z, x+y, x+z, y+z"
    basis = camera_basis(job)
    normals = {}
    for mode, exrs in job["octrace"].items():
        normals["octrace_" + mode] = octrace_normals(exrs)
    for grid, png in job["vtk"].items():
        normals["vtk_" + grid] = vtk_normals(png, basis)
    x0, y0, x1, y1 = crop_box([m for _, m in normals.values()])
    out = {"crop": [int(x0), int(y0), int(x1), int(y1)], "angle_black_deg": ANGLE_BLACK_DEG, "maps": {}, "pairs": {}}
    tw = int(job["thumb_width"])
    for name, (n, m) in normals.items():
        face = np.where(n[..., 2:3] < 0, -n, n)
        rgb = np.where(m[..., None], np.clip(np.rint((face + 1.0) * 127.5), 0, 255), 255).astype(np.uint8)
        thumb = os.path.join(job["thumb_dir"], "%s_normals_%s.png" % (job["prefix"], name))
        write_png(thumb, rgb[y0:y1, x0:x1], tw)
        out["maps"][name] = {"surface_pixels": int(m.sum()), "thumb": os.path.basename(thumb)}
    for mode in job["octrace"]:
        no, mo = normals["octrace_" + mode]
        for grid in job["vtk"]:
            nv, mv = normals["vtk_" + grid]
            both = mo & mv
            ang = np.degrees(np.arccos(np.clip(np.abs((no * nv).sum(-1)), 0.0, 1.0)))
            a = ang[both]
            grey = np.clip(255.0 * (1.0 - ang / ANGLE_BLACK_DEG), 0, 255)
            img = np.full(no.shape, 255, dtype=np.uint8)
            img[both] = grey[both][:, None].astype(np.uint8)
            img[mo != mv] = (220, 40, 40)
            thumb = os.path.join(job["thumb_dir"], "%s_normals_angle_%s_%s.png" % (job["prefix"], mode, grid))
            write_png(thumb, img[y0:y1, x0:x1], tw)
            out["pairs"]["%s_vs_%s" % (mode, grid)] = {
                "octrace": mode, "vtk": grid, "pixels_both": int(both.sum()), "pixels_only_octrace": int((mo & ~mv).sum()),
                "pixels_only_vtk": int((mv & ~mo).sum()), "mean_deg": float(a.mean()), "median_deg": float(np.median(a)),
                "p90_deg": float(np.percentile(a, 90)), "p99_deg": float(np.percentile(a, 99)),
                "thumb": os.path.basename(thumb)}
    with open(out_json, "w") as f:
        json.dump(out, f, indent=2)


if __name__ == "__main__":
    main()
