#!/usr/bin/env python3
"""Writes the 2-D (map) NetCDF fixtures and their invalid-corpus files (run once; the outputs
are committed). Needs the venv's netCDF4 and NumPy, and the shared Levitus atlas
(../shared/data/ocean/levitus_climatology.cdf beside the checkout, or OCTRACE_SHARED_DATA).

levitus_sst_2d.nc: Levitus's TEMP at its first level (0 m) as a 2-D field sst(lat, lon), CF
  attributes (degrees_east / degrees_north, _FillValue -1e10 on land as in the atlas), the
  atlas's own longitudes 20.5..379.5 and latitudes -89.5..89.5; float32, NetCDF-3 classic.
  Its values are the atlas's level-0 samples bit for bit.
oisst_like_zlev.nc: the same level as NOAA OISST v2.1 stores SST: sst(time = 1, zlev = 1, lat,
  lon), int16 with scale_factor 0.01 and _FillValue -999, zlev 0 m (units "meters", axis Z,
  positive down), time in "days since 1978-01-01 12:00:00", longitudes 0.5..359.5 (the atlas's
  20.5..379.5 rotated by 20 columns so the file starts at 0.5 as OISST does at 0.125).
bipolar_like.nc: a small curvilinear grid as CMIP6 ocean models store it: 2-D lat(y, x) and
  lon(y, x) with CF `bounds` lat_bnds(y, x, 4) / lon_bnds(y, x, 4), tos(y, x) and
  thetao(lev, y, x) naming them in `coordinates`; a 24 x 16 grid rotated 30 degrees over the
  North Atlantic, values the atlas's nearest samples. For the choice of variables only: the
  cell-bounds and coordinate variables must never be offered as fields.
../invalid/invalid_map_all_masked.nc: a 2-D sst(lat, lon) whose every sample is _FillValue.
../invalid/invalid_no_field.nc: only a 0-D and 1-D variables (a station's depth profile).
"""
import os

import netCDF4
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.abspath(os.path.join(HERE, "..", "..", ".."))
SHARED = os.environ.get("OCTRACE_SHARED_DATA", os.path.join(os.path.dirname(ROOT), "shared", "data"))
if not os.path.isdir(SHARED):
    SHARED = "/work/shared/data"
LEVITUS = os.path.join(SHARED, "ocean", "levitus_climatology.cdf")
FILL = np.float32(-1e10)


def levitus_level0():
    with netCDF4.Dataset(LEVITUS) as d:
        d.set_auto_maskandscale(False)
        lon = d["XAXLEVITR"][:].astype(np.float64)
        lat = d["YAXLEVITR"][:].astype(np.float64)
        temp = d["TEMP"][0, :, :].astype(np.float32)
    return lon, lat, temp


def axes(d, lon, lat, lon_name="lon", lat_name="lat"):
    d.createDimension(lat_name, len(lat))
    d.createDimension(lon_name, len(lon))
    v = d.createVariable(lat_name, "f8", (lat_name,))
    v.units, v.standard_name, v.axis = "degrees_north", "latitude", "Y"
    v[:] = lat
    v = d.createVariable(lon_name, "f8", (lon_name,))
    v.units, v.standard_name, v.axis = "degrees_east", "longitude", "X"
    v[:] = lon


def sst_2d(lon, lat, temp):
    with netCDF4.Dataset(os.path.join(HERE, "levitus_sst_2d.nc"), "w", format="NETCDF3_CLASSIC") as d:
        d.Conventions = "CF-1.8"
        d.title = "Levitus 1982 annual temperature at 0 m as a 2-D field (octrace test fixture)"
        axes(d, lon, lat)
        v = d.createVariable("sst", "f4", ("lat", "lon"), fill_value=FILL)
        v.units, v.long_name, v.standard_name = "degC", "sea surface temperature", "sea_surface_temperature"
        v.set_auto_maskandscale(False)
        v[:] = temp


def oisst_like(lon, lat, temp):
    shift = 20  # 20.5 + 340 = 360.5 wraps to 0.5: the file starts at 0.5 as OISST does
    lon = np.concatenate([lon[-shift:] - 360.0, lon[:-shift]])
    temp = np.concatenate([temp[:, -shift:], temp[:, :-shift]], axis=1)
    with netCDF4.Dataset(os.path.join(HERE, "oisst_like_zlev.nc"), "w", format="NETCDF3_CLASSIC") as d:
        d.Conventions = "CF-1.6, ACDD-1.3"
        d.title = "Levitus 1982 annual temperature at 0 m laid out as NOAA OISST v2.1 (octrace test fixture)"
        d.createDimension("time", 1)
        d.createDimension("zlev", 1)
        t = d.createVariable("time", "f4", ("time",))
        t.units, t.long_name, t.axis, t.calendar = "days since 1978-01-01 12:00:00", "Center time of the day", "T", "standard"
        t[:] = [16071.0]  # 2022-01-01
        z = d.createVariable("zlev", "f4", ("zlev",))
        z.units, z.long_name, z.axis, z.positive = "meters", "Sea surface height", "Z", "down"
        z[:] = [0.0]
        axes(d, lon, lat)
        v = d.createVariable("sst", "i2", ("time", "zlev", "lat", "lon"), fill_value=np.int16(-999))
        v.units, v.long_name, v.scale_factor, v.add_offset = "Celsius", "Daily sea surface temperature", np.float32(0.01), np.float32(0.0)
        v.valid_min, v.valid_max = np.int16(-300), np.int16(4500)
        v.set_auto_maskandscale(False)
        packed = np.where(temp == FILL, -999, np.round(temp / 0.01)).astype(np.int16)
        v[0, 0, :, :] = packed


