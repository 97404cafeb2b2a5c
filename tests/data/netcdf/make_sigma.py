#!/usr/bin/env python3
"""Writes the terrain-following test files (run once; the outputs are committed).

Needs netCDF4, NumPy and SciPy (the project's venv) and the shared real data
(../shared/data/ocean: etopo20.cdf, levitus_climatology.cdf; or OCTRACE_SHARED_DATA).

roms_g2_nwatlantic.nc: a ROMS-like file (as ROMS writes its history files, but on 1-D
  longitude/latitude) over the North-West Atlantic, 80W-56W, 30N-47N: the shelf from Cape
  Hatteras to Nova Scotia, the slope and the deep basin. The grid is ETOPO20's own 1/3 degree
  points; h = -ETOPO20 relief, clipped to at least 10 m (ROMS's hmin), land (relief >= 0)
  masked. 20 s-levels `s_rho` with standard_name ocean_s_coordinate_g2 (Vtransform = 2) and
  ROMS's Vstretching = 4 (theta_s = 5, theta_b = 0.4, hc = 100 m), formula_terms
  "s: s_rho C: Cs_r eta: zeta depth: h depth_c: hc". Two time steps: zeta = 0, then a
  sea-surface bump of up to 0.5 m. temp(ocean_time, s_rho, lat, lon) is the Levitus 1982
  annual temperature interpolated (linearly in depth, longitude and latitude) at each
  s-level's depth of each column and step; Levitus's own land and sea floor are filled from
  the nearest valid point of the same level first (then the level above), so that every
  ETOPO20 water column has values down to its floor.
roms_curvilinear_nwatlantic.nc: the same model set-up on a curvilinear grid as ROMS names it:
  eta_rho x xi_rho = 96 x 100 points, 30 km apart on an azimuthal equidistant plane centred at
  68W, 38.5N whose grid axes are turned 30 degrees from east (so neither grid line follows a
  meridian or a parallel, and both curve on the lon/lat plane), covering the region above with
  margin. 2-D lat_rho/lon_rho (units degree_north/degree_east, named by temp's
  `coordinates`), mask_rho, h bilinear from ETOPO20 (land where the interpolated relief is
  >= 0), the same s-levels, zeta and temperature law (Levitus at each s-level's depth).
sigma_small.nc: ocean_sigma_coordinate, 8 sigma levels over a 9 x 7 grid (1-D lon/lat) whose
  depth runs from 20 m to 420 m, eta(time, lat, lon) of up to 1 m, two steps, and
  temp = 20 - 0.01 * depth_below_surface at every point (so a resampled column must give the
  same linear law).
The invalid corpus (tests/data/invalid, see its README), 3 x 3 x 3 with one time step:
  formula_terms naming a missing variable, a malformed formula_terms, a term whose dimensions
  are not the field's; and a ROMS-like curvilinear one (3 s-levels, 4 x 3 rho points) whose h
  lies on the staggered v points (eta_v, xi_rho) instead of the field's rho points.
"""
import os
import sys

import netCDF4
import numpy as np
from scipy.interpolate import RegularGridInterpolator
from scipy.ndimage import distance_transform_edt

HERE = os.path.dirname(os.path.abspath(__file__))
INVALID = os.path.join(HERE, "..", "invalid")
SHARED = os.environ.get("OCTRACE_SHARED_DATA",
                        os.path.join(HERE, "..", "..", "..", "..", "shared", "data"))
OCEAN = os.path.join(SHARED, "ocean")
if not os.path.isdir(OCEAN):
    OCEAN = "/work/shared/data/ocean"

REGION = (-80.0, -56.0, 30.0, 47.0)
N = 20
THETA_S, THETA_B, HC, HMIN = 5.0, 0.4, 100.0, 10.0
FILL = 1.0e37


def stretching(sc):
    """ROMS Vstretching = 4 (Shchepetkin 2010): C(s) for s in [-1, 0]."""
    csur = (1.0 - np.cosh(THETA_S * sc)) / (np.cosh(THETA_S) - 1.0)
    return (np.exp(THETA_B * csur) - 1.0) / (1.0 - np.exp(-THETA_B))


def depth_g2(s, C, h, zeta, hc):
    """CF ocean_s_coordinate_g2 (ROMS Vtransform = 2): depth (positive down) per (k, j, i)."""
    S = (hc * s[:, None, None] + h[None] * C[:, None, None]) / (hc + h[None])
    return -(zeta[None] + (zeta[None] + h[None]) * S)


