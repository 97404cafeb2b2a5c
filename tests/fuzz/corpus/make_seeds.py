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
    # CF ocean model output: 365_day time axis, height positive up, potential temperature in
    # kelvin and salinity by standard_name (--var sound_speed derives from them), packed salinity.
    "cf_ocean_noleap": """netcdf cf_ocean_noleap {
dimensions:
  time = 2 ; z = 3 ; lat = 3 ; lon = 4 ;
variables:
  double time(time) ; time:units = "days since 2000-01-01" ; time:calendar = "365_day" ; time:axis = "T" ;
  double z(z) ; z:units = "m" ; z:positive = "up" ; z:standard_name = "height" ;
  float lat(lat) ; lat:units = "degrees_north" ;
  float lon(lon) ; lon:units = "degrees_east" ;
  float thetao(time, z, lat, lon) ; thetao:standard_name = "sea_water_potential_temperature" ; thetao:units = "K" ;
    thetao:_FillValue = 1.e+20f ;
  short so(time, z, lat, lon) ; so:standard_name = "sea_water_salinity" ; so:scale_factor = 0.001f ;
    so:add_offset = 30.f ; so:missing_value = -1s ; so:valid_min = 0s ;
data:
  time = 0, 59 ; z = 0, -100, -2000 ; lat = -10, 0, 10 ; lon = 170, 175, 180, 185 ;
  thetao = 300, 300, 300, 300, 299, 299, 299, 299, 298, 298, 298, 1.e+20, 290, 290, 290, 290, 289, 289, 289,
    289, 288, 288, 288, 288, 276, 276, 276, 276, 276, 276, 276, 276, 275, 275, 275, 275,
    301, 301, 301, 301, 300, 300, 300, 300, 299, 299, 299, 1.e+20, 291, 291, 291, 291, 290, 290, 290,
    290, 289, 289, 289, 289, 277, 277, 277, 277, 277, 277, 277, 277, 276, 276, 276, 276 ;
  so = 4000, 4100, 4200, 4300, 4400, 4500, 4600, 4700, 4800, 4900, 5000, -1, 4000, 4100, 4200, 4300, 4400,
    4500, 4600, 4700, 4800, 4900, 5000, 5100, 4000, 4100, 4200, 4300, 4400, 4500, 4600, 4700, 4800, 4900,
    5000, 5100, 4000, 4100, 4200, 4300, 4400, 4500, 4600, 4700, 4800, 4900, 5000, -1, 4000, 4100, 4200,
    4300, 4400, 4500, 4600, 4700, 4800, 4900, 5000, 5100, 4000, 4100, 4200, 4300, 4400, 4500, 4600, 4700,
    4800, 4900, 5000, 5100 ;
}
""",
    # A curvilinear grid (2-D nav_lat/nav_lon named by `coordinates`), resampled onto a lattice
    # (more curvilinear seeds: make_curvilinear_seeds.py).
    "cf_curvilinear": """netcdf cf_curvilinear {
dimensions:
  deptht = 2 ; y = 2 ; x = 3 ;
variables:
  float deptht(deptht) ; deptht:units = "m" ; deptht:positive = "down" ;
  float nav_lat(y, x) ; nav_lat:units = "degrees_north" ;
  float nav_lon(y, x) ; nav_lon:units = "degrees_east" ;
  float votemper(deptht, y, x) ; votemper:coordinates = "nav_lon nav_lat" ; votemper:units = "degC" ;
data:
  deptht = 5, 50 ; nav_lat = 40, 40.2, 40.4, 41, 41.2, 41.4 ; nav_lon = 140, 141, 142, 139.8, 140.8, 141.8 ;
  votemper = 20, 19, 18, 17, 16, 15, 10, 9, 8, 7, 6, 5 ;
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
             "invalid_infinite_extent.nc", "invalid_billion_points.nc", "invalid_size_overflow.nc",
             "invalid_formula_terms_curvilinear_staggered.nc"):
    copy(cf, os.path.join(DATA, "invalid", name))
    copy(classic, os.path.join(DATA, "invalid", name))
# Mutated, this one led fuzz_netcdf_cf within seconds to inputs HDF5 never finishes opening
# (tests/data/invalid/invalid_hdf5_hang_*.nc); NetcdfFile now refuses those after a deadline.
copy(cf, os.path.join(DATA, "invalid", "invalid_billion_points_nc4.nc"), limit=9000)
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
    "render_sound_speed": ["render", "levitus.cdf", "--var", "sound_speed", "--time", "1990-07-15T12:00",
                           "--depth-range", "0,1000", "--iso", "1500", "-o", "v.png"],
    "info_ocean": ["info", "a.nc", "b.nc", "--var=speed_of_sound_in_sea_water", "--time", "3",
                   "--depth-range=10,500", "--region", "170,-170,-60,60"],
    "export_levitus": ["export", "levitus.cdf", "--var", "TEMP", "--iso", "10", "--region", "120,180,10,60",
                       "--depth", "8", "--level", "5", "--format", "ply", "--ascii", "--colormap", "viridis",
                       "-o", "temp10.ply"],
    "render_colour_by": ["render", "levitus.cdf", "--var", "SALT", "--iso", "34.5", "--colour-by", "TEMP",
                         "--colour-range", "0,25", "--colormap", "thermal", "--masked-colour", "0.6,0.6,0.6",
                         "--floor", "--floor-colour=0.55,0.5,0.45", "-o", "s.png"],
    "render_figure": ["render", "levitus.cdf", "--var", "SALT", "--iso", "34.5", "--colour-by", "TEMP", "--figure",
                      "--title", "North Pacific", "--dpi", "300", "--print-size", "180x120mm", "-o", "f.png"],
    "info": ["info", "a.nc", "b.nrrd", "analytic:sphere"],
    "render_memory": ["render", "analytic:noise:1024", "--depth", "12", "--max-memory", "1.5GiB", "-o", "n.png"],
    "info_memory": ["info", "--max-memory=25%", "a.nc", "--max-memory", "512m"],
    "sample": ["sample", "noise", "-o", "n.nrrd", "--samples", "17", "--seed", "1073741824"],
}
for name, args in CLI.items():
    out("fuzz_cli_options", name, b"\0".join(a.encode() for a in args))
# CityJSON: the test cube (two LoDs, a solid and a TIN), and small variants of what real files
# hold (no transform, CityJSON 1.0 numeric lod, a MultiSolid, a polygon with a hole, broken ones).
CITY = "fuzz_cityjson"
copy(CITY, os.path.join(DATA, "city", "cube.city.json"), "cube.city.json")
SQUARE = "[[0,0,0],[10,0,0],[10,10,0],[0,10,0],[3,3,0],[6,3,0],[6,6,0],[3,6,0],[0,0,5],[10,0,5],[10,10,5],[0,10,5]]"
CITY_SEEDS = {
    "hole.json": '{"type":"CityJSON","version":"1.0","CityObjects":{"p":{"type":"LandUse","geometry":[{"type":"MultiSurface","lod":1,'
                 '"boundaries":[[[0,1,2,3],[4,7,6,5]]]}]}},"vertices":' + SQUARE + '}',
    "multisolid.json": '{"type":"CityJSON","version":"1.1","metadata":{"referenceSystem":"urn:ogc:def:crs:EPSG::28992"},'
                       '"CityObjects":{"b":{"type":"Building","geometry":[{"type":"MultiSolid","lod":"1.2","boundaries":[[['
                       '[[0,3,2,1]],[[8,9,10,11]],[[0,1,9,8]],[[1,2,10,9]],[[2,3,11,10]],[[3,0,8,11]]]]]}]}},"vertices":' + SQUARE + '}',
    "bowtie.json": '{"type":"CityJSON","version":"2.0","CityObjects":{"w":{"type":"WaterBody","geometry":[{"type":"MultiSurface",'
                   '"lod":"1","boundaries":[[[0,2,1,3]]]}]}},"vertices":' + SQUARE + '}',
    "bad_index.json": '{"type":"CityJSON","version":"2.0","CityObjects":{"r":{"type":"Road","geometry":[{"type":"MultiSurface",'
                      '"lod":"1","boundaries":[[[0,1,99]]]}]}},"vertices":' + SQUARE + '}',
    "instance.json": '{"type":"CityJSON","version":"2.0","transform":{"scale":[0.5,0.5,0.5],"translate":[1,2,3]},"CityObjects":'
                     '{"t":{"type":"SolitaryVegetationObject","geometry":[{"type":"GeometryInstance","template":0,"boundaries":[0],'
                     '"transformationMatrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1]}]},"g":{"type":"TINRelief","geometry":[{"type":'
                     '"CompositeSurface","lod":"1","boundaries":[[[0,1,2]],[[0,2,3]]]}]}},"vertices":' + SQUARE + '}',
}
for name, text in CITY_SEEDS.items():
    out(CITY, name, text.encode())

# ---------------------------------------------------------------- molecules (fuzz_molecule)
def pdb_atom(serial, name, res, chain, seq, x, y, z, element, record="ATOM  ", alt=" "):
    return "%-6s%5d %-4s%1s%3s %1s%4d    %8.3f%8.3f%8.3f  1.00 20.00          %2s" % (
        record, serial, name, alt, res, chain, seq, x, y, z, element)


GLY = [("N", 1.0, 2.0, 3.0, "N"), ("CA", 2.4, 2.1, 3.2, "C"), ("C", 3.0, 3.5, 3.1, "C"), ("O", 2.3, 4.5, 3.0, "O")]
pdb_lines = ["HEADER    OCTRACE FUZZ SEED", "CRYST1   10.000   10.000   10.000  90.00  90.00  90.00 P 1           1"]
pdb_lines += [pdb_atom(i + 1, n, "GLY", "A", 1, x, y, z, e) for i, (n, x, y, z, e) in enumerate(GLY)]
pdb_lines += [pdb_atom(5, "FE", "HEM", "A", 2, 4.0, 4.0, 4.0, "FE", "HETATM"), "TER", "END"]
out("fuzz_molecule", "glycine.pdb", ("\n".join(pdb_lines) + "\n").encode())
# Two models (only the first is drawn), alternate locations, an element left blank.
models = ["MODEL        1", pdb_atom(1, "CA", "ALA", "A", 1, 0, 0, 0, "C", alt="A"),
          pdb_atom(2, "CA", "ALA", "A", 1, 0.2, 0, 0, "C", alt="B"), pdb_atom(3, " OG", "SER", "A", 2, 1, 1, 1, ""),
          "ENDMDL", "MODEL        2", pdb_atom(1, "CA", "ALA", "A", 1, 5, 5, 5, "C"), "ENDMDL", "END"]
out("fuzz_molecule", "models_altloc.pdb", ("\r\n".join(models) + "\r\n").encode())
out("fuzz_molecule", "invalid_coordinate.pdb", (pdb_atom(1, "CA", "ALA", "A", 1, 0, 0, 0, "C")[:30] + "   1.0e9x" + "\n").encode())
cif = """data_SEED
#
_entry.id SEED
loop_
_atom_site.group_PDB
_atom_site.id
_atom_site.type_symbol
_atom_site.label_atom_id
_atom_site.label_alt_id
_atom_site.label_comp_id
_atom_site.Cartn_x
_atom_site.Cartn_y
_atom_site.Cartn_z
_atom_site.pdbx_PDB_model_num
ATOM 1 N N . GLY 1.000 2.000 3.000 1
ATOM 2 C CA . GLY 2.400 2.100 3.200 1
ATOM 3 C "C'" . GLY 3.000 3.500 3.100 1
ATOM 4 O 'O 1' . GLY 2.300 4.500 3.000 1
HETATM 5 FE FE . HEM 4.000 4.000 4.000 1
HETATM 6 O O . HOH 9.000 9.000 9.000 2
#
loop_
_struct_keywords.text
;multi-line
text field
;
"""
out("fuzz_molecule", "glycine.cif", cif.encode())
out("fuzz_molecule", "single_atom.cif", b"data_ONE\n_atom_site.type_symbol S\n_atom_site.Cartn_x 1\n_atom_site.Cartn_y 2\n_atom_site.Cartn_z 3\n")
CLI_SPHERES = {
    "render_molecule": ["render", "4HHB.pdb", "--renderer", "beam", "--leaf-objects", "4", "--samples", "4",
                        "--bounces", "1", "--shadows", "off", "--octree", "object", "-o", "m.png", "--verify"],
    "render_sphereflake": ["render", "sphereflake:3", "--renderer", "samet", "--size", "64x48", "-o", "f.png"],
    "render_random_voxel": ["render", "random:100:7", "--octree", "voxel", "--depth", "6", "-o", "r.png"],
    "info_spheres": ["info", "sphereflake:2", "random:10", "a.cif"],
}
for name, args in CLI_SPHERES.items():
    out("fuzz_cli_options", name, b"\0".join(a.encode() for a in args))
# Footprints (GeoJSON through OGR): a square with height and base, a multipolygon with a hole,
# features without height, a bow tie, a point, a CRS member.
FOOT = "fuzz_footprints"
FOOT_SEEDS = {
    "square.geojson": '{"type":"FeatureCollection","features":[{"type":"Feature","properties":{"height":10,"base":5},'
                      '"geometry":{"type":"Polygon","coordinates":[[[0,0],[10,0],[10,10],[0,10],[0,0]]]}}]}',
    "hole.geojson": '{"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::3946"}},'
                    '"features":[{"type":"Feature","properties":{"height":"12.5"},"geometry":{"type":"MultiPolygon","coordinates":'
                    '[[[[0,0,3],[20,0,3],[20,20,3],[0,20,3],[0,0,3]],[[5,5],[5,15],[15,15],[15,5],[5,5]]],[[[30,0],[40,0],[35,8],[30,0]]]]}}]}',
    "broken.geojson": '{"type":"FeatureCollection","features":[{"type":"Feature","properties":{"height":null},"geometry":'
                      '{"type":"Polygon","coordinates":[[[0,0],[1,0],[1,1],[0,0]]]}},{"type":"Feature","properties":{"height":4},'
                      '"geometry":{"type":"Polygon","coordinates":[[[0,0],[10,10],[10,0],[0,10],[0,0]]]}},{"type":"Feature",'
                      '"properties":{"height":4},"geometry":{"type":"Point","coordinates":[1,2]}},{"type":"Feature","properties":{},"geometry":null}]}',
}
for name, text in FOOT_SEEDS.items():
    out(FOOT, name, text.encode())

# CityGML: a 2.0 house (LoD1 solid, LoD2 ground with a hole and a gable roof, one slope through
# xlink:href, a compound srsName), a 1.0 building with gml:pos and GML 2 coordinates, an AdV CRS
# name, and broken ones (odd coordinates, no CityModel, not XML).
GML = "fuzz_citygml"
GML_HEAD = ('<?xml version="1.0"?><core:CityModel xmlns:core="http://www.opengis.net/citygml/2.0" '
            'xmlns:bldg="http://www.opengis.net/citygml/building/2.0" xmlns:gml="http://www.opengis.net/gml" '
            'xmlns:xlink="http://www.w3.org/1999/xlink"><gml:boundedBy><gml:Envelope srsName="%s"/></gml:boundedBy>')


def gml_polygon(pos, hole="", pid=""):
    ident = ' gml:id="%s"' % pid if pid else ""
    inner = "<gml:interior><gml:LinearRing><gml:posList>%s</gml:posList></gml:LinearRing></gml:interior>" % hole if hole else ""
    return ("<gml:Polygon%s><gml:exterior><gml:LinearRing><gml:posList srsDimension=\"3\">%s</gml:posList></gml:LinearRing>"
            "</gml:exterior>%s</gml:Polygon>" % (ident, pos, inner))


def gml_member(body):
    return "<core:cityObjectMember>%s</core:cityObjectMember>" % body


GML_SEEDS = {
    "house.gml": GML_HEAD % "urn:ogc:def:crs,crs:EPSG::25833,crs:EPSG::5783" + gml_member(
        '<bldg:Building gml:id="house"><bldg:lod1Solid><gml:Solid><gml:exterior><gml:CompositeSurface><gml:surfaceMember>' +
        gml_polygon("0 0 0 10 0 0 10 10 0 0 10 0 0 0 0") +
        "</gml:surfaceMember></gml:CompositeSurface></gml:exterior></gml:Solid></bldg:lod1Solid>"
        "<bldg:boundedBy><bldg:GroundSurface><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>" +
        gml_polygon("0 0 0 0 10 0 10 10 0 10 0 0 0 0 0", "4 4 0 6 4 0 6 6 0 4 6 0 4 4 0") +
        "</gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface></bldg:GroundSurface></bldg:boundedBy>"
        "<bldg:boundedBy><bldg:RoofSurface><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>" +
        gml_polygon("0 0 5 10 0 5 10 5 8 0 5 8 0 0 5") + '</gml:surfaceMember><gml:surfaceMember xlink:href="#north"/>'
        "</gml:MultiSurface></bldg:lod2MultiSurface></bldg:RoofSurface></bldg:boundedBy></bldg:Building>") + gml_member(
        '<bldg:Building gml:id="shed"><bldg:lod2MultiSurface><gml:MultiSurface><gml:surfaceMember>' +
        gml_polygon("0 5 8 10 5 8 10 10 5 0 10 5 0 5 8", pid="north") + "</gml:surfaceMember><gml:surfaceMember>" +
        gml_polygon("20 0 0 21 0 0 21 1") + "</gml:surfaceMember></gml:MultiSurface></bldg:lod2MultiSurface></bldg:Building>") +
        "</core:CityModel>",
    "citygml1_pos.gml": '<CityModel xmlns="http://www.opengis.net/citygml/1.0" xmlns:gml="http://www.opengis.net/gml" '
                        'xmlns:bldg="http://www.opengis.net/citygml/building/1.0" xmlns:dem="http://www.opengis.net/citygml/relief/1.0">'
                        '<cityObjectMember><dem:ReliefFeature gml:id="r"><dem:lod1MultiSurface><gml:Polygon><gml:exterior>'
                        '<gml:LinearRing><gml:pos>0 0 1</gml:pos><gml:pos>9 0 1</gml:pos><gml:pos>9 9 2</gml:pos><gml:pos>0 0 1</gml:pos>'
                        '</gml:LinearRing></gml:exterior></gml:Polygon></dem:lod1MultiSurface></dem:ReliefFeature></cityObjectMember>'
                        '<cityObjectMember><bldg:Building><bldg:lod2MultiSurface><gml:Polygon srsName="urn:adv:crs:ETRS89_UTM32*DE_DHHN92_NH">'
                        '<gml:outerBoundaryIs><gml:LinearRing><gml:coordinates>1,1,0 5,1,0 5,5,3 1,1,0</gml:coordinates></gml:LinearRing>'
                        '</gml:outerBoundaryIs></gml:Polygon></bldg:lod2MultiSurface></bldg:Building></cityObjectMember></CityModel>',
    "no_citymodel.gml": '<gml:FeatureCollection xmlns:gml="http://www.opengis.net/gml"><gml:featureMember/></gml:FeatureCollection>',
    "not_xml.gml": '<CityModel><cityObjectMember><Building></cityObjectMember>',
}
for name, text in GML_SEEDS.items():
    out(GML, name, text.encode())

# City scene files: every key, a minimal one, and broken ones (unknown key, bad depth, colour).
SCENE_SEEDS = {
    "full.scene.json": '{"crs": "EPSG:3946", "texture": "ortho.tif", "sources": [{"path": "buildings.geojson", '
                       '"height_attr": "HAUTEUR", "base_attr": "Z_MIN_SOL", "colour": [0.85, 0.45, 0.35], "depth": 12}, '
                       '{"path": "ground.tif", "role": "terrain", "depth": 9, "color": [0.4, 0.6, 0.3]}, '
                       '{"path": "city.gml", "lod": "2", "role": "solid"}]}',
    "minimal.scene.json": '{"sources": [{"path": "a.json"}]}',
    "unknown_key.scene.json": '{"sources": [{"path": "a.json", "heigth_attr": "h"}]}',
    "bad_values.scene.json": '{"sources": [{"path": "a.json", "depth": 99, "colour": [1, 2]}], "crs": 7}',
}
for name, text in SCENE_SEEDS.items():
    out("fuzz_scene", name, text.encode())


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
    out("fuzz_session", "version3.json", b'{"octrace_studio_session": 3}')
    out("fuzz_session", "layout.json", b'{"octrace_studio_session": 2, "layout": {"four_up": true, "crosshair": [3, 4, 5], "slice_at": [450.5, null, -30], "slice_window": "40,400"}}')
    out("fuzz_session", "truncated.json", full[:200])


session_seeds()


# ---------------------------------------------------------------- MetaImage (fuzz_metaimage)
def mha(fields, data=b""):
    return ("\n".join(fields) + "\n").encode() + data


MHA_BASE = ["ObjectType = Image", "NDims = 3", "BinaryData = True", "BinaryDataByteOrderMSB = False"]
short_cube = struct.pack("<64h", *[(x * 16 + y * 4 + z) * 10 - 300 for z in range(4) for y in range(4) for x in range(4)])
out("fuzz_metaimage", "local_short.mha",
    mha(MHA_BASE + ["TransformMatrix = 0 1 0 -1 0 0 0 0 1", "Offset = -10.5 20 3.25",
                    "ElementSpacing = 0.7 0.7 2.5", "AnatomicalOrientation = RAI", "DimSize = 4 4 4",
                    "ElementType = MET_SHORT", "ElementDataFile = LOCAL"], short_cube))
out("fuzz_metaimage", "local_float_msb.mha",
    mha(["ObjectType = Image", "NDims = 3", "BinaryData = True", "ElementByteOrderMSB = True",
         "Position = 0 0 0", "ElementSize = 1 1 1", "DimSize = 4 4 4", "ElementType = MET_FLOAT",
         "ElementDataFile = LOCAL"], struct.pack(">64f", *[v - 1.0 for v in struct.unpack("<64f", sphere)])))
out("fuzz_metaimage", "compressed.mha",
    mha(MHA_BASE + ["CompressedData = True", "CompressedDataSize = 40", "DimSize = 4 4 4",
                    "ElementType = MET_UCHAR", "ElementDataFile = LOCAL"],
        __import__("zlib").compress(bytes(range(64)))))
out("fuzz_metaimage", "detached.mhd",
    mha(MHA_BASE + ["HeaderSize = 16", "DimSize = 8 8 4", "ElementSpacing = 1 1 1",
                    "ElementType = MET_USHORT", "ElementDataFile = data.raw"]))
out("fuzz_metaimage", "not_3d.mha", mha(["ObjectType = Image", "NDims = 2", "DimSize = 4 4",
                                         "ElementType = MET_CHAR", "ElementDataFile = LOCAL"], bytes(16)))
out("fuzz_metaimage", "huge.mhd", mha(MHA_BASE + ["DimSize = 100000 100000 100000", "ElementType = MET_DOUBLE",
                                                  "ElementDataFile = data.raw"]))


# ---------------------------------------------------------------- formula_terms (fuzz_formula_terms)
def formula_seed(kind, nk, nt, given_depth, text):
    """The target's input: kind, levels, steps, the formula_terms text, then int16 numbers / 100."""
    sv = [-(k + 0.5) / nk for k in range(nk)]
    lev = [1.0 - (k + 0.5) / nk * 2 if kind == 3 else v for k, v in enumerate(sv)]
    numbers = [0, 1, 2] + [10, 11] + list(range(nt)) + lev + sv + [-v * v for v in sv]
    numbers += [50, 100, 150, 200, 250, 300] + [0.1 * (i % 3) for i in range(6 * nt)]
    numbers += [20, 3, 0.5, 40, 80, 150, 3]  # hc, a, b, z1, z2, href, k_c
    numbers += [(k + 0.5) / nk * (50 + 50 * i) for t in range(nt) for k in range(nk) for i in range(6)]
    numbers += [1] * 12 + [20 - 0.05 * k * (i + 1) for t in range(nt) for k in range(nk) for i in range(6)]
    ints = struct.pack("<%dh" % len(numbers), *[max(-32768, min(32767, int(round(v * 100)))) for v in numbers])
    return bytes([kind, nk - 1, (nt - 1) | (2 if given_depth else 0)]) + text.encode() + b"\n" + ints


