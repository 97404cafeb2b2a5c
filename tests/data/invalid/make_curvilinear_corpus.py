#!/usr/bin/env python3
"""Writes the invalid curvilinear-grid inputs of the corpus (run once; the outputs are committed).

Uses netCDF4 from the project's venv (make_corpus.py needs ncgen, which these do not).
Each file: temp(depth, y, x) on 2 x 3 x 4 points with 2-D lat(y, x) and lon(y, x) named by its
`coordinates` attribute, broken as its name says (see README.md).
"""
import os

import netCDF4
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, lat_dims=("y", "x"), lat_shift=0.0, lon_nan=False):
    d = netCDF4.Dataset(os.path.join(HERE, name + ".nc"), "w", format="NETCDF3_CLASSIC")
    for n, s in (("depth", 2), ("y", 3), ("x", 4), ("y2", 2)):
        d.createDimension(n, s)
    v = d.createVariable("depth", "f8", ("depth",))
    v.units, v.positive = "m", "down"
    v[:] = [0.0, 10.0]
    shape = tuple(len(d.dimensions[n]) for n in lat_dims)
    lat = d.createVariable("lat", "f8", lat_dims)
    lat.units = "degrees_north"
    lat[:] = 40.0 + lat_shift + np.arange(shape[0])[:, None] + 0.2 * np.arange(shape[1])[None, :]
    lon = d.createVariable("lon", "f8", ("y", "x"))
    lon.units = "degrees_east"
    values = 140.0 + np.arange(4)[None, :] - 0.2 * np.arange(3)[:, None]
    if lon_nan:
        values[1, 2] = np.nan
    lon[:] = values
    t = d.createVariable("temp", "f4", ("depth", "y", "x"))
    t.units, t.coordinates = "degC", "lon lat"
    t[:] = np.arange(24, dtype=np.float32).reshape(2, 3, 4)
    d.close()


write("invalid_curvilinear_shape", lat_dims=("y2", "x"))
write("invalid_curvilinear_nan", lon_nan=True)
write("invalid_curvilinear_latitude", lat_shift=50.0)
