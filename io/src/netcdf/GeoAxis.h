#pragma once
// Recognises what a 1-D grid axis of a NetCDF variable is (internal, no GDAL types).
#include <string>
#include <vector>

namespace octrace::io::detail {

enum class AxisRole { Longitude, Latitude, Vertical, Time, Other };

/// What the file says about one dimension and its coordinate variable.
struct AxisInfo {
    std::string name;           ///< dimension name
    std::size_t size = 0;
    std::string units, positive, standardName, axis, longName, calendar, bounds;  ///< coordinate variable attributes
    std::string coordinateVariable;  ///< name of the variable the values come from (empty: none)
    std::string gdalType, gdalDirection;  ///< GDAL's guess (e.g. HORIZONTAL_X / EAST), may be empty
    std::vector<double> values;  ///< coordinate values; empty when there is no coordinate variable
};

struct AxisClass {
    AxisRole role = AxisRole::Other;
    bool positiveDown = true;  ///< vertical only: larger values are deeper
    double toKm = 0.001;       ///< vertical only: factor from the file's units to km
    double toDbar = 0.0;       ///< vertical only: factor from the file's units to dbar for a pressure axis, else 0
    std::string note;          ///< assumption made, for ScalarField::notes (may be empty)
};

/// Role from units first (degrees_east / degrees_north and variants, "since" for time, length
/// units or `positive` for vertical), then standard_name and the CF `axis` attribute, then
/// GDAL's dimension type, then the name (lon/longitude, lat/latitude, depth/lev/level/z, ...).
AxisClass classifyAxis(const AxisInfo& axis);

const char* roleName(AxisRole role);

}  // namespace octrace::io::detail
