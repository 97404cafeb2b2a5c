#!/usr/bin/python3
"""Image side of bench/peers.py, with VTK's PNG reader and writer (no X needed):

    /usr/bin/python3 bench/peers/images.py JOB.json OUT.json

JOB: {"reference": NAME, "images": {NAME: {"png": PATH, "background": [r,g,b] (0..255)}},
      "thumb_dir": DIR, "prefix": TEXT, "thumb_width": 480}
For every image: the foreground mask (pixels that differ from its background colour), and against
the reference image (octrace's): pixels hit by both, by only one, and the agreement
(both / either). Thumbnails: every image cropped to one common window (the union of all
foreground boxes, padded by 2 %) and scaled to thumb_width, background shown white, so that
they can be compared with each other; plus, for each non-reference image, a mask difference
(grey = both hit, red = only the reference, blue = only this peer).
With "also_against": [NAME, ...] in JOB, every other image is compared with those too
(`vs_NAME`, the same counts; bench/peers.py: octrace's smooth surface, which draws the trilinear
interpolant the peers' lattice meshes approximate, where the voxel image draws the voxels' boxes).
"""
import json
import os
import sys

import numpy as np


def read_png(path):
    import vtk
    from vtk.util import numpy_support as ns
    r = vtk.vtkPNGReader()
    r.SetFileName(path)
    r.Update()
    img = r.GetOutput()
    w, h, _ = img.GetDimensions()
    a = ns.vtk_to_numpy(img.GetPointData().GetScalars()).reshape(h, w, -1)
    return np.ascontiguousarray(a[::-1, :, :3])  # row 0 at the top


def write_png(path, rgb, width):
    import vtk
    from vtk.util import numpy_support as ns
    h, w, _ = rgb.shape
    img = vtk.vtkImageData()
    img.SetDimensions(w, h, 1)
    arr = ns.numpy_to_vtk(np.ascontiguousarray(rgb[::-1]).reshape(-1, 3), deep=1, array_type=vtk.VTK_UNSIGNED_CHAR)
    arr.SetNumberOfComponents(3)
    img.GetPointData().SetScalars(arr)
    rs = vtk.vtkImageResize()
    rs.SetInputData(img)
    rs.SetResizeMethodToOutputDimensions()
    rs.SetOutputDimensions(width, max(1, int(round(h * width / w))), 1)
    rs.InterpolateOn()
    wr = vtk.vtkPNGWriter()
    wr.SetFileName(path)
    wr.SetInputConnection(rs.GetOutputPort())
    wr.Write()


def compare(m, ref):
    """Pixels of the masks m and ref: both, only ref, only m, agreement = both / either."""
    both = int((m & ref).sum())
    either = int((m | ref).sum())
    return {"both": both, "only_reference": int((ref & ~m).sum()), "only_this": int((m & ~ref).sum()),
            "agreement": both / either if either else 1.0}


def main():
    job_path, out_json = sys.argv[1:3]
    with open(job_path) as f:
        job = json.load(f)
    imgs, masks = {}, {}
    for name, d in job["images"].items():
        a = read_png(d["png"])
        bg = np.array(d["background"], dtype=np.uint8)
        imgs[name] = (a, bg)
        masks[name] = np.any(a != bg, axis=2)
    ref = job["reference"]
    out = {"images": {}}
    boxes = []
    for name, m in masks.items():
        ys, xs = np.nonzero(m)
        entry = {"png": job["images"][name]["png"], "width": int(m.shape[1]), "height": int(m.shape[0]),
                 "foreground_pixels": int(m.sum())}
        if len(xs):
            entry["foreground_box"] = [int(xs.min()), int(ys.min()), int(xs.max()), int(ys.max())]
            boxes.append(entry["foreground_box"])
        if name != ref and m.shape == masks[ref].shape:
            entry["vs_reference"] = compare(m, masks[ref])
        for other in job.get("also_against", []):
            if other in masks and name not in (ref, other) and m.shape == masks[other].shape:
                entry["vs_" + other] = compare(m, masks[other])
        out["images"][name] = entry
    H, W = masks[ref].shape
    if boxes:
        x0 = min(b[0] for b in boxes)
        y0 = min(b[1] for b in boxes)
        x1 = max(b[2] for b in boxes)
        y1 = max(b[3] for b in boxes)
        pad = int(0.02 * W)
        x0, y0, x1, y1 = max(0, x0 - pad), max(0, y0 - pad), min(W - 1, x1 + pad), min(H - 1, y1 + pad)
        # keep the frame's aspect ratio
        cw, ch = x1 - x0 + 1, y1 - y0 + 1
        if cw * H > ch * W:
            grow = int(round(cw * H / W)) - ch
            y0 = max(0, y0 - grow // 2)
            y1 = min(H - 1, y0 + ch + grow - 1)
        else:
            grow = int(round(ch * W / H)) - cw
            x0 = max(0, x0 - grow // 2)
            x1 = min(W - 1, x0 + cw + grow - 1)
    else:
        x0, y0, x1, y1 = 0, 0, W - 1, H - 1
    out["crop"] = [x0, y0, x1, y1]
    tw = int(job.get("thumb_width", 480))
    os.makedirs(job["thumb_dir"], exist_ok=True)
    for name, (a, bg) in imgs.items():
        shown = a.copy()
        shown[~masks[name]] = 255
        p = os.path.join(job["thumb_dir"], "%s_%s.png" % (job["prefix"], name))
        write_png(p, shown[y0:y1 + 1, x0:x1 + 1], tw)
        out["images"][name]["thumb"] = p
        if name != ref and masks[name].shape == masks[ref].shape:
            d = np.full(a.shape, 255, dtype=np.uint8)
            d[masks[name] & masks[ref]] = (170, 170, 170)
            d[masks[ref] & ~masks[name]] = (220, 30, 30)
            d[masks[name] & ~masks[ref]] = (30, 60, 220)
            p = os.path.join(job["thumb_dir"], "%s_%s_maskdiff.png" % (job["prefix"], name))
            write_png(p, d[y0:y1 + 1, x0:x1 + 1], tw)
            out["images"][name]["maskdiff"] = p
    with open(out_json, "w") as f:
        json.dump(out, f, indent=2)


if __name__ == "__main__":
    main()
