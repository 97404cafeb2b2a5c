#pragma once
/// @file Coastline.h
/// Shorelines for map figures, as polylines in longitude/latitude (degrees, WGS84): from GSHHG
/// (the Global Self-consistent, Hierarchical, High-resolution Geography database of Wessel and
/// Smith, as Debian's gmt-gshhg-low/-high ship it: GMT's binned netCDF, decoded here; the format
/// is described in docs/dev/coastlines.md) or from any vector file OGR reads.
#include "octrace/util/Math.h"

#include <string>
#include <vector>

namespace octrace::io {

/// A longitude/latitude box. Longitudes are unwrapped (lonMin < lonMax, possibly beyond 180 or
/// below -180, e.g. 20.5 .. 379.5 for a global grid starting at 20.5°E): lines are returned
/// shifted by multiples of 360° into it.
struct LonLatBox {
    double lonMin = -180.0, lonMax = 180.0, latMin = -90.0, latMax = 90.0;
};

/// Shorelines as polylines of (longitude, latitude) in degrees; consecutive points of a line
/// never jump across the globe (a line crossing the box's longitude seam comes as the copies
/// that overlap the box, shifted by 360°).
struct Coastlines {
    std::vector<std::vector<dvec2>> lines;
    std::string source;  ///< what they were read from, for messages: "GSHHG 2.3.7 low (/usr/share/...)"
};

/// GSHHG's resolutions as Debian ships them (full is not packaged): crude (binned_GSHHS_c.nc,
/// 25 km), low (l, 5 km), intermediate (i, 1 km), high (h, 0.2 km).
enum class GshhgResolution { Crude, Low, Intermediate, High };

/// "crude", "low", "intermediate", "high".
std::string gshhgResolutionName(GshhgResolution r);
/// The resolution for a region: crude when its larger side (longitude span times the cosine of
/// its middle latitude, or latitude span) exceeds 90°, low above 25°, intermediate above 6°,
/// high for a few degrees.
GshhgResolution gshhgResolutionFor(const LonLatBox& region);
/// The binned file of a resolution: $OCTRACE_GSHHG_DIR, else /usr/share/gmt-gshhg, then
/// binned_GSHHS_{c,l,i,h}.nc.
std::string gshhgPath(GshhgResolution r);
/// The Debian package that holds it: gmt-gshhg-low (crude, low) or gmt-gshhg-high (intermediate, high).
std::string gshhgPackage(GshhgResolution r);

/// The level-1 shorelines (land against ocean, Antarctica's ice front included), and with
/// `lakes` also level 2 (lake shores), of the GSHHG bins that meet `region`, each bin's piece a
/// polyline. @throws FileError naming the file and the Debian package to install when it is
/// missing, FileError when it is not a GSHHG binned file (a variable missing, counts that
/// disagree). Thread-safe (GDAL opens its own handle).
Coastlines readGshhg(GshhgResolution resolution, const LonLatBox& region, bool lakes = false);

/// The lines of a vector file OGR reads (shapefile, GeoPackage, GeoJSON, ...): line strings and
/// polygon rings (every layer, multi-geometries and collections included), reprojected to
/// WGS84 longitude/latitude when the layer has another CRS, unwrapped along each line and kept
/// where they meet `region`. @throws FileError when the file is missing, FormatNotSupported
/// when OGR cannot open it as vector data, InputError when it holds no line or polygon.
Coastlines readVectorCoastlines(const std::string& path, const LonLatBox& region);

/// Appends to `out` the copies of `line` (unwrapped: no step over 180° in longitude) shifted
/// by multiples of 360° whose longitude range meets `region`'s (and whose latitude range does).
void addWrappedCopies(const std::vector<dvec2>& line, const LonLatBox& region, std::vector<std::vector<dvec2>>& out);

}  // namespace octrace::io