def etopo_region(margin=0.0):
    d = netCDF4.Dataset(os.path.join(OCEAN, "etopo20.cdf"))
    lon = d.variables["ETOPO20X1_1081"][:].astype(float)
    lat = d.variables["ETOPO20Y"][:].astype(float)
    lon360 = (np.array(REGION[:2]) + 360.0)
    ii = np.where((lon >= lon360[0] - margin - 1e-6) & (lon <= lon360[1] + margin + 1e-6))[0]
    jj = np.where((lat >= REGION[2] - margin - 1e-6) & (lat <= REGION[3] + margin + 1e-6))[0]
    rose = np.asarray(d.variables["ROSE"][jj, ii], dtype=float)
    return lon[ii] - 360.0, lat[jj], rose


def levitus_interpolator(margin=4.0):
    d = netCDF4.Dataset(os.path.join(OCEAN, "levitus_climatology.cdf"))
    lon = d.variables["XAXLEVITR"][:].astype(float)
    lat = d.variables["YAXLEVITR"][:].astype(float)
    z = d.variables["ZAXLEVITR"][:].astype(float)
    # a box a few degrees around the region, longitudes as -180..180
    lon180 = np.where(lon > 180.0, lon - 360.0, lon)
    ii = np.where((lon180 >= REGION[0] - margin) & (lon180 <= REGION[1] + margin))[0]
    ii = ii[np.argsort(lon180[ii])]
    jj = np.where((lat >= REGION[2] - margin) & (lat <= REGION[3] + margin))[0]
    t = np.ma.filled(d.variables["TEMP"][:, jj, :][:, :, ii].astype(float), np.nan)
    t[t < -100] = np.nan
    for k in range(len(z)):
        bad = ~np.isfinite(t[k])
        if bad.all():
            t[k] = t[k - 1]
            continue
        if bad.any():  # nearest valid point of the same level
            _, (a, b) = distance_transform_edt(bad, return_indices=True)
            t[k] = t[k][a, b]
    return RegularGridInterpolator((z, lat[jj], lon180[ii]), t), z[-1]


def s_levels(d, sc, C):
    """ROMS's vertical grid variables: Vtransform 2, Vstretching 4, hc, s_rho with its
    formula_terms, Cs_r."""
    for name, value in (("Vtransform", 2), ("Vstretching", 4)):
        v = d.createVariable(name, "i4", ())
        v[...] = value
    for name, value in (("theta_s", THETA_S), ("theta_b", THETA_B)):
        v = d.createVariable(name, "f8", ())
        v[...] = value
    v = d.createVariable("hc", "f8", ())
    v.long_name, v.units = "S-coordinate parameter, critical depth", "meter"
    v[...] = HC
    v = d.createVariable("s_rho", "f8", ("s_rho",))
    v.long_name = "S-coordinate at RHO-points"
    v.valid_min, v.valid_max = -1.0, 0.0
    v.positive = "up"
    v.standard_name = "ocean_s_coordinate_g2"
    v.formula_terms = "s: s_rho C: Cs_r eta: zeta depth: h depth_c: hc"
    v[:] = sc
    v = d.createVariable("Cs_r", "f8", ("s_rho",))
    v.long_name = "S-coordinate stretching curves at RHO-points"
    v.valid_min, v.valid_max = -1.0, 0.0
    v[:] = C


def model_fields(lon, lat, relief, levitus):
    """At points (lon, lat) (2-D) with ETOPO20 relief there: the land mask, h (>= HMIN), s and
    C(s) at rho points, the two steps' zeta and temp (Levitus at each s-level's depth)."""
    interp, zmax = levitus
    land = relief >= 0.0
    h = np.maximum(-relief, HMIN)
    sc = (np.arange(1, N + 1) - N - 0.5) / N  # s at rho points, -0.975 .. -0.025
    C = stretching(sc)
    zetas = [np.zeros_like(h), 0.5 * np.exp(-(((lon + 68.0) / 6.0) ** 2 + ((lat - 38.0) / 4.0) ** 2))]
    temps = []
    for zeta in zetas:
        zeta = np.where(land, 0.0, zeta)
        dep = depth_g2(sc, C, h, zeta, HC)
        pts = np.stack([np.clip(dep, 0.0, zmax), np.broadcast_to(lat, dep.shape), np.broadcast_to(lon, dep.shape)], -1)
        t = interp(pts.reshape(-1, 3)).reshape(dep.shape)
        t[:, land] = FILL
        temps.append(t)
    return land, h, sc, C, zetas, temps


