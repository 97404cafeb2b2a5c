#!/usr/bin/python3
"""VTK peer: the isosurface by flying edges (isomesh.py), drawn by VTK's OpenGL renderer.

Run by bench/peers.py as
    LP_NUM_THREADS=N xvfb-run -a -s "-screen 0 WxHx24" /usr/bin/python3 bench/peers/vtk_peer.py SPEC OUT.json OUT.png
SPEC (JSON) holds the scene (input, var, iso, region, depth, camera, size), `grid` ("native" or
"lattice", see isomesh.py), `threads` (vtkSMPTools threads for flying edges; LP_NUM_THREADS sets
Mesa llvmpipe's rasterizer threads to the same number) and `frames`. Every time is measured in
this process with time.perf_counter(); each frame ends with WaitForCompletion (glFinish) so that
the time covers the whole rasterization.

Shading as close to octrace's as VTK's fixed pipeline allows: one directional light fixed to the
camera (camera space direction --light, default 0.4,0.6,1), two-sided lighting, ambient 0.15 +
diffuse 0.85, no specular, colour --colour (default 0.85,0.62,0.35), white background; point
normals by vtkPolyDataNormals on the final world-space mesh (counted in the extraction time).
Camera: position, focal point, view up and view angle (VTK's view angle is vertical, as octrace's
--fov); clipping range from ResetCameraClippingRange.

With "normals": true in SPEC (bench/peers.py, normals step), the same mesh at the same camera is
drawn once, unlit, coloured by its point normals as direct RGB scalars (255 (n + 1) / 2): OpenGL
interpolates them across each triangle as it interpolates the normal for Phong shading, so
normalize(2 rgb / 255 - 1) is the normal VTK shades each pixel with (to 8 bits a component);
black background. No times are measured then.

With "mesh_out": PATH in SPEC, the final mesh (points, point normals, triangles) is also written
there for the Embree peer (bench/peers/embree_peer.cpp reads it), after the extraction is timed.
"""
import json
import os
import statistics
import sys
import time

sys.dont_write_bytecode = True  # keep bench/peers/ free of __pycache__
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import isomesh  # noqa: E402
from isomesh import vec  # noqa: E402


