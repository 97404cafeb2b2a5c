"""The scene's scalar field for the peer renderers, in octrace's world coordinates.

Two sources: a NetCDF variable over a longitude/latitude region (`load`, the ocean scenes) or a
NRRD file written by `octrace sample NAME --samples N` (`load_nrrd`, the analytic scenes: the
samples octrace generates for the input `analytic:NAME:N`, float32, so the same numbers).

Reads the NetCDF variable with the `netCDF4` module (Debian `python3-netcdf4`) and maps it the
way octrace's reader does (io/src/netcdf/GeoGrid.cpp, contract in ARCHITECTURE.md "Coordinates"):
kilometres, x = R (lon - lon0) cos(lat0), y = R (lat - lat0), z = -depth_km * vertical_scale,
R = 6371, (lon0, lat0) the centre of the region, longitudes unwrapped from the region's west edge,
missing_value/_FillValue masked (NaN here). Axes are returned increasing (z: deepest first).

`lattice()` evaluates the trilinear field at the corners of octrace's 2^depth voxel lattice over
its scene cube, exactly as octrace's builder does (core/src/build/OctreeBuilder.cpp: FieldSampler), so a
peer can work at the same resolution: a corner is NaN when any sample its trilinear stencil uses
is masked (a weight of exactly 0 does not use the sample).
"""
import math

import numpy as np

R_KM = 6371.0
EPS_DEG = 1e-7


def load(path, var, region, vertical_scale=None):
    """Returns dict(x, y, z, values[nz, ny, nx] float32 with NaN = masked, lon0, lat0,
    vertical_scale, lons, lats, depths_m)."""
    import netCDF4
    ds = netCDF4.Dataset(path)
    try:
        v = ds.variables[var]
        dims = v.dimensions
        if len(dims) != 3:
            raise ValueError("%s: variable %s is not 3-D" % (path, var))
        zname, yname, xname = dims
        lon = np.asarray(ds.variables[xname][:], dtype=np.float64)
        lat = np.asarray(ds.variables[yname][:], dtype=np.float64)
        zvar = ds.variables[zname]
        depth = np.asarray(zvar[:], dtype=np.float64)
        units = getattr(zvar, "units", "m").lower()
        depth_km = depth / 1000.0 if units in ("m", "meters", "metres", "meter", "metre") else depth
        if getattr(zvar, "positive", "down").lower() == "up":
            depth_km = -depth_km
        v.set_auto_mask(True)
        data = v[:]
        values = np.ma.filled(np.ma.asarray(data, dtype=np.float32), np.nan).astype(np.float32)
    finally:
        ds.close()
    values[~np.isfinite(values)] = np.nan

    l0, l1, b0, b1 = region
    if l1 < l0:
        l1 += 360.0
    u = l0 + np.mod(lon - l0 + EPS_DEG, 360.0) - EPS_DEG
    xsel = np.nonzero(u <= l1 + EPS_DEG)[0]
    xsel = xsel[np.argsort(u[xsel])]
    ysel = np.nonzero((lat >= b0 - EPS_DEG) & (lat <= b1 + EPS_DEG))[0]
    ysel = ysel[np.argsort(lat[ysel])]
    zsel = np.argsort(-depth_km)  # deepest first: z increases
    lon0, lat0 = 0.5 * (l0 + l1), 0.5 * (b0 + b1)
    deg = math.pi / 180.0
    x = R_KM * (u[xsel] - lon0) * deg * math.cos(lat0 * deg)
    y = R_KM * (lat[ysel] - lat0) * deg
    if vertical_scale is None:
        horizontal = max(x[-1] - x[0], y[-1] - y[0])
        vertical_scale = 0.25 * horizontal / (depth_km.max() - depth_km.min())
    z = -depth_km[zsel] * vertical_scale + 0.0
    vals = values[np.ix_(zsel, ysel, xsel)]
    return dict(x=x, y=y, z=z, values=np.ascontiguousarray(vals), lon0=lon0, lat0=lat0,
                vertical_scale=vertical_scale, lons=u[xsel], lats=lat[ysel], depths_m=depth_km[zsel] * 1000.0)