def roms_file(path):
    lon, lat, rose = etopo_region()
    yy, xx = np.meshgrid(lat, lon, indexing="ij")
    land, h, sc, C, zetas, temps = model_fields(xx, yy, rose, levitus_interpolator())
    d = netCDF4.Dataset(path, "w", format="NETCDF4_CLASSIC")
    d.title = "ROMS-like s-coordinate (Vtransform 2) file over ETOPO20 with Levitus 1982 temperature (octrace test)"
    d.Conventions = "CF-1.8"
    d.createDimension("ocean_time", None)
    d.createDimension("s_rho", N)
    d.createDimension("lat", len(lat))
    d.createDimension("lon", len(lon))
    v = d.createVariable("lon", "f8", ("lon",))
    v.units, v.standard_name = "degrees_east", "longitude"
    v[:] = lon
    v = d.createVariable("lat", "f8", ("lat",))
    v.units, v.standard_name = "degrees_north", "latitude"
    v[:] = lat
    v = d.createVariable("ocean_time", "f8", ("ocean_time",))
    v.units, v.calendar = "days since 2000-01-01 00:00:00", "proleptic_gregorian"
    v[:] = [0.0, 1.0]
    s_levels(d, sc, C)
    v = d.createVariable("h", "f8", ("lat", "lon"))
    v.long_name, v.units = "bathymetry at RHO-points", "meter"
    v[:] = h
    v = d.createVariable("mask_rho", "f8", ("lat", "lon"))
    v.long_name = "mask on RHO-points"
    v.flag_values, v.flag_meanings = np.array([0.0, 1.0]), "land water"
    v[:] = np.where(land, 0.0, 1.0)
    v = d.createVariable("zeta", "f4", ("ocean_time", "lat", "lon"), fill_value=FILL)
    v.long_name, v.units = "free-surface", "meter"
    v[:] = np.where(land, FILL, np.stack(zetas))
    v = d.createVariable("temp", "f4", ("ocean_time", "s_rho", "lat", "lon"), fill_value=FILL, zlib=True)
    v.long_name, v.units = "potential temperature", "Celsius"
    v.standard_name = "sea_water_potential_temperature"
    v.coordinates = "lon lat s_rho ocean_time"
    v[:] = np.stack(temps)
    d.close()


def curvilinear_grid(nx=100, ny=96, step_km=30.0, angle_deg=30.0, lon0=-68.0, lat0=38.5):
    """lon, lat (ny x nx) of a grid regular on the azimuthal equidistant plane around (lon0, lat0),
    its axes turned angle_deg anticlockwise from east: curved lines on the lon/lat plane."""
    a = np.radians(angle_deg)
    u = (np.arange(nx) - (nx - 1) / 2.0) * step_km
    v = (np.arange(ny) - (ny - 1) / 2.0) * step_km
    uu, vv = np.meshgrid(u, v)
    east, north = uu * np.cos(a) - vv * np.sin(a), uu * np.sin(a) + vv * np.cos(a)
    dist = np.hypot(east, north) / 6371.0  # angular distance, radians
    az = np.arctan2(east, north)  # azimuth from north
    p0, l0 = np.radians(lat0), np.radians(lon0)
    lat = np.arcsin(np.sin(p0) * np.cos(dist) + np.cos(p0) * np.sin(dist) * np.cos(az))
    lon = l0 + np.arctan2(np.sin(az) * np.sin(dist) * np.cos(p0), np.cos(dist) - np.sin(p0) * np.sin(lat))
    return np.degrees(lon), np.degrees(lat)