G = "s: s C: C eta: zeta depth: h depth_c: hc"
out("fuzz_formula_terms", "g1.bin", formula_seed(0, 6, 1, False, G))
out("fuzz_formula_terms", "g2_two_steps.bin", formula_seed(1, 6, 2, False, G))
out("fuzz_formula_terms", "sigma.bin", formula_seed(2, 5, 1, False, "sigma: s eta: zeta depth: h"))
out("fuzz_formula_terms", "double_sigma.bin",
    formula_seed(3, 6, 1, False, "sigma: lev depth: h z1: z1 z2: z2 a: a href: href k_c: k_c"))
out("fuzz_formula_terms", "s_coordinate.bin", formula_seed(4, 8, 1, False, "s: s eta: zeta depth: h a: a b: b depth_c: hc"))
out("fuzz_formula_terms", "unknown_formula.bin", formula_seed(5, 4, 1, False, "sigma: s ps: h ptop: hc"))
out("fuzz_formula_terms", "given_depth.bin", formula_seed(6, 6, 2, True, ""))
out("fuzz_formula_terms", "foreign_term.bin", formula_seed(2, 4, 1, False, "sigma: s eta: zeta depth: foreign"))
out("fuzz_formula_terms", "malformed.bin", formula_seed(1, 3, 1, False, "s: s C C eta: : zeta depth:"))

print("seeds written under", HERE)
