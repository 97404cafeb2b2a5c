#!/usr/bin/env python3
"""Writes the small NetCDF test fixtures (run once; the .cdl and .nc outputs are committed).

Needs `ncgen` (Debian package netcdf-bin).

dateline_cf: CF-style ocean grid, longitudes -177.5..177.5 step 5 (the dateline is the file's
  seam), latitudes stored north to south, depth 0/100/500 m positive down, a time dimension of
  length 1, temp(time, depth, lat, lon) with _FillValue. Each value encodes where it sits:
      temp = 100 * k + (lat + 90) + lon360 / 1000
  with k the stored depth index and lon360 the longitude in [0, 360). One land point
  (lon -177.5, lat -30, every depth) is _FillValue, one sample (lon 2.5, lat 10, k 2) is NaN.
  Written twice: NetCDF-3 classic (.nc) and NetCDF-4 (_nc4.nc).
packed_4d: t(time, lev, lat, lon) as int16 with scale_factor 0.5, add_offset 10 and _FillValue,
  time of length 2 (the reader takes the first step), levels 10/0 m without `positive`,
  latitudes in "degrees_N", longitudes "degrees_E" stored decreasing 360, 270, 180, 90, 0
  (360 and 0 are the same meridian). Raw values at time 0 are 0..29 in file order, one _FillValue.
cartesian: a non-geographic grid, density(z, y, x) = 100 z + 10 y + x (indices), x in km
  (0..8 step 2), y in km (40..10, decreasing), z without coordinate variable.
"""
import math
import os
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))


def ncgen(name, cdl, kinds):
    cdl_path = os.path.join(HERE, name + ".cdl")
    with open(cdl_path, "w") as f:
        f.write(cdl)
    for kind, suffix in kinds:
        subprocess.run(["ncgen", "-k", kind, "-o", os.path.join(HERE, name + suffix + ".nc"), cdl_path], check=True)


def dateline():
    lons = [-177.5 + 5 * i for i in range(72)]
    lats = [30.0, 10.0, -10.0, -30.0]
    depths = [0.0, 100.0, 500.0]
    values = []
    for k in range(len(depths)):
        for lat in lats:
            for lon in lons:
                if lon == -177.5 and lat == -30.0:
                    values.append("_")
                elif lon == 2.5 and lat == 10.0 and k == 2:
                    values.append("NaNf")
                else:
                    values.append(repr(round(100 * k + (lat + 90) + (lon % 360) / 1000, 4)))
    return f"""netcdf dateline_cf {{
dimensions:
  time = 1 ; depth = 3 ; lat = 4 ; lon = 72 ;
variables:
  double time(time) ; time:units = "days since 2000-01-01" ; time:standard_name = "time" ;
  double depth(depth) ; depth:units = "m" ; depth:positive = "down" ;
  double lat(lat) ; lat:units = "degrees_north" ;
  double lon(lon) ; lon:units = "degree_east" ;
  float temp(time, depth, lat, lon) ;
    temp:units = "degC" ; temp:long_name = "synthetic temperature" ; temp:_FillValue = -999.f ;
  byte landmask(lat, lon) ;
data:
  time = 0 ;
  depth = {", ".join(map(repr, depths))} ;
  lat = {", ".join(map(repr, lats))} ;
  lon = {", ".join(map(repr, lons))} ;
  temp = {", ".join(values)} ;
  landmask = {", ".join(["0"] * 288)} ;
}}
"""


def cartesian():
    values = [str(100 * z + 10 * y + x) for z in range(3) for y in range(4) for x in range(5)]
    return f"""netcdf cartesian {{
dimensions:
  z = 3 ; y = 4 ; x = 5 ;
variables:
  double x(x) ; x:units = "km" ;
  double y(y) ; y:units = "km" ;
  float density(z, y, x) ; density:units = "kg m-3" ;
data:
  x = 0, 2, 4, 6, 8 ;
  y = 40, 30, 20, 10 ;
  density = {", ".join(values)} ;
}}
"""


def packed_4d():
    raw = [str(v) for v in range(29)] + ["_"] + ["100"] * 30
    return f"""netcdf packed_4d {{
dimensions:
  time = 2 ; lev = 2 ; lat = 3 ; lon = 5 ;
variables:
  double time(time) ; time:units = "hours since 2000-01-01" ;
  double lev(lev) ; lev:units = "meters" ;
  double lat(lat) ; lat:units = "degrees_N" ;
  double lon(lon) ; lon:units = "degrees_E" ;
  short t(time, lev, lat, lon) ; t:scale_factor = 0.5 ; t:add_offset = 10. ; t:_FillValue = -32767s ;
data:
  time = 0, 1 ; lev = 10, 0 ; lat = -1, 0, 1 ; lon = 360, 270, 180, 90, 0 ;
  t = {", ".join(raw)} ;
}}
"""


ncgen("dateline_cf", dateline(), [("classic", ""), ("nc4", "_nc4")])
ncgen("cartesian", cartesian(), [("classic", "")])
ncgen("packed_4d", packed_4d(), [("classic", "")])