def roms_curvilinear_file(path):
    lon_e, lat_e, rose_e = etopo_region(margin=13.0)
    lon, lat = curvilinear_grid()
    relief = RegularGridInterpolator((lat_e, lon_e), rose_e)(np.stack([lat, lon], -1).reshape(-1, 2)).reshape(lon.shape)
    land, h, sc, C, zetas, temps = model_fields(lon, lat, relief, levitus_interpolator(margin=13.0))
    d = netCDF4.Dataset(path, "w", format="NETCDF4_CLASSIC")
    d.title = ("ROMS-like s-coordinate (Vtransform 2) file on a curvilinear grid over ETOPO20 with Levitus 1982 "
               "temperature (octrace test)")
    d.Conventions = "CF-1.8"
    d.type = "ROMS/TOMS history file"
    d.createDimension("ocean_time", None)
    d.createDimension("s_rho", N)
    d.createDimension("eta_rho", lon.shape[0])
    d.createDimension("xi_rho", lon.shape[1])
    v = d.createVariable("ocean_time", "f8", ("ocean_time",))
    v.long_name = "time since initialization"
    v.units, v.calendar = "seconds since 2000-01-01 00:00:00", "proleptic_gregorian"
    v[:] = [0.0, 86400.0]
    s_levels(d, sc, C)
    for name, units, sn, data in (("lon_rho", "degree_east", "longitude", lon),
                                  ("lat_rho", "degree_north", "latitude", lat)):
        v = d.createVariable(name, "f8", ("eta_rho", "xi_rho"), zlib=True)
        v.long_name = ("longitude" if sn == "longitude" else "latitude") + " of RHO-points"
        v.units, v.standard_name = units, sn
        v[:] = data
    v = d.createVariable("h", "f8", ("eta_rho", "xi_rho"), zlib=True)
    v.long_name, v.units = "bathymetry at RHO-points", "meter"
    v.coordinates = "lon_rho lat_rho"
    v[:] = h
    v = d.createVariable("mask_rho", "f8", ("eta_rho", "xi_rho"), zlib=True)
    v.long_name = "mask on RHO-points"
    v.flag_values, v.flag_meanings = np.array([0.0, 1.0]), "land water"
    v.coordinates = "lon_rho lat_rho"
    v[:] = np.where(land, 0.0, 1.0)
    v = d.createVariable("zeta", "f4", ("ocean_time", "eta_rho", "xi_rho"), fill_value=FILL, zlib=True)
    v.long_name, v.units = "free-surface", "meter"
    v.coordinates = "lon_rho lat_rho ocean_time"
    v[:] = np.where(land, FILL, np.stack(zetas))
    v = d.createVariable("temp", "f4", ("ocean_time", "s_rho", "eta_rho", "xi_rho"), fill_value=FILL, zlib=True,
                         complevel=9, least_significant_digit=3)
    v.long_name, v.units = "potential temperature", "Celsius"
    v.standard_name = "sea_water_potential_temperature"
    v.coordinates = "lon_rho lat_rho s_rho ocean_time"
    v[:] = np.stack(temps)
    d.close()


def sigma_file(path, formula_terms="sigma: sigma eta: eta depth: depth", depth_dims=("lat", "lon"),
               drop=(), small=False):
    nlon, nlat, nk = (9, 7, 8) if not small else (3, 3, 3)
    lon = np.linspace(10.0, 14.0, nlon)
    lat = np.linspace(40.0, 43.0, nlat)
    sigma = -(np.arange(nk) + 0.5) / nk  # surface to floor
    yy, xx = np.meshgrid(lat, lon, indexing="ij")
    depth = 20.0 + 400.0 * (xx - lon[0]) / (lon[-1] - lon[0]) * (0.5 + 0.5 * (yy - lat[0]) / (lat[-1] - lat[0]))
    etas = [np.zeros_like(depth), 1.0 * (yy - lat[0]) / (lat[-1] - lat[0])][:1 if small else 2]
    d = netCDF4.Dataset(path, "w", format="NETCDF3_CLASSIC")
    d.Conventions = "CF-1.8"
    d.createDimension("time", None)
    d.createDimension("sigma", nk)
    d.createDimension("lat", nlat)
    d.createDimension("lon", nlon)
    if depth_dims != ("lat", "lon"):
        d.createDimension("lat_v", nlat - 1)
    v = d.createVariable("lon", "f8", ("lon",))
    v.units = "degrees_east"
    v[:] = lon
    v = d.createVariable("lat", "f8", ("lat",))
    v.units = "degrees_north"
    v[:] = lat
    v = d.createVariable("time", "f8", ("time",))
    v.units = "hours since 2010-06-01"
    v[:] = [0.0, 6.0][:len(etas)]
    v = d.createVariable("sigma", "f8", ("sigma",))
    v.standard_name = "ocean_sigma_coordinate"
    v.long_name = "sigma at layer midpoints"
    v.positive = "up"
    v.formula_terms = formula_terms
    v[:] = sigma
    if "depth" not in drop:
        v = d.createVariable("depth", "f8", depth_dims)
        v.units = "m"
        v.long_name = "sea floor depth below mean sea level"
        v[:] = depth if depth_dims == ("lat", "lon") else depth[:-1]
    if "eta" not in drop:
        v = d.createVariable("eta", "f8", ("time", "lat", "lon"))
        v.units = "m"
        v.standard_name = "sea_surface_height_above_geoid"
        v[:] = np.stack(etas)
    t = d.createVariable("temp", "f4", ("time", "sigma", "lat", "lon"), fill_value=np.float32(-999.0))
    t.units = "degC"
    t.standard_name = "sea_water_temperature"
    vals = []
    for eta in etas:
        below = -sigma[:, None, None] * (depth[None] + eta[None])  # depth below the surface
        vals.append(20.0 - 0.01 * below)
    t[:] = np.stack(vals)
    d.close()


