#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets (run once; the outputs are committed).

Seeds are small (a few KB at most): valid and broken files of each format, modelled on
tests/data/ and on the real files of ../shared/data (the Levitus and ETOPO headers, the LIDC
chest CT and VTK head NRRD headers) with their grids shrunk. NetCDF seeds are made with
`ncgen` (Debian package netcdf-bin). Run from any folder: python3 tests/fuzz/corpus/make_seeds.py
"""
import gzip
import os
import shutil
import struct
import subprocess
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "data")


def out(target, name, data):
    d = os.path.join(HERE, target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(data)


def copy(target, src, name=None, limit=6000):
    with open(src, "rb") as f:
        data = f.read()
    if len(data) <= limit:
        out(target, name or os.path.basename(src), data)


# ---------------------------------------------------------------- NRRD (fuzz_nrrd)
def nrrd(lines, data=b""):
    return ("\n".join(["NRRD0004"] + lines) + "\n\n").encode() + data


sphere = struct.pack("<64f", *[((x - 1.5) ** 2 + (y - 1.5) ** 2 + (z - 1.5) ** 2) ** 0.5 - 1.2
                               for z in range(4) for y in range(4) for x in range(4)])
T = "fuzz_nrrd"
out(T, "raw_float.nrrd", nrrd(["type: float", "dimension: 3", "sizes: 4 4 4", "spacings: 0.5 0.5 1",
                               "endian: little", "encoding: raw", "content: sphere", "units:=mm"], sphere))
out(T, "raw_big_endian_int16.nrrd", nrrd(["type: short", "dimension: 3", "sizes: 4 4 2", "endian: big",
                                          "encoding: raw", "axis mins: -1 -1 -1"],
                                         struct.pack(">32h", *range(-16, 16))))
out(T, "gzip_uint8_lps.nrrd",  # the LIDC chest CT header, 4x4x4
    nrrd(["# Real chest CT (LIDC), shrunk", "type: uint8", "dimension: 3", "space: left-posterior-superior",
          "sizes: 4 4 4", "space directions: (1.40625,0,0) (0,1.40625,0) (0,0,2.5)", "kinds: domain domain domain",
          "endian: little", "encoding: gzip", "space origin: (0,0,0)"], gzip.compress(bytes(range(64)), mtime=0)))
out(T, "ascii_double.nrrd", nrrd(["type: double", "dimension: 3", "sizes: 2 2 2", "encoding: ascii",
                                  "space dimension: 3", "space origin: (1,2,3)",
                                  "space directions: (0,1,0) (-1,0,0) (0,0,2)"], b"0 1 2 3\n4 5 6 nan\n"))
out(T, "detached_raw.nhdr", b"NRRD0005\ntype: uchar\ndimension: 3\nsizes: 16 16 16\nspacings: 1 1 1\n"
                            b"encoding: raw\ndata file: data.raw\n")
out(T, "detached_slices_pattern.nhdr",  # the VTK head (headsq) header over the fuzzer's slice files
    b"NRRD0004\ndimension: 3\nsizes: 16 16 4\nspacings: 3.2 3.2 1.5\nendian: little\ntype: short\n"
    b"encoding: raw\nspace: 3D-left-handed\ndata file: slice.%d.raw 1 4 1\n")
out(T, "detached_list.nhdr", b"NRRD0004\ntype: int32\ndimension: 3\nsizes: 16 8 4\nendian: little\n"
                             b"encoding: raw\ndata file: LIST\nslice.1.raw\nslice.2.raw\nslice.3.raw\nslice.4.raw\n")
for name in ("invalid_truncated.nrrd", "invalid_not_3d.nrrd", "invalid_truncated_gzip.nrrd",
             "invalid_bad_spacing.nhdr", "invalid_missing_data_file.nhdr", "invalid_huge_sizes.nrrd",
             "invalid_nan_origin.nrrd", "invalid_infinite_extent.nrrd", "invalid_tiny_extent.nrrd"):
    copy(T, os.path.join(DATA, "invalid", name))
with open(os.path.join(DATA, "invalid", "invalid_sheared.nrrd"), "rb") as f:
    head = f.read().split(b"\n\n")[0].replace(b"sizes: 16 16 16", b"sizes: 2 2 2")
out(T, "invalid_sheared_small.nrrd", head + b"\n\n" + bytes(32))

# ---------------------------------------------------------------- NetCDF (fuzz_netcdf_cf, ..._classic_header)
CDL = {
    # The Levitus 1982 climatology's header (Ferret, not CF: units METERS, positive down, edges
    # variable, missing_value -1e10) on a 6 x 4 x 3 grid across the dateline.
    "levitus_small": """netcdf levitus_small {
dimensions:
  XAXLEVITR = 6 ; YAXLEVITR = 4 ; ZAXLEVITR = 3 ; ZAXLEVITRedges = 4 ;
variables:
  double XAXLEVITR(XAXLEVITR) ; XAXLEVITR:units = "degrees_east" ; XAXLEVITR:modulo = " " ;
  double YAXLEVITR(YAXLEVITR) ; YAXLEVITR:units = "degrees_north" ;
  double ZAXLEVITR(ZAXLEVITR) ; ZAXLEVITR:units = "METERS" ; ZAXLEVITR:positive = "down" ;
    ZAXLEVITR:edges = "ZAXLEVITRedges" ;
  double ZAXLEVITRedges(ZAXLEVITRedges) ;
  float TEMP(ZAXLEVITR, YAXLEVITR, XAXLEVITR) ; TEMP:missing_value = -1.e+10f ; TEMP:_FillValue = -1.e+10f ;
    TEMP:long_name = "TEMPERATURE" ; TEMP:units = "DEG C" ;
  float SALT(ZAXLEVITR, YAXLEVITR, XAXLEVITR) ; SALT:missing_value = -1.e+10f ; SALT:units = "PPT" ;
  :history = "FERRET V4.45 (GUI) 22-May-97" ;
data:
  XAXLEVITR = 165, 175, 185, 195, 205, 215 ; YAXLEVITR = -30, 0, 30, 60 ; ZAXLEVITR = 0, 100, 1000 ;
  ZAXLEVITRedges = 0, 50, 500, 1500 ;
  TEMP = 28, 27, 26, 25, 24, 23, 20, 19, 18, 17, 16, 15, 10, 9, 8, 7, 6, 5, 2, 1, 0, -1, -2, -1.e+10,
         20, 19, 18, 17, 16, 15, 15, 14, 13, 12, 11, 10, 8, 7, 6, 5, 4, 3, 1, 1, 0, 0, -1, -1.e+10,
         4, 4, 4, 3, 3, 3, 3, 3, 3, 2, 2, 2, 2, 2, 2, 1, 1, 1, 1, 1, 0, 0, 0, -1.e+10 ;
  SALT = 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35,
         35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35,
         35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35, 35 ;
}
""",
    # ETOPO20's header (2-D relief, missing -1e34): no 3-D variable.
    "etopo_small": """netcdf etopo_small {
dimensions:
  ETOPO20X1_1081 = 4 ; ETOPO20Y = 3 ;
variables:
  double ETOPO20X1_1081(ETOPO20X1_1081) ; ETOPO20X1_1081:units = "degrees_east" ;
  double ETOPO20Y(ETOPO20Y) ; ETOPO20Y:units = "degrees_north" ;
  float ROSE(ETOPO20Y, ETOPO20X1_1081) ; ROSE:missing_value = -1.e+34f ; ROSE:units = "METERS" ;
data:
  ETOPO20X1_1081 = 20, 40, 60, 80 ; ETOPO20Y = -10, 0, 10 ; ROSE = -4000, -3000, 10, 200, -1.e+34, 5, 6, 7, 8, 9, 10, 11 ;
}
""",
    # CF time series with a record dimension, packing and valid_range, height axis in km.
    "cf_record_packed": """netcdf cf_record_packed {
dimensions:
  time = UNLIMITED ; alt = 2 ; lat = 3 ; lon = 4 ;
variables:
  double time(time) ; time:units = "days since 2000-01-01" ; time:standard_name = "time" ;
  float alt(alt) ; alt:units = "km" ; alt:positive = "up" ; alt:axis = "Z" ;
  float lat(lat) ; lat:standard_name = "latitude" ; lat:units = "degrees_north" ;
  float lon(lon) ; lon:standard_name = "longitude" ; lon:units = "degrees_east" ;
  short t(time, alt, lat, lon) ; t:scale_factor = 0.01f ; t:add_offset = 10.f ; t:_FillValue = -32767s ;
    t:valid_range = -3000s, 3000s ;
data:
  time = 0, 1 ; alt = 0, 1.5 ; lat = 60, 50, 40 ; lon = 350, 355, 0, 5 ;
  t = 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, -32767,
      1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24 ;
}
""",
}
classic = "fuzz_netcdf_classic_header"
cf = "fuzz_netcdf_cf"
tmp = tempfile.mkdtemp()
try:
    for name, cdl in CDL.items():
        src = os.path.join(tmp, name + ".cdl")
        with open(src, "w") as f:
            f.write(cdl)
        for kind, suffix in (("classic", ".nc"), ("64-bit-offset", "_cdf2.nc"), ("cdf5", "_cdf5.nc"),
                             ("netCDF-4", "_nc4.nc")):
            if kind != "classic" and name != "levitus_small":
                continue
            dst = os.path.join(tmp, name + suffix)
            subprocess.run(["ncgen", "-k", kind, "-o", dst, src], check=True)
            copy(cf, dst, limit=12000)
            if kind != "netCDF-4":
                copy(classic, dst)
finally:
    shutil.rmtree(tmp)
for name in ("cartesian.nc", "dateline_cf.nc", "packed_4d.nc"):
    copy(cf, os.path.join(DATA, "netcdf", name))
    copy(classic, os.path.join(DATA, "netcdf", name))
for name in ("invalid_all_masked.nc", "invalid_no_variable.nc", "invalid_truncated.nc", "invalid_nan_coordinate.nc",
             "invalid_infinite_extent.nc", "invalid_billion_points.nc", "invalid_size_overflow.nc"):
    copy(cf, os.path.join(DATA, "invalid", name))
    copy(classic, os.path.join(DATA, "invalid", name))
# Not invalid_billion_points_nc4.nc: mutated, it led fuzz_netcdf_cf within seconds to an HDF5
# input that HDF5 never finishes opening (tests/fuzz/open-findings, docs/dev/fuzzing.md "Open").
# The real headers of ../shared/data/ocean (data cut away: the walker needs only the header).
for name, size in (("levitus_climatology.cdf", 1200), ("etopo20.cdf", 700)):
    path = os.path.join(HERE, "..", "..", "..", "..", "shared", "data", "ocean", name)
    if os.path.exists(path):
        with open(path, "rb") as f:
            out(classic, name.replace(".cdf", "_header.cdf"), f.read(size))

# ---------------------------------------------------------------- CLI (fuzz_cli_options)
CLI = {
    "render_levitus": ["render", "levitus.cdf", "--var", "TEMP", "--iso", "10", "--region", "120,180,10,60",
                       "--depth", "9", "--colormap", "viridis", "-o", "temp10.png", "--stats", "s.json", "--verify"],
    "render_camera": ["render", "analytic:torus:33", "--iso=0", "--size", "640x480", "--camera-pos", "3,-4,2",
                      "--look-at=0,0,0", "--up", "0,0,1", "--fov", "45", "--threads", "2", "--renderer", "reference",
                      "-o", "t.exr"],
    "render_colours": ["render", "x.nrrd", "--background", "0,0,0,0.5", "--light", "0.4,0.6,1", "--colour",
                       "0.85,0.62,0.35", "--color=1,1,1", "--vertical-scale", "50", "--quiet", "--verbose", "--",
                       "-o"],
    "render_dateline": ["render", "a.nc", "--region=170,-170,-60,60", "--depth", "14", "-o", "a.png"],
    "export_levitus": ["export", "levitus.cdf", "--var", "TEMP", "--iso", "10", "--region", "120,180,10,60",
                       "--depth", "8", "--level", "5", "--format", "ply", "--ascii", "--colormap", "viridis",
                       "-o", "temp10.ply"],
    "info": ["info", "a.nc", "b.nrrd", "analytic:sphere"],
    "render_memory": ["render", "analytic:noise:1024", "--depth", "12", "--max-memory", "1.5GiB", "-o", "n.png"],
    "info_memory": ["info", "--max-memory=25%", "a.nc", "--max-memory", "512m"],
    "sample": ["sample", "noise", "-o", "n.nrrd", "--samples", "17", "--seed", "1073741824"],
}
for name, args in CLI.items():
    out("fuzz_cli_options", name, b"\0".join(a.encode() for a in args))


# ---------------------------------------------------------------- studio sessions (fuzz_session)
def session_seeds():
    """fuzz_session: studio session files (app/studio/Session.cpp), valid and broken."""
    full = b"""{
    "camera": {"fov": 30, "look_at": [0, 0, 0], "position": [1.5, -2.5, 2], "up": [0, 0, 1]},
    "export": {"height": 1200, "transparent": false, "width": 1600},
    "input": {"path": "data_samples/torus.nrrd", "series": "", "time": "", "variable": ""},
    "octrace_studio_session": 1,
    "renderers": {"main": "area+colour", "second": "direct", "split": true},
    "shading": {"background": [1, 1, 1, 1], "colormap": "viridis", "colour": [0.85, 0.62, 0.35], "light": [0.4, 0.6, 1]},
    "surface": {"depth": 8, "iso": -0.4}
}
"""
    out("fuzz_session", "full.json", full)
    out("fuzz_session", "minimal.json", b'{"octrace_studio_session": 1}')
    out("fuzz_session", "analytic.json", b'{"octrace_studio_session": 1, "input": {"path": "analytic:gyroid:33", "time": "1990-07-15"}, "surface": {"iso": null}}')
    out("fuzz_session", "ocean.json", b'{"octrace_studio_session": 1, "input": {"path": "/data/ocean/levitus.cdf", "variable": "TEMP", "time": "3"}, "surface": {"iso": 10.5, "depth": 9}}')
    out("fuzz_session", "broken_types.json", b'{"octrace_studio_session": 1, "camera": {"position": [1, 2], "up": "z"}, "export": {"width": 1e9}}')
    out("fuzz_session", "version2.json", b'{"octrace_studio_session": 2}')
    out("fuzz_session", "truncated.json", full[:200])


session_seeds()
print("seeds written under", HERE)

