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
# Absurd headers (limits that fail cleanly): each is refused from its header, before any
# large allocation. 8x8x8 uchar samples follow where the header would otherwise be valid.
U8 = ["type: uchar", "dimension: 3", "encoding: raw"]
SAMPLES512 = bytes(range(256)) * 2
# Dimensions of 10^9: more than the 2^24 points octrace reads along one axis.
write("invalid_huge_sizes.nrrd", nrrd_header(["type: float", "dimension: 3", "sizes: 1000000000 1000000000 1000000000",
                                              "endian: little", "encoding: raw"]) + bytes(8))
# 4000^3 floats (256 GB): more samples than the supported 2^32.
write("invalid_too_many_samples.nrrd", nrrd_header(["type: float", "dimension: 3", "sizes: 4000 4000 4000",
                                                    "endian: little", "encoding: raw"]) + bytes(8))
# A size beyond 64 bits (2^64 + 1): strtoll overflows.
write("invalid_size_overflow.nrrd", nrrd_header(U8 + ["sizes: 18446744073709551617 2 2"]) + bytes(8))
# Negative and infinite spacings, a NaN origin, a zero-length space direction.
write("invalid_negative_spacing.nrrd", nrrd_header(U8 + ["sizes: 8 8 8", "spacings: 1 1 -2"]) + SAMPLES512)
write("invalid_infinite_spacing.nrrd", nrrd_header(U8 + ["sizes: 8 8 8", "spacings: 1 inf 1"]) + SAMPLES512)
write("invalid_nan_origin.nrrd", nrrd_header(U8 + ["sizes: 8 8 8", "space: left-posterior-superior",
                                                   "space directions: (1,0,0) (0,1,0) (0,0,1)",
                                                   "space origin: (0,nan,0)"]) + SAMPLES512)
write("invalid_zero_space_direction.nrrd", nrrd_header(U8 + ["sizes: 8 8 8", "space: left-posterior-superior",
                                                             "space directions: (1,0,0) (0,0,0) (0,0,1)"]) + SAMPLES512)
# Finite spacings whose grid is not: 7 x 1e308 overflows, 7 x 1e-310 is denormal.
write("invalid_infinite_extent.nrrd", nrrd_header(U8 + ["sizes: 8 8 8", "spacings: 1e308 1 1"]) + SAMPLES512)
write("invalid_tiny_extent.nrrd", nrrd_header(U8 + ["sizes: 8 8 8", "spacings: 1e-310 1e-310 1e-310"]) + SAMPLES512)


def classic_header(version, dims, var_dims, var_type):
    """A NetCDF classic header (CDF-1 or CDF-5) with the named dimensions and one variable
    `v` over `var_dims` (indices), no attributes, whose data start right after the header."""
    count = (lambda n: struct.pack(">Q", n)) if version == 5 else (lambda n: struct.pack(">I", n))
    name = lambda s: count(len(s)) + s.encode() + bytes(-len(s) % 4)
    h = b"CDF" + bytes([version]) + count(0)
    h += struct.pack(">I", 10) + count(len(dims)) + b"".join(name(n) + count(size) for n, size in dims)
    h += struct.pack(">II", 0, 0) if version != 5 else struct.pack(">I", 0) + count(0)  # no global attributes
    h += struct.pack(">I", 11) + count(1) + name("v") + count(len(var_dims)) + b"".join(count(d) for d in var_dims)
    h += struct.pack(">I", 0) + count(0)  # no variable attributes
    h += struct.pack(">I", var_type) + count(min(2**32 - 4, 2**64 - 1))  # vsize: clamped, recomputed by readers
    begin = len(h) + (8 if version == 5 else 4)
    return h + (struct.pack(">Q", begin) if version == 5 else struct.pack(">I", begin))


# CDF-1 float v(depth, lat, lon) with lon = 10^9: 16 GB of data announced in a 132-byte file.
write("invalid_billion_points.nc", classic_header(1, [("lon", 10**9), ("lat", 2), ("depth", 2)], [2, 1, 0], 5) + bytes(16))
# CDF-5 double v(x, y, z) with three dimensions of 2^40: the byte count overflows 64 bits.
write("invalid_size_overflow.nc", classic_header(5, [("x", 2**40), ("y", 2**40), ("z", 2**40)], [0, 1, 2], 6) + bytes(16))