def staggered_curvilinear_file(path):
    """A tiny ROMS-like curvilinear file whose `depth` term h is on the v points (eta_v = eta_rho - 1)."""
    lon, lat = curvilinear_grid(nx=4, ny=3, step_km=50.0)
    d = netCDF4.Dataset(path, "w", format="NETCDF3_CLASSIC")
    d.Conventions = "CF-1.8"
    for name, n in (("ocean_time", 1), ("s_rho", 3), ("eta_rho", 3), ("eta_v", 2), ("xi_rho", 4)):
        d.createDimension(name, n)
    v = d.createVariable("ocean_time", "f8", ("ocean_time",))
    v.units = "seconds since 2000-01-01"
    v[:] = [0.0]
    v = d.createVariable("hc", "f8", ())
    v[...] = HC
    sc = np.array([-5.0, -3.0, -1.0]) / 6.0
    v = d.createVariable("s_rho", "f8", ("s_rho",))
    v.positive, v.standard_name = "up", "ocean_s_coordinate_g2"
    v.formula_terms = "s: s_rho C: Cs_r eta: zeta depth: h depth_c: hc"
    v[:] = sc
    v = d.createVariable("Cs_r", "f8", ("s_rho",))
    v[:] = stretching(sc)
    for name, units, data in (("lon_rho", "degree_east", lon), ("lat_rho", "degree_north", lat)):
        v = d.createVariable(name, "f8", ("eta_rho", "xi_rho"))
        v.units = units
        v[:] = data
    v = d.createVariable("h", "f8", ("eta_v", "xi_rho"))
    v.units = "meter"
    v[:] = np.full((2, 4), 500.0)
    v = d.createVariable("zeta", "f4", ("ocean_time", "eta_rho", "xi_rho"))
    v.units = "meter"
    v[:] = np.zeros((1, 3, 4))
    v = d.createVariable("temp", "f4", ("ocean_time", "s_rho", "eta_rho", "xi_rho"))
    v.units, v.coordinates = "Celsius", "lon_rho lat_rho s_rho ocean_time"
    v[:] = np.full((1, 3, 3, 4), 10.0)
    d.close()


def main():
    # make_sigma.py roms_curvilinear writes only that file (the others are committed as made)
    if sys.argv[1:] == ["roms_curvilinear"]:
        roms_curvilinear_file(os.path.join(HERE, "roms_curvilinear_nwatlantic.nc"))
        return
    roms_file(os.path.join(HERE, "roms_g2_nwatlantic.nc"))
    roms_curvilinear_file(os.path.join(HERE, "roms_curvilinear_nwatlantic.nc"))
    sigma_file(os.path.join(HERE, "sigma_small.nc"))
    sigma_file(os.path.join(INVALID, "invalid_formula_terms_missing_variable.nc"), drop=("eta",), small=True)
    sigma_file(os.path.join(INVALID, "invalid_formula_terms_malformed.nc"),
               formula_terms="sigma: sigma eta eta depth: depth", small=True)
    sigma_file(os.path.join(INVALID, "invalid_formula_terms_shape.nc"), depth_dims=("lat_v", "lon"), small=True)
    staggered_curvilinear_file(os.path.join(INVALID, "invalid_formula_terms_curvilinear_staggered.nc"))


if __name__ == "__main__":
    main()
