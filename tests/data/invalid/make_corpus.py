#!/usr/bin/env python3
"""Writes the invalid-input corpus (run once; the outputs are committed).

NRRD files are written byte by byte; NetCDF files from the CDL below with `ncgen`
(Debian package netcdf-bin). See README.md for what is wrong with each file.
"""
import gzip
import os
import struct
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


def nrrd_header(lines):
    return ("\n".join(["NRRD0004"] + lines) + "\n\n").encode()


RAW16 = ["type: float", "dimension: 3", "sizes: 16 16 16", "spacings: 1 1 1", "endian: little", "encoding: raw"]

# Header says 16x16x16 float (16384 bytes), only 1000 bytes follow.
write("invalid_truncated.nrrd", nrrd_header(RAW16) + bytes(1000))
# Wrong magic: "NRRX" instead of "NRRD".
write("invalid_magic.nrrd", b"NRRX0004\n" + nrrd_header(RAW16)[9:] + bytes(16384))
# Nothing at all.
write("invalid_empty.nrrd", b"")
# Detached header with a zero and a negative spacing (its data file is fine).
write("invalid_bad_spacing.nhdr", ("NRRD0004\ntype: uchar\ndimension: 3\nsizes: 12 4 4\n"
                                   "spacings: 1 0 -2\nencoding: raw\n"
                                   "data file: data_for_invalid_bad_spacing.raw\n").encode())
write("data_for_invalid_bad_spacing.raw", bytes(range(192)))
# Detached header naming a data file that does not exist.
write("invalid_missing_data_file.nhdr", ("NRRD0004\ntype: uchar\ndimension: 3\nsizes: 12 4 4\n"
                                         "spacings: 1 1 1\nencoding: raw\n"
                                         "data file: no_such_data_file.raw\n").encode())
# A 2-D image, not a volume.
write("invalid_not_3d.nrrd", nrrd_header(["type: uchar", "dimension: 2", "sizes: 16 16", "encoding: raw"]) + bytes(256))
# gzip stream that inflates to 100 bytes where 16x16x16 uchar = 4096 are needed.
write("invalid_truncated_gzip.nrrd",
      nrrd_header(["type: uchar", "dimension: 3", "sizes: 16 16 16", "spacings: 1 1 1", "encoding: gzip"])
      + gzip.compress(bytes(100), mtime=0))
# Space directions at 60 degrees to each other (a sheared grid).
write("invalid_sheared.nrrd",
      nrrd_header(["type: float", "dimension: 3", "space: left-posterior-superior", "sizes: 16 16 16",
                   "space directions: (1,0,0) (0.5,0.8660254037844386,0) (0,0,1)", "endian: little",
                   "encoding: raw", "space origin: (0,0,0)"])
      + struct.pack("<4096f", *([1.0] * 4096)))
# NetCDF files cut short: the first 3000 bytes of the valid fixtures in ../netcdf/.
for src, dst in (("dateline_cf.nc", "invalid_truncated.nc"), ("dateline_cf_nc4.nc", "invalid_truncated_hdf5.nc")):
    with open(os.path.join(HERE, "..", "netcdf", src), "rb") as f:
        write(dst, f.read()[:3000])
# Text with a NetCDF extension.
write("invalid_not_netcdf.nc", b"this is a text file, not NetCDF\n")
# Neither NetCDF nor NRRD, and an extension no reader claims.
write("invalid_unknown_format.dat", b"GIF89a\x01\x00\x01\x00\x00\x00\x00;")

CDL = {
    # Valid NetCDF without TEMP and without any 3-D variable.
    "invalid_no_variable": """netcdf invalid_no_variable {
dimensions:
  lon = 4 ; lat = 3 ; depth = 2 ;
variables:
  double lon(lon) ; lon:units = "degrees_east" ;
  double lat(lat) ; lat:units = "degrees_north" ;
  double depth(depth) ; depth:units = "m" ; depth:positive = "down" ;
  float bathymetry(lat, lon) ; bathymetry:units = "m" ;
data:
  lon = 0, 1, 2, 3 ; lat = 0, 1, 2 ; depth = 0, 10 ;
  bathymetry = 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12 ;
}
""",
    # TEMP exists but every sample equals missing_value.
    "invalid_all_masked": """netcdf invalid_all_masked {
dimensions:
  lon = 4 ; lat = 3 ; depth = 2 ;
variables:
  double lon(lon) ; lon:units = "degrees_east" ;
  double lat(lat) ; lat:units = "degrees_north" ;
  double depth(depth) ; depth:units = "m" ; depth:positive = "down" ;
  float TEMP(depth, lat, lon) ; TEMP:units = "deg C" ; TEMP:missing_value = -1.e+10f ;
data:
  lon = 0, 1, 2, 3 ; lat = 0, 1, 2 ; depth = 0, 10 ;
  TEMP = """ + ", ".join(["-1.e+10"] * 24) + """ ;
}
""",
}
for name, cdl in CDL.items():
    cdl_path = os.path.join(HERE, name + ".cdl.tmp")
    with open(cdl_path, "w") as f:
        f.write(cdl)
    subprocess.run(["ncgen", "-k", "classic", "-o", os.path.join(HERE, name + ".nc"), cdl_path], check=True)
    os.remove(cdl_path)