def load_nrrd(path):
    """The NRRD files octrace writes (io/src/nrrd/NrrdWriter.cpp): float, raw, little endian, axes
    along x, y, z (diagonal space directions). Returns the same dict as load() with uniform axes
    (origin + i * spacing, as ScalarField::worldFromGrid) and `origin`, `spacing` for lattice()."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"\n\n")
    head = {}
    for line in data[:end].decode("utf-8").splitlines()[1:]:
        if line.startswith("#") or ":" not in line:
            continue
        k, v = line.split(":", 1)
        head[k.strip()] = v.lstrip("=").strip()
    if head.get("type") != "float" or head.get("encoding") != "raw" or head.get("endian", "little") != "little":
        raise ValueError("%s: not a raw little-endian float NRRD" % path)
    dims = [int(v) for v in head["sizes"].split()]
    dirs = [[float(c) for c in t.strip("()").split(",")] for t in head["space directions"].replace(") (", ")|(").split("|")]
    spacing = []
    for a in range(3):
        if any(dirs[a][b] != 0.0 for b in range(3) if b != a) or not dirs[a][a] > 0:
            raise ValueError("%s: only axis-aligned, increasing grids are read here" % path)
        spacing.append(dirs[a][a])
    origin = [float(c) for c in head["space origin"].strip("()").split(",")]
    n = dims[0] * dims[1] * dims[2]
    values = np.frombuffer(data[end + 2:end + 2 + 4 * n], dtype="<f4").astype(np.float32).reshape(dims[2], dims[1], dims[0])
    values = values.copy()
    values[~np.isfinite(values)] = np.nan
    x, y, z = [origin[a] + np.arange(dims[a]) * spacing[a] for a in range(3)]
    return dict(x=x, y=y, z=z, values=np.ascontiguousarray(values), origin=origin, spacing=spacing, vertical_scale=None)


def load_spec(spec):
    """The field a peer spec names: "format" "nrrd" (load_nrrd) or NetCDF (load, with var and region)."""
    if spec.get("format") == "nrrd":
        return load_nrrd(spec["input"])
    return load(spec["input"], spec["var"], [float(v) for v in str(spec["region"]).split(",")], spec.get("vertical_scale"))


def cube(field):
    """octrace's scene cube (core/src/build/OctreeBuilder.cpp): centred on the grid's world bounds, side
    = the largest extent. Returns (origin[3], side)."""
    lo = [field[a][0] for a in "xyz"]
    hi = [field[a][-1] for a in "xyz"]
    side = max(h - l for l, h in zip(lo, hi))
    return [0.5 * (l + h) - 0.5 * side for l, h in zip(lo, hi)], side


def _locate(coords, w, uniform=None):
    """octrace's FieldSampler::locate for the positions w along an increasing axis:
    (inside, i0, i1, t). uniform = (origin, spacing) for a uniform axis (octrace keeps no
    coordinates then and divides by the spacing), None for a rectilinear one."""
    n = len(coords)
    if uniform is not None:
        idx = (w - uniform[0]) / uniform[1]
        inside = np.ones(len(w), dtype=bool)
    else:
        span = coords[-1] - coords[0]
        inside = (w >= coords[0] - 1e-9 * span) & (w <= coords[-1] + 1e-9 * span)
        i = np.clip(np.searchsorted(coords, w, side="right") - 1, 0, n - 2)
        idx = i + (w - coords[i]) / (coords[i + 1] - coords[i])
    inside &= (idx >= -1e-7) & (idx <= (n - 1) + 1e-7)
    idx = np.clip(idx, 0.0, n - 1)
    i0 = np.minimum(np.floor(idx).astype(np.int64), n - 1)
    t = (idx - i0).astype(np.float32)
    i1 = np.where((t > 0) & (i0 + 1 < n), i0 + 1, i0)
    t = np.where(i1 == i0, np.float32(0), t)
    return inside, i0, i1, t


def _interp_axis(a, axis, i0, i1, t):
    lo = np.take(a, i0, axis=axis)
    hi = np.take(a, i1, axis=axis)
    shape = [1] * a.ndim
    shape[axis] = len(t)
    tt = t.reshape(shape)
    out = lo * (1 - tt) + hi * tt
    # weight exactly 0: octrace does not read the other sample (i1 == i0 there anyway)
    return out.astype(np.float32)


def lattice(field, cube_origin, cube_side, depth):
    """Trilinear field at the lattice corners c * h + cube_origin (h = cube_side / 2^depth) that lie
    inside the grid. Returns (offset ijk of the first corner kept, array[nz, ny, nx], h)."""
    n = (1 << depth) + 1
    h = cube_side / (1 << depth)
    axes = [field["x"], field["y"], field["z"]]
    sel = []
    for a in range(3):
        w = cube_origin[a] + np.arange(n) * h
        uniform = (field["origin"][a], field["spacing"][a]) if "spacing" in field else None
        inside, i0, i1, t = _locate(axes[a], w, uniform)
        keep = np.nonzero(inside)[0]
        sel.append((keep[0], i0[keep], i1[keep], t[keep]))
    v = field["values"]  # [z, y, x]
    (ox, xi0, xi1, xt), (oy, yi0, yi1, yt), (oz, zi0, zi1, zt) = sel
    v = _interp_axis(v, 2, xi0, xi1, xt)
    v = _interp_axis(v, 1, yi0, yi1, yt)
    v = _interp_axis(v, 0, zi0, zi1, zt)
    return (int(ox), int(oy), int(oz)), np.ascontiguousarray(v), h
