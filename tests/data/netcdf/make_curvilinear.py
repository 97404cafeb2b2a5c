#!/usr/bin/env python3
"""Writes curvilinear-grid test files from the real Levitus 1982 atlas (the outputs are committed).

Usage: make_curvilinear.py [LEVITUS.cdf] [OUTDIR] [--only nemo_sst]
(defaults: ../shared/data/ocean/levitus_climatology.cdf beside the checkout, this folder).
Needs netCDF4 and NumPy (the project's venv).

rotated_natl.nc: a rotated-pole grid over the North Atlantic, as regional models write it
  (CF 5.6): rlon -30..30, rlat -22..22 step 0.5 degrees (1-D, standard_name grid_longitude /
  grid_latitude) in a frame whose north pole sits at 140 E, 50 N (grid centre 40 W, 40 N), with
  the true 2-D lat(rlat, rlon) and lon(rlat, rlon) named by temp's `coordinates` attribute.
tripolar_global.nc: a global tripolar-like grid (x periodic, 240 columns, longitudes stored in
  -180..180 so the dateline is a seam inside the array): regular 1.5-degree rows from 78 S to
  60 N, above them a bipolar Arctic cap whose two grid poles sit on land at 60 N, 70 E and
  60 N, 110 W (Murray 1996's construction: ellipses in the polar stereographic plane), the top
  row folding onto itself mirrored (column i meets column 239 - i) over the Arctic Ocean.
nemo_sst_2d.nc: a NEMO-like 2-D map on the tripolar grid: sosstsst(time_counter, y, x) (float32,
  _FillValue 1e20 on land), the surface level of tripolar_global.nc's temperature (the same
  interpolation), with nav_lat(y, x)/nav_lon(y, x) named by its `coordinates` as NEMO names them
  and one time step (time_counter, seconds since 1900-01-01, with time_centered beside it).
Both 3-D files: temp(depth, y, x) as int16 (scale 0.001, _FillValue -32767, zlib), the Levitus depth
levels, values interpolated bilinearly from Levitus's TEMP with its land: a point is land when
less than half of the bilinear weight falls on Levitus ocean, else the weighted mean of the
ocean neighbours.
"""
import os
import sys

import netCDF4
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
R = 6371.0


def levitus(path):
    d = netCDF4.Dataset(path)
    d.set_auto_mask(False)
    lon = d["XAXLEVITR"][:].astype(float)
    lat = d["YAXLEVITR"][:].astype(float)
    z = d["ZAXLEVITR"][:].astype(float)
    t = d["TEMP"][:].astype(float)
    t[t < -1e9] = np.nan
    d.close()
    return lon, lat, z, t


def interpolate(lon_a, lat_a, t_a, lon, lat):
    """Bilinear from the regular 1-degree atlas at (lon, lat) (2-D arrays), land-aware."""
    # Levitus: lon 0.5..359.5, lat -89.5..89.5, step 1.
    x = np.mod(lon - lon_a[0], 360.0)
    y = np.clip(lat - lat_a[0], 0.0, len(lat_a) - 1.000001)
    i0 = np.floor(x).astype(int)
    j0 = np.floor(y).astype(int)
    fx, fy = x - i0, y - j0
    i1 = (i0 + 1) % len(lon_a)
    j1 = np.minimum(j0 + 1, len(lat_a) - 1)
    out = np.full((t_a.shape[0],) + lon.shape, np.nan)
    corners = [(j0, i0, (1 - fx) * (1 - fy)), (j0, i1, fx * (1 - fy)), (j1, i1, fx * fy), (j1, i0, (1 - fx) * fy)]
    for k in range(t_a.shape[0]):
        ws = np.zeros(lon.shape)
        vs = np.zeros(lon.shape)
        for j, i, w in corners:
            v = t_a[k][j, i]
            ok = np.isfinite(v)
            ws += np.where(ok, w, 0.0)
            vs += np.where(ok, w * np.nan_to_num(v), 0.0)
        out[k] = np.where(ws >= 0.5, vs / np.maximum(ws, 1e-12), np.nan)
    return out


