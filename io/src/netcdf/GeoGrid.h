#pragma once
// Maps longitude/latitude/depth axes to world kilometres per the project's coordinate contract
// (internal, no GDAL types, no file access).
#include "octrace/build/ScalarField.h"
#include "octrace/io/FieldRequest.h"

#include <cstddef>
#include <string>
#include <vector>

namespace octrace::io::detail {

/// Which stored samples of one file axis make the output axis, in output order.
struct AxisSelection {
    std::vector<std::size_t> stored;  ///< index into the file's axis, per output sample
    std::vector<double> world;        ///< world coordinate per output sample, strictly increasing
};

struct GeoMapping {
    AxisSelection x, y, z;            ///< longitude, latitude, vertical
    double lon0 = 0.0, lat0 = 0.0;    ///< centre of the region (or the grid), degrees
    double verticalScale = 1.0;
    std::vector<std::string> notes;
};

constexpr double kEarthRadiusKm = ScalarField::Geographic::kEarthRadiusKm;

/// Selects the grid points inside `req`'s region (all of them without one), unwraps
/// longitudes so the selection is contiguous, and computes world coordinates.
/// `depthKm` is positive down. `path` prefixes messages. `minLevels`: 1 for a map (a 2-D
/// field, one level), whose vertical scale is then 1 unless `req` gives one.
/// @throws UsageError (bad region or vertical scale), FileError (non-finite or non-monotonic
///         axis values), EmptyResultError (fewer than 2 grid points along a horizontal axis,
///         fewer than `minLevels` along the vertical).
GeoMapping mapGeographic(const std::string& path, const std::vector<double>& lon, const std::vector<double>& lat,
                         const std::vector<double>& depthKm, const FieldRequest& req, std::size_t minLevels = 2);

/// The auto rule's latitude: a region (else a grid) in one hemisphere that reaches this far
/// towards its pole is mapped polar stereographic.
constexpr double kPolarAutoLatitude = 75.0;

/// The pole of the polar mapping for `req` (+1 north, -1 south), 0 for the lon/lat mapping:
/// `projection` lonlat or polar decides; auto is polar when the region (else latLo..latHi, the
/// grid's latitudes) lies in one hemisphere and reaches kPolarAutoLatitude or beyond.
int polarPole(const FieldRequest& req, double latLo, double latHi);
/// Why polarPole chose `pole`, for notes.
std::string polarReason(const FieldRequest& req, int pole);

/// The polar mapping's axes: x and y are a plane lattice already in world km (PolarStereographic.h),
/// kept whole (stored = index); z as mapGeographic selects and scales it.
/// @throws UsageError (vertical scale), FileError (vertical axis), EmptyResultError (levels).
GeoMapping mapPolar(const std::string& path, const std::vector<double>& xKm, const std::vector<double>& yKm,
                    const std::vector<double>& depthKm, const FieldRequest& req, std::size_t minLevels = 2);

/// True when `v` is uniformly spaced (to 1e-6 of the step); fewer than 3 values are.
bool isUniform(const std::vector<double>& v);

/// A non-geographic axis: every stored sample, in increasing coordinate order (reversed when
/// the file's coordinates decrease); world = the coordinate. @throws FileError if not monotonic.
AxisSelection increasingAxis(const std::string& path, const std::string& axisName, const std::vector<double>& values);

}  // namespace octrace::io::detail
