"""The scene's isosurface as a triangle mesh in octrace's world coordinates, by VTK's flying edges.

Used by vtk_peer.py (which draws it) and vdb_peer.py (which turns it into a level set).

grid "native": the field's samples themselves (60 x 50 x 20 for the Levitus scenes, the NRRD's
samples for an analytic scene: uniform, so the depth mapping below is the identity). x and y are
uniform in km but depth is not, and vtkFlyingEdges3D takes only vtkImageData (uniform spacing),
so flying edges runs in index space for depth (k = level number) and every vertex's z is then
mapped through the level depths, piecewise linearly. Marching-cubes vertices lie on cell edges
and the index -> z map is affine within each cell, so this gives exactly the triangles that
marching cubes on the rectilinear grid (vtkContourFilter on a vtkRectilinearGrid) would give, at
flying-edges speed.

grid "lattice": the trilinear field at the corners of octrace's 2^depth voxel lattice over its
scene cube (field.lattice: the same values octrace classifies), uniform spacing, straight to
flying edges: the resolution octrace draws.

Masked samples (land, sea floor): octrace never forms a surface in a cell with a masked corner.
Here masked samples are set to iso - (value range) - 1 for flying edges, and afterwards every
triangle whose cell (found from its centroid in index space) has a masked corner is removed: the
walls that the fill value makes along coasts and the sea floor go, and exactly the cells octrace
can draw keep their triangles.
"""
import os
import sys
import time

import numpy as np

sys.dont_write_bytecode = True  # keep bench/peers/ free of __pycache__
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import field as fieldmod  # noqa: E402


def vec(text):
    return [float(v) for v in str(text).split(",")]


def extract(spec):
    """Returns dict(points[n,3] float64 world km, triangles[m,3] int64, info{...})."""
    import vtk
    from vtk.util import numpy_support as ns

    info = {"grid": spec["grid"]}
    t0 = time.perf_counter()
    fld = fieldmod.load_spec(spec)
    iso = float(spec["iso"])
    if spec["grid"] == "native":
        vals = fld["values"]
        nz, ny, nx = vals.shape
        dx = (fld["x"][-1] - fld["x"][0]) / (nx - 1)
        dy = (fld["y"][-1] - fld["y"][0]) / (ny - 1)
        if np.max(np.abs(fld["x"] - (fld["x"][0] + dx * np.arange(nx)))) > 1e-6 * abs(dx) or \
           np.max(np.abs(fld["y"] - (fld["y"][0] + dy * np.arange(ny)))) > 1e-6 * abs(dy):
            raise SystemExit("isomesh: the x or y axis is not uniform")
        zlev = fld["z"]

        def to_world(p):
            return np.column_stack((fld["x"][0] + p[:, 0] * dx, fld["y"][0] + p[:, 1] * dy,
                                    np.interp(p[:, 2], np.arange(nz), zlev)))
    else:
        co, cs = fieldmod.cube(fld)
        off, vals, h = fieldmod.lattice(fld, co, cs, int(spec["depth"]))
        nz, ny, nx = vals.shape
        origin = [co[a] + off[a] * h for a in range(3)]
        info["lattice_spacing_km"] = h
        info["cube_origin"] = co
        info["cube_side"] = cs

        def to_world(p):
            return np.column_stack((origin[0] + p[:, 0] * h, origin[1] + p[:, 1] * h, origin[2] + p[:, 2] * h))
    info["grid_dims"] = [nx, ny, nz]
    info["vertical_scale"] = fld["vertical_scale"]
    info["lon0"], info["lat0"] = fld.get("lon0"), fld.get("lat0")
    info["load_ms"] = (time.perf_counter() - t0) * 1e3

    masked = np.isnan(vals)
    info["masked_samples"] = int(masked.sum())
    valid = vals[~masked]
    fill = np.float32(iso - (float(valid.max()) - float(valid.min())) - 1.0)
    filled = np.where(masked, fill, vals).astype(np.float32)
    bad = np.zeros((nz - 1, ny - 1, nx - 1), dtype=bool)  # cells with a masked corner
    for dz in (0, 1):
        for dy_ in (0, 1):
            for dx_ in (0, 1):
                bad |= masked[dz:nz - 1 + dz, dy_:ny - 1 + dy_, dx_:nx - 1 + dx_]
    if spec["grid"] == "lattice":
        # octrace's boundary voxels: cells with 8 valid corners, some >= iso and some < iso
        # (core/src/build/OctreeBuilder.cpp); must equal its `boundary_voxels` when the field is the same.
        cmin = np.full(bad.shape, np.inf, dtype=np.float32)
        cmax = np.full(bad.shape, -np.inf, dtype=np.float32)
        for dz in (0, 1):
            for dy_ in (0, 1):
                for dx_ in (0, 1):
                    c = filled[dz:nz - 1 + dz, dy_:ny - 1 + dy_, dx_:nx - 1 + dx_]
                    np.minimum(cmin, c, out=cmin)
                    np.maximum(cmax, c, out=cmax)
        isof = np.float32(iso)
        info["boundary_cells"] = int(np.count_nonzero((cmax >= isof) & (cmin < isof) & ~bad))
        del cmin, cmax
    img = vtk.vtkImageData()
    img.SetDimensions(nx, ny, nz)
    img.SetOrigin(0, 0, 0)
    img.SetSpacing(1, 1, 1)
    arr = ns.numpy_to_vtk(filled.ravel(order="C"), deep=1)  # x fastest, then y, then z
    arr.SetName("f")
    img.GetPointData().SetScalars(arr)

    fe = vtk.vtkFlyingEdges3D()
    fe.SetInputData(img)
    fe.SetValue(0, iso)
    fe.ComputeNormalsOff()
    fe.ComputeGradientsOff()
    fe.ComputeScalarsOff()
    t1 = time.perf_counter()
    fe.Update()
    t2 = time.perf_counter()
    raw = fe.GetOutput()
    pts = ns.vtk_to_numpy(raw.GetPoints().GetData()).astype(np.float64)
    polys = ns.vtk_to_numpy(raw.GetPolys().GetConnectivityArray()).reshape(-1, 3)
    cen = pts[polys].mean(axis=1)
    ci = np.clip(np.floor(cen).astype(np.int64), 0, [nx - 2, ny - 2, nz - 2])
    keep = ~bad[ci[:, 2], ci[:, 1], ci[:, 0]]
    tris = polys[keep]
    used, inv = np.unique(tris.ravel(), return_inverse=True)
    wpts = to_world(pts[used])
    t3 = time.perf_counter()
    info["flying_edges_ms"] = (t2 - t1) * 1e3
    info["mask_and_map_ms"] = (t3 - t2) * 1e3
    info["triangles_flying_edges"] = int(len(polys))
    info["triangles_removed_masked"] = int((~keep).sum())
    info["triangles"] = int(len(tris))
    info["points"] = int(len(used))
    return {"points": np.ascontiguousarray(wpts), "triangles": inv.reshape(-1, 3).astype(np.int64), "info": info}
