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
# A NUL byte in a header comment: vtkNrrdReader ends the header there and never returns
# (found by fuzz_nrrd, see docs/dev/fuzzing.md).
write("invalid_nul_in_header.nrrd", b"NRRD0004\ntype: double\ndimension: 3\nsizes: 2 2 2\nencoding: ascii\n"
                                    b"# a NUL \0 byte\n\n0 1 2 3\n4 5 6 7\n")
# CDF-5 header whose first dimension name is 2^64 - 16 bytes long: as a signed file offset
# that is -16, and the header walker went round in circles (found by fuzz_netcdf_classic_header).
write("invalid_huge_name_length.nc", b"CDF\x05" + bytes(8) + struct.pack(">I", 10) + struct.pack(">Q", 2**40)
      + struct.pack(">Q", 2**64 - 16))
# 29 bytes of gzip data whose header announces 2048x2048x1024 doubles (32 GiB): deflate inflates
# at most 1032:1, so it is refused before VTK allocates the volume.
write("invalid_oversized_gzip.nrrd",
      nrrd_header(["type: double", "dimension: 3", "sizes: 2048 2048 1024", "endian: little", "encoding: gzip"])
      + gzip.compress(bytes(1000), mtime=0))
# Detached slices named by a pattern with step 2: two files for four slices. vtkNrrdReader
# reads one slice per file and read past the end of its file list (found by fuzz_nrrd).
write("invalid_fewer_files_than_slices.nhdr",
      ("NRRD0004\ntype: uchar\ndimension: 3\nsizes: 12 4 4\nspacings: 1 1 1\nencoding: raw\n"
       "data file: data_for_invalid_fewer_files_than_slices.%d.raw 1 4 2\n").encode())
for i in (1, 3):
    write("data_for_invalid_fewer_files_than_slices.%d.raw" % i, bytes(range(96)))
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