def rotated_to_geographic(rlon, rlat, pole_lon, pole_lat):
    """CF rotated_latitude_longitude: true longitude and latitude of rotated (rlon, rlat), degrees."""
    rl, rp = np.radians(rlon), np.radians(rlat)
    pl = np.radians(pole_lat)
    lat = np.arcsin(np.sin(rp) * np.sin(pl) + np.cos(rp) * np.cos(rl) * np.cos(pl))
    lon = np.radians(pole_lon - 180.0) + np.arctan2(np.cos(rp) * np.sin(rl),
                                                    np.sin(pl) * np.cos(rp) * np.cos(rl) - np.cos(pl) * np.sin(rp))
    return (np.degrees(lon) + 180.0) % 360.0 - 180.0, np.degrees(lat)


def tripolar(nx=240, lat_south=-78.0, lat_cap=60.0, step=1.5, ncap=20, pole_lon=70.0):
    """2-D lon, lat of a tripolar-like grid (ny x nx): regular rows up to lat_cap, then a bipolar cap."""
    theta = 2 * np.pi * (np.arange(nx) + 0.5) / nx  # angle from the first grid pole, counterclockwise
    south = np.arange(lat_south, lat_cap + 1e-9, step)
    lon_s = np.degrees(theta)[None, :] + pole_lon + 0 * south[:, None]
    lat_s = south[:, None] + 0 * theta[None, :]
    # Polar stereographic radius of the cap's edge; ellipses x = rc cos(theta), y = rc (1 - t) sin(theta)
    # shrink onto the segment between the two grid poles (the fold line).
    rc = 2 * R * np.tan(np.radians(90.0 - lat_cap) / 2)
    t = np.arange(1, ncap + 1) / (ncap + 0.5)
    X = rc * np.cos(theta)[None, :] + 0 * t[:, None]
    Y = rc * (1 - t)[:, None] * np.sin(theta)[None, :]
    r = np.hypot(X, Y)
    lat_c = 90.0 - 2 * np.degrees(np.arctan(r / (2 * R)))
    lon_c = np.degrees(np.arctan2(Y, X)) + pole_lon
    lon = np.vstack([lon_s, lon_c])
    lat = np.vstack([lat_s, lat_c])
    return (lon + 180.0) % 360.0 - 180.0, lat


def write(path, title, dims, lon, lat, depth, temp, extra, fmt="NETCDF4"):
    d = netCDF4.Dataset(path, "w", format=fmt)
    d.title = title
    d.Conventions = "CF-1.8"
    d.source = "interpolated from Levitus 1982 (levitus_climatology.cdf) by tests/data/netcdf/make_curvilinear.py"
    d.createDimension("depth", len(depth))
    d.createDimension(dims[0], lat.shape[0])
    d.createDimension(dims[1], lat.shape[1])
    v = d.createVariable("depth", "f4", ("depth",))
    v.units, v.positive, v.standard_name = "m", "down", "depth"
    v[:] = depth
    extra(d)
    for name, units, sn, data in (("lat", "degrees_north", "latitude", lat), ("lon", "degrees_east", "longitude", lon)):
        v = d.createVariable(name, "f8", dims, zlib=True)
        v.units, v.standard_name = units, sn
        v[:] = data
    v = d.createVariable("temp", "i2", ("depth",) + dims, zlib=True, complevel=9, fill_value=np.int16(-32767))
    v.set_auto_maskandscale(False)
    v.units = "degC"
    v.long_name = "temperature"
    v.standard_name = "sea_water_temperature"
    v.scale_factor = np.float32(0.001)
    v.add_offset = np.float32(0.0)
    v.coordinates = "lon lat"
    if "rotated_pole" in d.variables:
        v.grid_mapping = "rotated_pole"
    packed = np.where(np.isfinite(temp), np.round(np.nan_to_num(temp) / 0.001), -32767).astype(np.int16)
    v[:] = packed
    d.close()


