#pragma once
/// @file ReliefReader.h
/// Reads relief rasters (land height and sea floor depth over longitude and latitude) for the
/// relief solid of CSG (csg/Relief.h, `relief:FILE`).
#include "octrace/csg/Relief.h"

#include <cstdint>
#include <string>

namespace octrace::io {

/// Reads a relief over longitude and latitude, heights in metres (up), rows and columns
/// increasing:
///   - NetCDF: the file's only numeric variable with two dimensions longer than 1, whose axes
///     are longitude and latitude by the CF rules of NetcdfReader (e.g. ETOPO's ROSE), evenly
///     spaced; missing values, valid range and packing as there. Units m (metres, METERS...) or
///     km; none: metres. A variable whose `positive` attribute is "down" or whose
///     standard_name or name says depth is negated.
///   - any other raster GDAL opens (GeoTIFF, ...): band 1, north-up, in a geographic CRS
///     (longitude/latitude degrees), nodata missing, heights in metres.
/// @throws InputError (missing file, no or several 2-D variables, axes that are not
///         longitude and latitude or not evenly spaced, unknown units, a projected raster),
///         FormatNotSupported (neither NetCDF nor a GDAL raster), FileError (GDAL cannot read
///         it), LimitError (more than `memoryBudget` bytes, 0 = no limit).
ReliefRaster readRelief(const std::string& path, std::uint64_t memoryBudget = 0);

}  // namespace octrace::io