def bipolar_like(lon1, lat1, temp0):
    ny, nx = 16, 24
    j, i = np.meshgrid(np.arange(ny + 1) - ny / 2, np.arange(nx + 1) - nx / 2, indexing="ij")  # cell corners
    a = np.radians(30.0)
    corner_lon = -40.0 + 1.5 * (i * np.cos(a) - j * np.sin(a))
    corner_lat = 40.0 + 1.5 * (i * np.sin(a) + j * np.cos(a))
    lon = 0.25 * (corner_lon[:-1, :-1] + corner_lon[1:, :-1] + corner_lon[1:, 1:] + corner_lon[:-1, 1:])
    lat = 0.25 * (corner_lat[:-1, :-1] + corner_lat[1:, :-1] + corner_lat[1:, 1:] + corner_lat[:-1, 1:])

    def nearest(field):
        ii = np.clip(np.round(np.mod(lon - lon1[0], 360.0)).astype(int), 0, len(lon1) - 1)
        jj = np.clip(np.round(lat - lat1[0]).astype(int), 0, len(lat1) - 1)
        return field[..., jj, ii]

    with netCDF4.Dataset(LEVITUS) as d:
        d.set_auto_maskandscale(False)
        temp = d["TEMP"][:3, :, :].astype(np.float32)
    with netCDF4.Dataset(os.path.join(HERE, "bipolar_like.nc"), "w", format="NETCDF3_CLASSIC") as d:
        d.Conventions = "CF-1.7 CMIP-6.2"
        d.createDimension("y", ny)
        d.createDimension("x", nx)
        d.createDimension("vertices", 4)
        d.createDimension("lev", 3)
        lev = d.createVariable("lev", "f8", ("lev",))
        lev.units, lev.positive, lev.axis, lev.standard_name = "m", "down", "Z", "depth"
        lev[:] = [0.0, 10.0, 20.0]
        for name, centre, corners, std, units in (("lat", lat, corner_lat, "latitude", "degrees_north"),
                                                  ("lon", lon, corner_lon, "longitude", "degrees_east")):
            v = d.createVariable(name, "f8", ("y", "x"))
            v.units, v.standard_name, v.bounds = units, std, name + "_bnds"
            v[:] = centre
            b = d.createVariable(name + "_bnds", "f8", ("y", "x", "vertices"))
            b[:] = np.stack([corners[:-1, :-1], corners[:-1, 1:], corners[1:, 1:], corners[1:, :-1]], axis=-1)
        tos = d.createVariable("tos", "f4", ("y", "x"), fill_value=FILL)
        tos.units, tos.standard_name, tos.coordinates = "degC", "sea_surface_temperature", "lat lon"
        tos[:] = nearest(temp0)
        th = d.createVariable("thetao", "f4", ("lev", "y", "x"), fill_value=FILL)
        th.units, th.standard_name, th.coordinates = "degC", "sea_water_potential_temperature", "lat lon"
        th[:] = nearest(temp)


def invalid():
    out = os.path.join(HERE, "..", "invalid")
    with netCDF4.Dataset(os.path.join(out, "invalid_map_all_masked.nc"), "w", format="NETCDF3_CLASSIC") as d:
        axes(d, np.arange(4.0), np.arange(3.0))
        v = d.createVariable("sst", "f4", ("lat", "lon"), fill_value=FILL)
        v.units = "degC"
        v.set_auto_maskandscale(False)
        v[:] = np.full((3, 4), FILL, np.float32)
    with netCDF4.Dataset(os.path.join(out, "invalid_no_field.nc"), "w", format="NETCDF3_CLASSIC") as d:
        d.createDimension("depth", 5)
        z = d.createVariable("depth", "f8", ("depth",))
        z.units, z.positive = "m", "down"
        z[:] = [0, 10, 20, 50, 100]
        t = d.createVariable("temp", "f4", ("depth",))
        t.units = "degC"
        t[:] = [20, 18, 15, 11, 8]
        s = d.createVariable("station", "i4", ())
        s.long_name = "station number"
        s.assignValue(7)


lon, lat, temp = levitus_level0()
sst_2d(lon, lat, temp)
oisst_like(lon, lat, temp)
bipolar_like(lon, lat, temp)
invalid()