def nemo_sst(path, lon, lat, sst):
    """A NEMO-like 2-D surface field on the grid (lon, lat): names and attributes as NEMO writes them."""
    d = netCDF4.Dataset(path, "w", format="NETCDF4")
    d.title = "Levitus surface temperature on a tripolar-like global grid, NEMO-like 2-D map (octrace test)"
    d.Conventions = "CF-1.6"
    d.source = "interpolated from Levitus 1982 (levitus_climatology.cdf) by tests/data/netcdf/make_curvilinear.py"
    d.createDimension("y", lat.shape[0])
    d.createDimension("x", lat.shape[1])
    d.createDimension("time_counter", None)
    for name, units, sn, data in (("nav_lat", "degrees_north", "latitude", lat),
                                  ("nav_lon", "degrees_east", "longitude", lon)):
        v = d.createVariable(name, "f4", ("y", "x"), zlib=True)
        v.units, v.standard_name, v.long_name = units, sn, sn.capitalize()
        v.nav_model = "grid_T"
        v[:] = data
    for name in ("time_counter", "time_centered"):
        v = d.createVariable(name, "f8", ("time_counter",))
        v.units, v.calendar, v.standard_name = "seconds since 1900-01-01 00:00:00", "gregorian", "time"
        v.long_name = "Time axis" if name == "time_counter" else "Time axis (centered)"
        v[:] = [3155716800.0]  # 2000-01-01
    v = d.createVariable("sosstsst", "f4", ("time_counter", "y", "x"), zlib=True, fill_value=np.float32(1e20))
    v.units, v.standard_name = "degC", "sea_surface_temperature"
    v.long_name = "sea surface temperature"
    v.online_operation = "average"
    v.coordinates = "time_centered nav_lat nav_lon"
    v[:] = np.where(np.isfinite(sst), sst, np.float32(1e20))[None].astype(np.float32)
    d.close()


def main():
    args = sys.argv[1:]
    only_nemo = args[-2:] == ["--only", "nemo_sst"]  # writes only nemo_sst_2d.nc (the others are committed)
    args = args[:-2] if only_nemo else args
    src = args[0] if len(args) > 0 else os.path.join(HERE, "../../../../shared/data/ocean/levitus_climatology.cdf")
    out = args[1] if len(args) > 1 else HERE
    lon_a, lat_a, depth, t_a = levitus(src)

    rlon = np.arange(-30.0, 30.0 + 1e-9, 0.5)
    rlat = np.arange(-22.0, 22.0 + 1e-9, 0.5)
    lon, lat = rotated_to_geographic(rlon[None, :] + 0 * rlat[:, None], rlat[:, None] + 0 * rlon[None, :], 140.0, 50.0)

    def rotated_axes(d):
        p = d.createVariable("rotated_pole", "i4")
        p.grid_mapping_name = "rotated_latitude_longitude"
        p.grid_north_pole_longitude = 140.0
        p.grid_north_pole_latitude = 50.0
        for name, values, sn in (("rlon", rlon, "grid_longitude"), ("rlat", rlat, "grid_latitude")):
            v = d.createVariable(name, "f8", (name,))
            v.units, v.standard_name, v.axis = "degrees", sn, "X" if name == "rlon" else "Y"
            v[:] = values

    if not only_nemo:
        write(os.path.join(out, "rotated_natl.nc"), "Levitus temperature on a rotated-pole North Atlantic grid",
              ("rlat", "rlon"), lon, lat, depth, interpolate(lon_a, lat_a, t_a, lon, lat), rotated_axes)

    lon, lat = tripolar()
    surface = interpolate(lon_a, lat_a, t_a[:1], lon, lat)[0]
    nemo_sst(os.path.join(out, "nemo_sst_2d.nc"), lon, lat, surface)
    if only_nemo:
        return
    write(os.path.join(out, "tripolar_global.nc"), "Levitus temperature on a tripolar-like global grid",
          ("y", "x"), lon, lat, depth, interpolate(lon_a, lat_a, t_a, lon, lat), lambda d: None)


if __name__ == "__main__":
    main()
