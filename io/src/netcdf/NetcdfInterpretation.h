#pragma once
// The CF interpretation of a dataset (internal): which variable, the role of each axis, the
// geographic mapping, masking and packing. It reads through a CfSource: a NetCDF file opened
// through GDAL (NetcdfFile) or arrays handed over in memory (CfMemorySource, the public
// CfDataset.h). NetcdfReader first checks the file on disk (signature, and for classic files
// that all announced data are there), then calls interpretNetcdf / describeNetcdf. The fuzz
// target tests/fuzz/fuzz_netcdf_cf.cpp calls them on GDAL in-memory files (/vsimem/...), which
// have no path on disk.
#include "netcdf/CfSource.h"
#include "netcdf/NetcdfFile.h"
#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"

#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io::detail {

/// The on-disk checks: the signature and, for classic files, that the data the header
/// announces are all there. Returns the format's name. Throws FormatNotSupported, FileError.
std::string checkNetcdfOnDisk(const std::string& path);

/// What the on-disk checks found: the format's name and the GDAL driver that reads it.
struct CfOnDisk {
    std::string format;
    GdalDriver driver = GdalDriver::NetCdf;
};

/// checkNetcdfOnDisk for a file; for a folder, the Zarr store's (checkZarrOnDisk: Zarr
/// metadata at its root, not the final v3 layout). Throws as those.
CfOnDisk checkCfOnDisk(const std::string& path);

/// Refuses a request before any data are touched: a bad region or vertical scale (UsageError
/// naming `source`).
void checkFieldRequest(const std::string& source, const FieldRequest& req);

/// The field `req` asks for from `data` (after checkFieldRequest); `source` names the data in
/// messages and in ScalarField::source. Throws as NetcdfReader::read.
ScalarField interpretCf(const std::string& source, const CfSource& data, const FieldRequest& req);

/// The text of `octrace info` for `data`: `source`, then `formatLine`, then the dimensions, the
/// variables and the grid `req` asks for.
std::string describeCf(const std::string& source, const std::string& formatLine, const CfSource& data,
                       const FieldRequest& req);

/// Short names of the variables of `data` that can be drawn as volumes (3 dimensions longer than 1).
std::vector<std::string> cfVolumeNames(const CfSource& data);

/// NetcdfReader::read without the on-disk checks; `gdalPath` is anything GDAL's netCDF
/// driver (or Zarr driver) opens (a file, a store, /vsimem/...). Throws as NetcdfReader::read.
ScalarField interpretNetcdf(const std::string& gdalPath, const FieldRequest& req,
                            GdalDriver driver = GdalDriver::NetCdf);

/// NetcdfReader::describe without the on-disk checks; `format` names the format in the text.
std::string describeNetcdf(const std::string& gdalPath, const std::string& format, const FieldRequest& req,
                           GdalDriver driver = GdalDriver::NetCdf);

}  // namespace octrace::io::detail
