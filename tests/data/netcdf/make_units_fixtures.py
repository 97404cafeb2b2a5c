#!/usr/bin/env python3
"""Writes the unit test files from the shared Levitus atlas (run once; the .nc outputs are committed).

Needs netCDF4 and NumPy (the project's venv) and ../shared/data/ocean/levitus_climatology.cdf.
Both hold the North Atlantic of Levitus, longitudes 300.5..339.5, latitudes 20.5..59.5, all 20
levels (0..5000 m), TEMP as in the atlas (_FillValue/missing_value -1e10 on land), axes with the
atlas's attributes but for what each file changes:

levitus_cm.nc: the depth axis in centimetres, depth * 100 with units "centimeters" (as POP writes
  it); TEMP in "DEG C" as in the atlas. Rendered, it gives the picture of the atlas over
  --region 300,340,20,60.
levitus_kelvin.nc: TEMP + 273.15 with units "K" (float32, as the atlas); depth in metres.
  `--iso 10degC` on it gives the picture of `--iso 10` on the atlas.

Usage: make_units_fixtures.py [LEVITUS]
"""
import os
import sys

import netCDF4
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT = os.path.join(HERE, "..", "..", "..", "..", "shared", "data", "ocean", "levitus_climatology.cdf")
FILL = np.float32(-1e10)


def write(path, lons, lats, depths, depth_units, temp, temp_units):
    with netCDF4.Dataset(path, "w", format="NETCDF3_CLASSIC") as d:
        d.history = "octrace tests/data/netcdf/make_units_fixtures.py from levitus_climatology.cdf"
        for name, values in (("XAXLEVITR", lons), ("YAXLEVITR", lats), ("ZAXLEVITR", depths)):
            d.createDimension(name, len(values))
            v = d.createVariable(name, "f8", (name,))
            v[:] = values
        d["XAXLEVITR"].units = "degrees_east"
        d["YAXLEVITR"].units = "degrees_north"
        d["ZAXLEVITR"].units = depth_units
        d["ZAXLEVITR"].positive = "down"
        t = d.createVariable("TEMP", "f4", ("ZAXLEVITR", "YAXLEVITR", "XAXLEVITR"), fill_value=FILL)
        t.missing_value = FILL
        t.long_name = "TEMPERATURE"
        t.units = temp_units
        t[:] = temp


def main():
    src = sys.argv[1] if len(sys.argv) > 1 else DEFAULT
    with netCDF4.Dataset(src) as d:
        d.set_auto_mask(False)
        x, y, z = d["XAXLEVITR"][:], d["YAXLEVITR"][:], d["ZAXLEVITR"][:]
        i = np.nonzero((x >= 300) & (x <= 340))[0]
        j = np.nonzero((y >= 20) & (y <= 60))[0]
        temp = d["TEMP"][:, j[0]:j[-1] + 1, i[0]:i[-1] + 1].astype(np.float32)
    land = temp == FILL
    write(os.path.join(HERE, "levitus_cm.nc"), x[i], y[j], z * 100.0, "centimeters", temp, "DEG C")
    kelvin = np.where(land, FILL, temp + np.float32(273.15)).astype(np.float32)
    write(os.path.join(HERE, "levitus_kelvin.nc"), x[i], y[j], z, "METERS", kelvin, "K")


if __name__ == "__main__":
    main()
