#!/usr/bin/env python3
"""Writes the curvilinear seeds of fuzz_netcdf_cf and fuzz_curvilinear_grid (run once; committed).

Uses NumPy and netCDF4 from the project's venv and the grid constructions of
tests/data/netcdf/make_curvilinear.py, at toy sizes:
  fuzz_netcdf_cf/cf_tripolar_tiny.nc   tripolar-like 16 x 7 grid (periodic x, north fold), 2 levels
  fuzz_netcdf_cf/cf_rotated_tiny.nc    rotated-pole 6 x 5 grid with 1-D rlon/rlat and 2-D lat/lon
  fuzz_netcdf_cf/invalid_curvilinear_*.nc   the invalid corpus's curvilinear files
  fuzz_curvilinear_grid/*              the target's binary layout (see fuzz_curvilinear_grid.cpp)
"""
import os
import shutil
import struct
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "data")
sys.path.insert(0, os.path.join(DATA, "netcdf"))
import make_curvilinear as mc  # noqa: E402


def synthetic(lon, lat, depth):
    """A field from the coordinates, land where it is negative (a stand-in for the atlas)."""
    t = 20.0 * np.cos(np.radians(lat)) + 2.0 * np.sin(np.radians(3 * lon)) - 4.0
    return np.stack([np.where(t > 0, t - k, np.nan) for k in range(len(depth))])


def main():
    cf = os.path.join(HERE, "fuzz_netcdf_cf")
    grid = os.path.join(HERE, "fuzz_curvilinear_grid")
    os.makedirs(grid, exist_ok=True)
    depth = np.array([0.0, 100.0])
    lon, lat = mc.tripolar(nx=16, lat_south=-60.0, lat_cap=60.0, step=30.0, ncap=2)
    mc.write(os.path.join(cf, "cf_tripolar_tiny.nc"), "tiny tripolar", ("y", "x"), lon, lat, depth,
             synthetic(lon, lat, depth), lambda d: None, fmt="NETCDF3_CLASSIC")
    seeds = {"tripolar": (lon, lat, 0, None)}
    rlon, rlat = np.arange(-10.0, 11.0, 4.0), np.arange(-8.0, 9.0, 4.0)
    rl, rp = np.meshgrid(rlon, rlat)
    lon, lat = mc.rotated_to_geographic(rl, rp, 140.0, 50.0)

    def axes(d):
        p = d.createVariable("rotated_pole", "i4")
        p.grid_mapping_name = "rotated_latitude_longitude"
        p.grid_north_pole_longitude, p.grid_north_pole_latitude = 140.0, 50.0
        for name, values, sn in (("rlon", rlon, "grid_longitude"), ("rlat", rlat, "grid_latitude")):
            v = d.createVariable(name, "f8", (name,))
            v.units, v.standard_name = "degrees", sn
            v[:] = values

    mc.write(os.path.join(cf, "cf_rotated_tiny.nc"), "tiny rotated pole", ("rlat", "rlon"), lon, lat, depth,
             synthetic(lon, lat, depth), axes, fmt="NETCDF3_CLASSIC")
    seeds["rotated"] = (lon, lat, 34, (-60.0, -20.0, 20.0, 60.0))
    # Across the dateline: longitudes stored 176 .. 180, -180 .. -171.
    i, j = np.meshgrid(np.arange(8.0), np.arange(6.0))
    seeds["dateline"] = ((177.0 + i - 0.2 * j + 180.0) % 360.0 - 180.0, -10.0 + j + 0.2 * i, 17, (178.0, -178.0, -8.0, -6.0))
    for name, (lon, lat, res, region) in seeds.items():
        ny, nx = lon.shape
        head = bytes([(nx - 2) % 16, (ny - 2) % 16, res, 1 if region else 0])
        body = struct.pack("<4d", *(region or (0, 0, 0, 0)))
        plane = synthetic(lon, lat, [0.0])[0]
        for a in (lon, lat, np.nan_to_num(plane, nan=0.0)):
            body += struct.pack("<%dd" % a.size, *a.ravel())
        with open(os.path.join(grid, name), "wb") as f:
            f.write(head + body)
    for n in ("shape", "nan", "latitude"):
        shutil.copy(os.path.join(DATA, "invalid", "invalid_curvilinear_%s.nc" % n), cf)


if __name__ == "__main__":
    main()
