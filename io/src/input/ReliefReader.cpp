#include "octrace/io/ReliefReader.h"

#include "input/FormatSniffer.h"
#include "input/GdalSupport.h"
#include "netcdf/GeoAxis.h"
#include "netcdf/GeoGrid.h"
#include "input/InputFile.h"
#include "netcdf/NetcdfFile.h"
#include "netcdf/NetcdfInterpretation.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace octrace::io {
namespace {

using namespace detail;

constexpr float kMissing = std::numeric_limits<float>::quiet_NaN();

void checkBudget(const std::string& path, std::uint64_t samples, std::uint64_t budget) {
    const std::uint64_t need = samples * (sizeof(double) + 2 * sizeof(float));  // the read, the heights, the pyramid
    if (budget && need > budget)
        throw LimitError(path + ": the relief's " + std::to_string(samples) + " heights need about " + std::to_string(need >> 20) +
                         " MiB, more than the memory budget (`max_memory`)");
}

/// Metres per unit of the heights; InputError for units that are not a length.
double metresPer(const std::string& path, const std::string& variable, const std::string& units) {
    const std::string u = lower(trim(units));
    if (u.empty()) {
        log::info(path + ": " + variable + " has no units: taken as metres");
        return 1.0;
    }
    if (u == "m" || u == "meter" || u == "meters" || u == "metre" || u == "metres") return 1.0;
    if (u == "km" || u == "kilometers" || u == "kilometres") return 1000.0;
    throw InputError(path + ": the relief " + variable + " is in '" + units + "', expected a length (m or km)");
}

/// One evenly spaced, increasing axis of the raster from a NetCDF axis: first value, step and
/// whether the file stores it decreasing.
struct EvenAxis {
    double first = 0.0, step = 1.0;
    bool reversed = false;
};

EvenAxis evenAxis(const std::string& path, const AxisInfo& a) {
    if (a.values.size() < 2) throw InputError(path + ": the relief's axis " + a.name + " has no coordinate values");
    if (!isUniform(a.values))
        throw InputError(path + ": the relief's axis " + a.name + " is not evenly spaced (a relief raster must be)");
    EvenAxis e;
    const double step = (a.values.back() - a.values.front()) / double(a.values.size() - 1);
    if (!(step != 0.0) || !std::isfinite(step)) throw InputError(path + ": the relief's axis " + a.name + " does not advance");
    e.reversed = step < 0.0;
    e.step = std::abs(step);
    e.first = e.reversed ? a.values.back() : a.values.front();
    return e;
}

ReliefRaster readNetcdfRelief(const std::string& path, std::uint64_t budget) {
    checkNetcdfOnDisk(path);
    NetcdfFile file(path);
    std::vector<const VariableInfo*> found;
    std::string names;
    for (const auto& v : file.variables())
        if (v.numeric && !v.coordinate && !v.auxiliary && v.extent() == 2) {
            found.push_back(&v);
            names += (names.empty() ? "" : ", ") + v.signature();
        }
    if (found.size() != 1)
        throw InputError(path + ": a relief needs exactly one 2-D variable over longitude and latitude, found " +
                         (found.empty() ? std::string("none") : names));
    const VariableInfo& var = *found.front();
    int lonDim = -1, latDim = -1;
    AxisInfo lon, lat;
    for (std::size_t d = 0; d < var.dimSizes.size(); ++d) {
        if (var.dimSizes[d] < 2) continue;
        AxisInfo a = file.axis(var, d);
        const AxisRole role = classifyAxis(a).role;
        if (role == AxisRole::Longitude) lonDim = int(d), lon = std::move(a);
        else if (role == AxisRole::Latitude) latDim = int(d), lat = std::move(a);
    }
    if (lonDim < 0 || latDim < 0)
        throw InputError(path + ": the relief " + var.signature() + " is not over longitude and latitude axes");
    const EvenAxis u = evenAxis(path, lon), v = evenAxis(path, lat);
    ReliefRaster r;
    r.nx = int(lon.values.size());
    r.ny = int(lat.values.size());
    r.u0 = u.first, r.du = u.step, r.v0 = v.first, r.dv = v.step;
    r.source = path;
    checkBudget(path, std::uint64_t(r.nx) * std::uint64_t(r.ny), budget);
    std::vector<std::uint64_t> start(var.dimSizes.size(), 0);
    const std::vector<double> raw = file.read(var, start, var.dimSizes);
    const SampleRules rules = file.rules(var);
    double scale = metresPer(path, var.shortName, var.units);
    const std::string positive = lower(trim(file.attributeText(var, "positive")));
    const std::string what = lower(var.standardName + " " + var.shortName);
    if (positive == "down" || (positive != "up" && what.find("depth") != std::string::npos)) {
        scale = -scale;
        log::info(path + ": " + var.shortName + " holds depths (positive down): the relief is their negation");
    }
    // C order over the variable's dimensions: the stride of each.
    std::vector<std::size_t> stride(var.dimSizes.size(), 1);
    for (std::size_t d = var.dimSizes.size() - 1; d > 0; --d) stride[d - 1] = stride[d] * var.dimSizes[d];
    r.heights.assign(std::size_t(r.nx) * std::size_t(r.ny), kMissing);
    for (int j = 0; j < r.ny; ++j)
        for (int i = 0; i < r.nx; ++i) {
            const std::size_t si = std::size_t(u.reversed ? r.nx - 1 - i : i), sj = std::size_t(v.reversed ? r.ny - 1 - j : j);
            const double x = raw[si * stride[std::size_t(lonDim)] + sj * stride[std::size_t(latDim)]];
            if (rules.isValid(x)) r.heights[std::size_t(i) + std::size_t(r.nx) * std::size_t(j)] = float((x * rules.scale + rules.offset) * scale);
        }
    return r;
}

ReliefRaster readGdalRelief(const std::string& path, std::uint64_t budget) {
    registerGdal();
    GdalMessages messages;
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!ds) throw FormatNotSupported(path + ": neither NetCDF nor a raster GDAL opens: " + GdalMessages::last());
    if (ds->GetRasterCount() < 1) throw FileError(path + ": the raster has no band");
    double gt[6];
    if (ds->GetGeoTransform(gt) != CE_None) throw InputError(path + ": the raster has no georeferencing (geotransform)");
    const OGRSpatialReference* srs = ds->GetSpatialRef();
    if (!srs || !srs->IsGeographic())
        throw InputError(path + ": a relief raster must be in longitude and latitude (a geographic CRS); reproject it first "
                                "(gdalwarp -t_srs EPSG:4326)");
    if (gt[2] != 0.0 || gt[4] != 0.0 || !(gt[1] > 0.0) || !(gt[5] < 0.0))
        throw InputError(path + ": a relief raster must be north-up without rotation");
    ReliefRaster r;
    r.nx = ds->GetRasterXSize();
    r.ny = ds->GetRasterYSize();
    checkBudget(path, std::uint64_t(r.nx) * std::uint64_t(r.ny), budget);
    // Pixel centres; rows stored north first, the raster's rows south first.
    r.du = gt[1];
    r.dv = -gt[5];
    r.u0 = gt[0] + 0.5 * gt[1];
    r.v0 = gt[3] + (r.ny - 0.5) * gt[5];
    r.source = path;
    GDALRasterBand* band = ds->GetRasterBand(1);
    std::vector<double> z(std::size_t(r.nx) * std::size_t(r.ny));
    if (band->RasterIO(GF_Read, 0, 0, r.nx, r.ny, z.data(), r.nx, r.ny, GDT_Float64, 0, 0) != CE_None)
        throw FileError(path + ": cannot read its heights: " + GdalMessages::last());
    int hasNoData = 0;
    const double noData = band->GetNoDataValue(&hasNoData);
    r.heights.assign(z.size(), kMissing);
    for (int j = 0; j < r.ny; ++j)
        for (int i = 0; i < r.nx; ++i) {
            const double h = z[std::size_t(i) + std::size_t(r.nx) * std::size_t(r.ny - 1 - j)];
            if (std::isfinite(h) && !(hasNoData && h == noData)) r.heights[std::size_t(i) + std::size_t(r.nx) * std::size_t(j)] = float(h);
        }
    return r;
}

}  // namespace

ReliefRaster readRelief(const std::string& path, std::uint64_t memoryBudget) {
    requireReadableFile(path);
    ReliefRaster r = sniffFormat(path).kind == FileKind::NetCdf ? readNetcdfRelief(path, memoryBudget) : readGdalRelief(path, memoryBudget);
    if (std::none_of(r.heights.begin(), r.heights.end(), [](float h) { return std::isfinite(h); }))
        throw EmptyResultError(path + ": the relief has no valid height");
    return r;
}

}  // namespace octrace::io
