#pragma once
// The CF interpretation of a NetCDF dataset opened through GDAL (internal): which variable,
// the role of each axis, the geographic mapping, masking and packing. NetcdfReader first
// checks the file on disk (signature, and for classic files that all announced data are
// there), then calls these. The fuzz target tests/fuzz/fuzz_netcdf_cf.cpp calls them on GDAL
// in-memory files (/vsimem/...), which have no path on disk.
#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"

#include <cstdint>
#include <string>

namespace octrace::io::detail {

/// The on-disk checks: the signature and, for classic files, that the data the header
/// announces are all there. Returns the format's name. Throws FormatNotSupported, FileError.
std::string checkNetcdfOnDisk(const std::string& path);

/// NetcdfReader::read without the on-disk checks; `gdalPath` is anything GDAL's netCDF
/// driver opens (a file, /vsimem/...). Throws as NetcdfReader::read.
ScalarField interpretNetcdf(const std::string& gdalPath, const FieldRequest& req);

/// NetcdfReader::describe without the on-disk checks; `format` names the format in the text.
std::string describeNetcdf(const std::string& gdalPath, const std::string& format, const FieldRequest& req);

}  // namespace octrace::io::detail
