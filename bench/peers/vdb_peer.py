#!/usr/bin/python3
"""OpenVDB peer, first half: the scene's isosurface as a narrow-band level set in a .vdb file,
for `vdb_render` (Debian libopenvdb-tools) to draw. Run by bench/peers.py as
    /usr/bin/python3 bench/peers/vdb_peer.py SPEC.json OUT.json OUT.vdb

Path: the isosurface mesh of the field sampled on octrace's own depth-N voxel lattice (isomesh.py,
grid "lattice": flying edges, masked cells removed, world km) -> pyopenvdb
FloatGrid.createLevelSetFromPolygons (OpenVDB's meshToVolume) with the voxel size of octrace's
voxels (cube side / 2^depth) and a half width of 4 voxels -> .vdb. The grid's index (0,0,0) sits
at the world origin, so its world coordinates are octrace's.

Why a shell: the ocean isosurfaces are open sheets (they end at the region's sides, the coasts and
the sea floor), and meshToVolume can only give an inside/outside sign to closed surfaces: on these
meshes every value comes out positive, i.e. an unsigned distance to the sheet. Its zero set has no
sign change for a ray tracer to find, so vdb_render is asked for the iso-value eps = 1 voxel
(`-isovalue`): the surface at distance one voxel from the sheet, a closed shell two voxels thick,
which from the camera looks like the sheet (octrace's boundary voxels are one voxel thick).
Half a voxel was tried: rays then step over the thin shell between two samples of the
intersector's linear search and leave dark seams.
A closed mesh (every edge shared by exactly two triangles: the spheres scene, whose balls all lie
inside the grid) comes out signed, negative inside; then the level set's own zero is drawn
(`isovalue` 0, `shell_voxels` 0). An open sheet can come out partly signed (some of Levitus S's
values are negative), so the mesh's edges decide, not the values.
"""
import json
import os
import sys
import time

sys.dont_write_bytecode = True  # keep bench/peers/ free of __pycache__
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import isomesh  # noqa: E402

HALF_WIDTH = 4.0
SHELL_VOXELS = 1.0


def closed_mesh(tris):
    """Whether every edge of the triangles is shared by exactly two of them."""
    import numpy as np
    e = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    e.sort(axis=1)
    _, counts = np.unique(e[:, 0].astype(np.int64) * (int(tris.max()) + 1) + e[:, 1], return_counts=True)
    return bool(len(counts)) and bool(np.all(counts == 2))


def main():
    spec_path, out_json, out_vdb = sys.argv[1:4]
    with open(spec_path) as f:
        spec = json.load(f)
    import numpy as np
    import pyopenvdb as vdb

    spec = dict(spec, grid="lattice")
    m = isomesh.extract(spec)
    info = dict(m["info"])
    h = info["lattice_spacing_km"]
    pts = m["points"].astype(np.float32)
    tris = m["triangles"].astype(np.int32)
    xf = vdb.createLinearTransform(voxelSize=h)
    t0 = time.perf_counter()
    grid = vdb.FloatGrid.createLevelSetFromPolygons(pts, triangles=tris, transform=xf, halfWidth=HALF_WIDTH)
    info["levelset_ms"] = (time.perf_counter() - t0) * 1e3
    grid.name = "isosurface"
    vmin, vmax = grid.evalMinMax()
    shell = 0.0 if closed_mesh(tris) else SHELL_VOXELS
    info.update({"peer": "openvdb", "openvdb_version": ".".join(str(v) for v in vdb.LIBRARY_VERSION),
                 "voxel_size_km": h, "half_width_voxels": HALF_WIDTH, "active_voxels": int(grid.activeVoxelCount()),
                 "leaf_nodes": int(grid.leafCount()), "mem_bytes": int(grid.memUsage()),
                 "value_min": float(vmin), "value_max": float(vmax), "background": float(grid.background),
                 "isovalue": shell * h, "shell_voxels": shell, "closed_mesh": shell == 0.0})
    t0 = time.perf_counter()
    vdb.write(out_vdb, grids=[grid])
    info["write_ms"] = (time.perf_counter() - t0) * 1e3
    info["vdb_bytes"] = os.path.getsize(out_vdb)
    with open(out_json, "w") as f:
        json.dump(info, f, indent=2)


if __name__ == "__main__":
    main()
