#!/usr/bin/env python3
"""Writes a small NetCDF time series from the Levitus annual climatology, for the studio's time
slider (tests/studio/StudioOceanTest.cpp and its screenshots).

levitus_seasons.nc: TEMP of ../shared/data/ocean/levitus_climatology.cdf over the North Atlantic
(longitudes 280.5 .. 359.5, latitudes 0.5 .. 69.5, the 20 levels) at four steps dated
2001-01-15, 04-15, 07-15 and 10-15 (days since 2001-01-01, CF standard calendar). The climatology
is annual: each step adds a made-up seasonal signal to it, warmest in July, strongest at the
surface and fading below 100 m (4 degC * cos(2 pi (month - 7) / 12) * exp(-depth / 100 m),
times the sine of the latitude), so that a surface moves from step to step. It is a test
fixture, not observations; the file says so in its `comment`. Land and sea floor stay missing
(-1e10, as in the source).

Usage: make_levitus_seasons.py LEVITUS_CDF OUT_NC  (needs numpy and netCDF4: app/python/requirements.txt)
"""
import sys

import numpy as np
from netCDF4 import Dataset

MISSING = -1e10


def main(source, out):
    with Dataset(source) as src:
        lon = src["XAXLEVITR"][:]
        lat = src["YAXLEVITR"][:]
        depth = src["ZAXLEVITR"][:]
        i = np.where((lon >= 280.0) & (lon < 360.0))[0]
        j = np.where((lat >= 0.0) & (lat < 70.0))[0]
        temp = np.ma.filled(src["TEMP"][:, j[0]:j[-1] + 1, i[0]:i[-1] + 1], MISSING).astype(np.float32)
    lon, lat = lon[i], lat[j]
    months = np.array([1, 4, 7, 10])
    days = np.array([14.0, 104.0, 195.0, 287.0])  # the 15th of each month in 2001
    with Dataset(out, "w", format="NETCDF3_CLASSIC") as d:
        d.comment = ("Test fixture: the Levitus 1982 annual TEMP climatology plus a made-up seasonal signal "
                     "(tests/data/netcdf/make_levitus_seasons.py); not observations")
        for name, values, attrs in (("time", days, {"units": "days since 2001-01-01", "calendar": "standard", "axis": "T"}),
                                    ("depth", depth, {"units": "m", "positive": "down"}),
                                    ("lat", lat, {"units": "degrees_north"}),
                                    ("lon", lon, {"units": "degrees_east"})):
            d.createDimension(name, len(values))
            v = d.createVariable(name, "f8", (name,))
            v.setncatts(attrs)
            v[:] = values
        t = d.createVariable("TEMP", "f4", ("time", "depth", "lat", "lon"), fill_value=np.float32(MISSING))
        t.units = "degC"
        t.long_name = "temperature (annual climatology plus a made-up seasonal signal)"
        fade = np.exp(-depth / 100.0)[:, None, None]
        north = np.sin(np.radians(lat))[None, :, None]
        for k, m in enumerate(months):
            season = (4.0 * np.cos(2.0 * np.pi * (m - 7) / 12.0) * fade * north).astype(np.float32)
            t[k] = np.where(temp == MISSING, MISSING, temp + season)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