def main():
    spec_path, out_json, out_png = sys.argv[1:4]
    with open(spec_path) as f:
        spec = json.load(f)
    import numpy as np
    import vtk
    from vtk.util import numpy_support as ns

    threads = int(spec["threads"])
    vtk.vtkSMPTools.Initialize(threads)
    res = {"peer": "vtk", "grid": spec["grid"], "threads": threads, "vtk_version": vtk.vtkVersion.GetVTKVersion(),
           "smp_backend": vtk.vtkSMPTools.GetBackend() if hasattr(vtk.vtkSMPTools, "GetBackend") else None,
           "lp_num_threads": os.environ.get("LP_NUM_THREADS")}

    # --- extraction (timed: flying edges + masked-cell removal + world mapping + normals) ---
    m = isomesh.extract(spec)
    info = m["info"]
    t0 = time.perf_counter()
    pd = vtk.vtkPolyData()
    vp = vtk.vtkPoints()
    vp.SetData(ns.numpy_to_vtk(m["points"], deep=1))
    pd.SetPoints(vp)
    conn = m["triangles"].ravel()
    offsets = np.arange(0, len(conn) + 1, 3, dtype=np.int64)
    cells = vtk.vtkCellArray()
    cells.SetData(ns.numpy_to_vtk(offsets, deep=1, array_type=vtk.VTK_ID_TYPE),
                  ns.numpy_to_vtk(conn, deep=1, array_type=vtk.VTK_ID_TYPE))
    pd.SetPolys(cells)
    nrm = vtk.vtkPolyDataNormals()
    nrm.SetInputData(pd)
    nrm.SplittingOff()
    nrm.ConsistencyOff()
    nrm.ComputePointNormalsOn()
    nrm.Update()
    mesh = nrm.GetOutput()
    info["normals_ms"] = (time.perf_counter() - t0) * 1e3
    if spec.get("mesh_out"):  # the mesh for the Embree peer (embree_peer.cpp: OCTMESH1), not timed
        pts = ns.vtk_to_numpy(mesh.GetPoints().GetData()).astype("<f4")
        nrms = ns.vtk_to_numpy(mesh.GetPointData().GetNormals()).astype("<f4")
        tris = ns.vtk_to_numpy(mesh.GetPolys().GetConnectivityArray()).astype("<i4")
        with open(spec["mesh_out"], "wb") as f:
            f.write(b"OCTMESH1" + np.array([len(pts), len(tris) // 3], dtype="<u8").tobytes())
            f.write(pts.tobytes() + nrms.tobytes() + tris.tobytes())
    info["extract_ms"] = info["flying_edges_ms"] + info["mask_and_map_ms"] + info["normals_ms"]
    res.update(info)

    # --- rendering ---
    width, height = [int(v) for v in spec["size"].split("x")]
    ren = vtk.vtkRenderer()
    ren.SetBackground(1, 1, 1)
    ren.AutomaticLightCreationOff()
    ren.TwoSidedLightingOn()
    light = vtk.vtkLight()
    light.SetLightTypeToCameraLight()  # position in camera space: x right, y up, z towards the viewer
    light.SetPosition(*vec(spec.get("light", "0.4,0.6,1")))
    light.SetFocalPoint(0, 0, 0)
    light.SetPositional(False)
    ren.AddLight(light)
    normals_only = bool(spec.get("normals"))
    if normals_only:
        n = ns.vtk_to_numpy(mesh.GetPointData().GetNormals()).astype(np.float64)
        rgb = ns.numpy_to_vtk(np.clip(np.rint((n + 1.0) * 127.5), 0, 255).astype(np.uint8), deep=1)
        rgb.SetName("normal_rgb")
        mesh.GetPointData().SetScalars(rgb)
        ren.SetBackground(0, 0, 0)
    mapper = vtk.vtkPolyDataMapper()
    mapper.SetInputData(mesh)
    if normals_only:
        mapper.ScalarVisibilityOn()
        mapper.SetScalarModeToUsePointData()
        mapper.SetColorModeToDirectScalars()
    else:
        mapper.ScalarVisibilityOff()
    actor = vtk.vtkActor()
    actor.SetMapper(mapper)
    prop = actor.GetProperty()
    prop.SetLighting(not normals_only)
    prop.SetColor(*vec(spec.get("colour", "0.85,0.62,0.35")))
    prop.SetAmbient(0.15)
    prop.SetDiffuse(0.85)
    prop.SetSpecular(0.0)
    prop.SetInterpolationToGouraud()
    ren.AddActor(actor)
    cam = ren.GetActiveCamera()
    cam.SetPosition(*vec(spec["camera_pos"]))
    cam.SetFocalPoint(*vec(spec["look_at"]))
    cam.SetViewUp(*vec(spec["up"]))
    cam.SetViewAngle(float(spec["fov"]))  # vertical, as octrace's --fov (UseHorizontalViewAngle is off)
    ren.ResetCameraClippingRange()
    rw = vtk.vtkRenderWindow()
    rw.SetOffScreenRendering(1)
    rw.SetMultiSamples(0)
    rw.SetSize(width, height)
    rw.AddRenderer(ren)
    t = time.perf_counter()
    rw.Render()
    rw.WaitForCompletion()
    res["first_frame_ms"] = (time.perf_counter() - t) * 1e3  # includes shader compilation and upload
    for line in (rw.ReportCapabilities() or "").splitlines():
        if "renderer string" in line:
            res["gl_renderer"] = line.split(":", 1)[1].strip()
        if "OpenGL version string" in line:
            res["gl_version"] = line.split(":", 1)[1].strip()
    times = []
    for _ in range(0 if normals_only else int(spec.get("frames", 7))):
        cam.Modified()
        t = time.perf_counter()
        rw.Render()
        rw.WaitForCompletion()
        times.append((time.perf_counter() - t) * 1e3)
    res["frame_ms"] = times
    if times:
        # The fastest frame, as every program of the comparison is timed (bench/peers.py).
        res["render_ms"] = min(times)
        res["render_ms_median"] = statistics.median(times)
    grab = vtk.vtkWindowToImageFilter()
    grab.SetInput(rw)
    grab.ReadFrontBufferOff()
    grab.Update()
    pw = vtk.vtkPNGWriter()
    pw.SetFileName(out_png)
    pw.SetInputConnection(grab.GetOutputPort())
    pw.Write()
    res["width"], res["height"] = width, height
    with open(out_json, "w") as f:
        json.dump(res, f, indent=2)


if __name__ == "__main__":
    main()
