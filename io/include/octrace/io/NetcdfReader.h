#pragma once
/// @file NetcdfReader.h
/// Reads 3-D variables of NetCDF files (classic, 64-bit offset, CDF-5, NetCDF-4/HDF5) and of
/// Zarr v2 stores (a folder: the same CF interpretation, through GDAL's Zarr driver) through
/// GDAL's multidimensional API, mapping geographic grids to world kilometres.
#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"
#include "octrace/io/TimeAxis.h"

#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io {

class NetcdfReader {
public:
    /// Reads one 3-D variable (`req.variable`, or the file's only 3-D variable).
    ///
    /// Geographic grids (1-D longitude, latitude and vertical axes, recognised by units such as
    /// degrees_east / degrees_north / m with positive="down", by standard_name, or by names
    /// like lon/lat/depth/lev/z) follow the project's coordinate contract: x = R (lon - lon0)
    /// cos(lat0), y = R (lat - lat0), z = -depth_km * vertical scale, R = 6371 km, (lon0, lat0)
    /// the centre of the region (or of the whole grid). Longitudes are unwrapped so the region
    /// is contiguous (it may cross the dateline or the file's own seam). Every axis is stored
    /// increasing: uniform axes as origin + spacing, uneven ones (e.g. depth levels) in
    /// ScalarField::coords. Other grids keep their coordinate variables (or indices) as world
    /// units. Extra dimensions (e.g. time) are read at index 0 with a warning.
    ///
    /// Samples equal to missing_value / _FillValue, outside valid_min/valid_max/valid_range, or
    /// not finite are invalid; scale_factor / add_offset are applied. ScalarField::notes
    /// describe the mapping (centre, region, vertical scale).
    ///
    /// @throws InputError (missing file, unknown variable, no or several 3-D variables, a
    ///         region on a non-geographic grid), FormatNotSupported (not NetCDF), FileError
    ///         (truncated, GDAL cannot open or read it, non-monotonic axes), UsageError (malformed region
    ///         or negative vertical scale), EmptyResultError (fewer than 2 grid points in the
    ///         region along an axis, or no valid sample), LimitError (the samples would need
    ///         more than `req.memoryBudget` bytes: refused before they are allocated).
    /// Thread-safe as far as GDAL is: each call opens its own dataset.
    static ScalarField read(const std::string& path, const FieldRequest& req);

    /// Multi-line human-readable summary for `octrace info`: format, dimensions with their
    /// axis role and values, every variable with dims, units and valid value range, and the
    /// world geometry of the default (or first) 3-D variable. Throws as read(), except that a
    /// variable without valid samples, or one too large for `memoryBudget` bytes (0 = no
    /// limit), is reported in the text.
    static std::string describe(const std::string& path, std::uint64_t memoryBudget = 0);
    /// The same, with the last part describing the field `req` asks for (variable, sound speed,
    /// region, depth range, time step) instead of the default one; an error reading it is
    /// thrown as by read().
    static std::string describe(const std::string& path, const FieldRequest& req);

    /// The names read() accepts without a choice being refused: the short names of the
    /// variables with at least 3 dimensions longer than 1, in the file's order (for a variable
    /// chooser, e.g. the studio's). Throws as read() for a file that cannot be opened.
    static std::vector<std::string> volumeVariables(const std::string& path);

    /// The time dimension of the variable `req` asks for (as read() chooses it; for sound speed
    /// derived from temperature and salinity, the temperature's), with its coordinate values and
    /// their dates; empty when the variable has none. Reads no samples but the axis's.
    /// Throws as read() for a file that cannot be opened or a variable that is not found.
    static TimeAxis timeAxis(const std::string& path, const FieldRequest& req);
};

}  // namespace octrace::io