# NetCDF files cut short: the first 3000 bytes of the valid fixtures in ../netcdf/.
for src, dst in (("dateline_cf.nc", "invalid_truncated.nc"), ("dateline_cf_nc4.nc", "invalid_truncated_hdf5.nc")):
    with open(os.path.join(HERE, "..", "netcdf", src), "rb") as f:
        write(dst, f.read()[:3000])
# Text with a NetCDF extension.
write("invalid_not_netcdf.nc", b"this is a text file, not NetCDF\n")
# Neither NetCDF nor NRRD, and an extension no reader claims.
write("invalid_unknown_format.dat", b"GIF89a\x01\x00\x01\x00\x00\x00\x00;")


TEMP_0_23 = "TEMP = " + ", ".join(str(i) for i in range(24))


def grid_cdl(name, lat="0, 1, 2", depth="0, 10", variable='float TEMP(depth, lat, lon) ; TEMP:units = "deg C" ;',
             values=TEMP_0_23):
    """CDL of a 4 x 3 x 2 longitude / latitude / depth grid and one variable on it."""
    return """netcdf %s {
dimensions:
  lon = 4 ; lat = 3 ; depth = 2 ;
variables:
  double lon(lon) ; lon:units = "degrees_east" ;
  double lat(lat) ; lat:units = "degrees_north" ;
  double depth(depth) ; depth:units = "m" ; depth:positive = "down" ;
  %s
data:
  lon = 0, 1, 2, 3 ; lat = %s ; depth = %s ;
  %s ;
}
""" % (name, variable, lat, depth, values)


CDL = {
    # Valid NetCDF without TEMP and without any 3-D variable.
    "invalid_no_variable": grid_cdl("invalid_no_variable", variable='float bathymetry(lat, lon) ; bathymetry:units = "m" ;',
                                    values="bathymetry = " + ", ".join(str(i) for i in range(1, 13))),
    # TEMP exists but every sample equals missing_value.
    "invalid_all_masked": grid_cdl(
        "invalid_all_masked", variable='float TEMP(depth, lat, lon) ; TEMP:units = "deg C" ; TEMP:missing_value = -1.e+10f ;',
        values="TEMP = " + ", ".join(["-1.e+10"] * 24)),
    # A latitude that is NaN; two depth levels at the same depth (a zero spacing).
    "invalid_nan_coordinate": grid_cdl("invalid_nan_coordinate", lat="0, NaN, 2"),
    "invalid_repeated_coordinate": grid_cdl("invalid_repeated_coordinate", depth="10, 10"),
    # A non-geographic grid whose x coordinates (-1e308, 1e308) are finite but 2e308 apart.
    "invalid_infinite_extent": """netcdf invalid_infinite_extent {
dimensions:
  x = 2 ; y = 3 ; z = 2 ;
variables:
  double x(x) ; x:units = "km" ;
  double y(y) ; y:units = "km" ;
  float density(z, y, x) ;
data:
  x = -1e308, 1e308 ; y = 0, 1, 2 ;
  density = """ + ", ".join(str(i) for i in range(12)) + """ ;
}
""",
}
# NetCDF-4 (HDF5) whose longitude has 10^9 points: chunked storage with nothing written keeps
# the file small, and reading the coordinate alone would allocate 8 GB.
CDL_NC4 = {
    "invalid_billion_points_nc4": """netcdf invalid_billion_points_nc4 {
dimensions:
  lon = 1000000000 ; lat = 2 ; depth = 2 ;
variables:
  double lon(lon) ; lon:units = "degrees_east" ; lon:_Storage = "chunked" ; lon:_ChunkSizes = 1024 ;
  double lat(lat) ; lat:units = "degrees_north" ;
  double depth(depth) ; depth:units = "m" ; depth:positive = "down" ;
  float TEMP(depth, lat, lon) ; TEMP:_Storage = "chunked" ; TEMP:_ChunkSizes = 1, 1, 1024 ;
data:
  lat = 0, 1 ; depth = 0, 10 ;
}
""",
}
for kind, table in (("classic", CDL), ("nc4", CDL_NC4)):
    for name, cdl in table.items():
        cdl_path = os.path.join(HERE, name + ".cdl.tmp")
        with open(cdl_path, "w") as f:
            f.write(cdl)
        subprocess.run(["ncgen", "-k", kind, "-o", os.path.join(HERE, name + ".nc"), cdl_path], check=True)
        os.remove(cdl_path)
