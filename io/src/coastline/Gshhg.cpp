// GSHHG's shorelines from GMT's binned netCDF files (binned_GSHHS_{c,l,i,h}.nc), read through
// GDAL's multidimensional API. The layout (docs/dev/coastlines.md): the globe in square bins
// numbered row by row from the north-west corner; each bin lists its segments (pieces of
// shoreline inside the bin), each segment its points as unsigned 16-bit offsets from the bin's
// south-west corner in 1/65535 of the bin's side; a segment's 32-bit info word packs its
// number of points (bits 9 and up), its level (bits 6-8), and the bin sides it leaves and
// enters by (bits 0-5).
#include "octrace/io/Coastline.h"

#include "input/GdalSupport.h"

#include "octrace/util/Error.h"

#include <gdal_priv.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

namespace octrace::io {
namespace {

using detail::GdalMessages;

constexpr int kLand = 1, kLake = 2;

template <typename T>
std::vector<T> readArray(GDALGroup& root, const std::string& path, const char* name, GDALDataType type, std::size_t expected) {
    const auto a = root.OpenMDArray(name);
    if (!a || a->GetDimensionCount() != 1)
        throw FileError(path + ": no 1-D variable " + name + ": not a GSHHG binned shoreline file (binned_GSHHS_*.nc)");
    const std::size_t n = std::size_t(a->GetDimensions()[0]->GetSize());
    if (expected != std::size_t(-1) && n != expected)
        throw FileError(path + ": " + name + " has " + std::to_string(n) + " values where the file's counts give " +
                        std::to_string(expected));
    std::vector<T> out(n);
    const GUInt64 start = 0;
    const size_t count = n;
    if (n && !a->Read(&start, &count, nullptr, nullptr, GDALExtendedDataType::Create(type), out.data()))
        throw FileError(path + ": cannot read " + name + ": " + GdalMessages::last());
    return out;
}

int readScalar(GDALGroup& root, const std::string& path, const char* name) {
    const auto v = readArray<std::int32_t>(root, path, name, GDT_Int32, 1);
    if (v[0] <= 0) throw FileError(path + ": " + name + " is " + std::to_string(v[0]) + ", expected a positive count");
    return v[0];
}

}  // namespace

std::string gshhgResolutionName(GshhgResolution r) {
    switch (r) {
    case GshhgResolution::Crude: return "crude";
    case GshhgResolution::Low: return "low";
    case GshhgResolution::Intermediate: return "intermediate";
    case GshhgResolution::High: return "high";
    }
    return "crude";
}

GshhgResolution gshhgResolutionFor(const LonLatBox& r) {
    const double midLat = 0.5 * (std::clamp(r.latMin, -90.0, 90.0) + std::clamp(r.latMax, -90.0, 90.0));
    const double lonSpan = std::min(360.0, r.lonMax - r.lonMin) * std::cos(midLat * 3.14159265358979323846 / 180.0);
    const double side = std::max(lonSpan, r.latMax - r.latMin);
    return side > 90.0 ? GshhgResolution::Crude : side > 25.0 ? GshhgResolution::Low : side > 6.0 ? GshhgResolution::Intermediate : GshhgResolution::High;
}

std::string gshhgPath(GshhgResolution r) {
    const char* dir = std::getenv("OCTRACE_GSHHG_DIR");
    const std::string base = dir && *dir ? std::string(dir) : std::string("/usr/share/gmt-gshhg");
    return base + "/binned_GSHHS_" + gshhgResolutionName(r).substr(0, 1) + ".nc";
}

std::string gshhgPackage(GshhgResolution r) {
    return r == GshhgResolution::Crude || r == GshhgResolution::Low ? "gmt-gshhg-low" : "gmt-gshhg-high";
}

Coastlines readGshhg(GshhgResolution resolution, const LonLatBox& region, bool lakes) {
    const std::string path = gshhgPath(resolution);
    if (!std::filesystem::exists(path))
        throw FileError(path + ": no GSHHG " + gshhgResolutionName(resolution) + " shorelines: install the Debian package " +
                        gshhgPackage(resolution) + " (or give coastlines of your own as a vector file, or none)");
    detail::registerGdal();
    GdalMessages messages;
    const char* const drivers[] = {"netCDF", nullptr};
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_MULTIDIM_RASTER | GDAL_OF_READONLY, drivers));
    if (!ds) throw FileError(path + ": GDAL's netCDF driver cannot open it: " + GdalMessages::last());
    const auto root = ds->GetRootGroup();
    if (!root) throw FileError(path + ": GDAL gives no root group: " + GdalMessages::last());

    const int binMinutes = readScalar(*root, path, "Bin_size_in_minutes");
    const int nx = readScalar(*root, path, "N_bins_in_360_longitude_range");
    const int ny = readScalar(*root, path, "N_bins_in_180_degree_latitude_range");
    const int nBins = readScalar(*root, path, "N_bins_in_file");
    const int nSegments = readScalar(*root, path, "N_segments_in_file");
    const int nPoints = readScalar(*root, path, "N_points_in_file");
    if (binMinutes * nx != 360 * 60 || binMinutes * ny != 180 * 60 || nBins != nx * ny)
        throw FileError(path + ": bins of " + std::to_string(binMinutes) + "' in " + std::to_string(nx) + " x " + std::to_string(ny) +
                        " (" + std::to_string(nBins) + " in the file) do not tile the globe");
    const auto firstSegment = readArray<std::int32_t>(*root, path, "Id_of_first_segment_in_a_bin", GDT_Int32, std::size_t(nBins));
    const auto segmentCount = readArray<std::int32_t>(*root, path, "N_segments_in_a_bin", GDT_Int32, std::size_t(nBins));
    const auto info = readArray<std::int32_t>(*root, path, "Embedded_npts_levels_exit_entry_for_a_segment", GDT_Int32, std::size_t(nSegments));
    const auto firstPoint = readArray<std::int32_t>(*root, path, "Id_of_first_point_in_a_segment", GDT_Int32, std::size_t(nSegments));
    // Stored as int16, meant as uint16: read as stored (GDAL would clamp negatives to 0 when
    // converting) and reinterpreted below.
    const auto dx = readArray<std::int16_t>(*root, path, "Relative_longitude_from_SW_corner_of_bin", GDT_Int16, std::size_t(nPoints));
    const auto dy = readArray<std::int16_t>(*root, path, "Relative_latitude_from_SW_corner_of_bin", GDT_Int16, std::size_t(nPoints));

    Coastlines out;
    out.source = "GSHHG " + gshhgResolutionName(resolution) + " (" + path + ")";
    const double side = binMinutes / 60.0, unit = side / 65535.0;
    LonLatBox bin;
    std::vector<dvec2> line;
    for (int b = 0; b < nBins; ++b) {
        // Bins run west to east from 0°, rows north to south from 90°N.
        bin.lonMin = (b % nx) * side, bin.lonMax = bin.lonMin + side;
        bin.latMax = 90.0 - (b / nx) * side, bin.latMin = bin.latMax - side;
        if (bin.latMax < region.latMin || bin.latMin > region.latMax) continue;
        const double shift = std::ceil((region.lonMin - bin.lonMax) / 360.0) * 360.0;
        if (bin.lonMin + shift > region.lonMax) continue;  // no copy of the bin meets the region
        const std::int64_t s0 = firstSegment[std::size_t(b)], s1 = s0 + segmentCount[std::size_t(b)];
        if (s0 < 0 || s1 > nSegments || s1 < s0)
            throw FileError(path + ": bin " + std::to_string(b) + " lists segments " + std::to_string(s0) + " to " + std::to_string(s1 - 1) +
                            " of " + std::to_string(nSegments));
        for (std::int64_t s = s0; s < s1; ++s) {
            const std::uint32_t word = std::uint32_t(info[std::size_t(s)]);
            const int level = int((word >> 6) & 7u);
            if (level != kLand && !(lakes && level == kLake)) continue;
            const std::int64_t p0 = firstPoint[std::size_t(s)], n = std::int64_t(word >> 9);
            if (p0 < 0 || n < 0 || p0 + n > nPoints)
                throw FileError(path + ": segment " + std::to_string(s) + " has points " + std::to_string(p0) + " to " +
                                std::to_string(p0 + n - 1) + " of " + std::to_string(nPoints));
            if (n < 2) continue;
            line.clear();
            for (std::int64_t p = p0; p < p0 + n; ++p)
                line.push_back({bin.lonMin + std::uint16_t(dx[std::size_t(p)]) * unit, bin.latMin + std::uint16_t(dy[std::size_t(p)]) * unit});
            addWrappedCopies(line, region, out.lines);
        }
    }
    return out;
}

void addWrappedCopies(const std::vector<dvec2>& line, const LonLatBox& region, std::vector<std::vector<dvec2>>& out) {
    if (line.size() < 2) return;
    double lo = line[0].x, hi = lo, latLo = line[0].y, latHi = latLo;
    for (const dvec2& p : line) lo = std::min(lo, p.x), hi = std::max(hi, p.x), latLo = std::min(latLo, p.y), latHi = std::max(latHi, p.y);
    if (latHi < region.latMin || latLo > region.latMax) return;
    // The first shift whose copy ends east of the region's west edge, then every copy that
    // starts west of its east edge.
    for (double shift = std::ceil((region.lonMin - hi) / 360.0) * 360.0; lo + shift <= region.lonMax; shift += 360.0) {
        std::vector<dvec2>& copy = out.emplace_back(line);
        for (dvec2& p : copy) p.x += shift;
    }
}

}  // namespace octrace::io
