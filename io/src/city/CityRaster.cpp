#include "city/CityRaster.h"

#include "city/CityJson.h"
#include "input/GdalSupport.h"
#include "input/InputFile.h"
#include "octrace/octree/Octree.h"
#include "octrace/util/Error.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

namespace octrace::io::detail {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

GDALDatasetUniquePtr openRaster(const std::string& path) {
    requireReadableFile(path);
    registerGdal();
    GdalMessages messages;
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!ds) throw FormatNotSupported(path + ": GDAL cannot open it as a raster: " + GdalMessages::last());
    if (ds->GetRasterCount() < 1) throw FileError(path + ": the raster has no band");
    return ds;
}

/// The raster's pixel -> CRS transform for a read of bufW x bufH pixels over the whole raster.
void scaledTransform(GDALDataset& ds, const std::string& path, int bufW, int bufH, double gt[6]) {
    if (ds.GetGeoTransform(gt) != CE_None) throw FileError(path + ": the raster has no georeferencing (geotransform)");
    const double sx = double(ds.GetRasterXSize()) / bufW, sy = double(ds.GetRasterYSize()) / bufH;
    gt[1] *= sx;
    gt[2] *= sy;
    gt[4] *= sx;
    gt[5] *= sy;
}

std::string crsOf(GDALDataset& ds) {
    const OGRSpatialReference* srs = ds.GetSpatialRef();
    if (!srs) return {};
    char* wkt = nullptr;
    srs->exportToWkt(&wkt);
    std::string s = wkt ? wkt : "";
    CPLFree(wkt);
    return s;
}

struct Grid {
    int w = 0, h = 0;
    double gt[6] = {};
    std::vector<double> z;
    std::string crs;
};

Grid readElevations(const std::string& path, int maxSamples) {
    GDALDatasetUniquePtr ds = openRaster(path);
    GdalMessages messages;
    Grid g;
    g.w = std::min(ds->GetRasterXSize(), std::max(2, maxSamples));
    g.h = std::min(ds->GetRasterYSize(), std::max(2, maxSamples));
    scaledTransform(*ds, path, g.w, g.h, g.gt);
    g.crs = crsOf(*ds);
    GDALRasterBand* band = ds->GetRasterBand(1);
    g.z.resize(std::size_t(g.w) * std::size_t(g.h));
    GDALRasterIOExtraArg extra;
    INIT_RASTERIO_EXTRA_ARG(extra);
    extra.eResampleAlg = GRIORA_Average;
    if (band->RasterIO(GF_Read, 0, 0, ds->GetRasterXSize(), ds->GetRasterYSize(), g.z.data(), g.w, g.h, GDT_Float64, 0, 0,
                       &extra) != CE_None)
        throw FileError(path + ": cannot read its elevations: " + GdalMessages::last());
    int hasNoData = 0;
    const double noData = band->GetNoDataValue(&hasNoData);
    std::size_t valid = 0;
    for (double& v : g.z) {
        if ((hasNoData && v == noData) || !std::isfinite(v)) v = kNaN;
        else ++valid;
    }
    if (valid == 0) throw FileError(path + ": every elevation is nodata");
    return g;
}

/// World position of pixel centre (i, j).
dvec2 pixelCentre(const double gt[6], double i, double j) {
    return dvec2(gt[0] + (i + 0.5) * gt[1] + (j + 0.5) * gt[2], gt[3] + (i + 0.5) * gt[4] + (j + 0.5) * gt[5]);
}

OGRSpatialReference srsFrom(const std::string& text, const std::string& what) {
    OGRSpatialReference srs;
    if (srs.SetFromUserInput(text.c_str()) != OGRERR_NONE)
        throw InputError(what + ": unknown coordinate reference system '" + text.substr(0, 80) + "'");
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return srs;
}

}  // namespace

bool isRasterExtension(const std::string& path) {
    const std::string ext = lower(std::filesystem::path(path).extension().string());
    for (const char* e : {".tif", ".tiff", ".dem", ".asc", ".img", ".hgt", ".bil", ".vrt"})
        if (ext == e) return true;
    return false;
}

void addDemTerrain(CityModel& model, const std::string& path, int maxSamples) {
    const Grid g = readElevations(path, maxSamples);
    if (g.crs.empty()) model.notes.push_back(path + ": the DEM has no CRS; its coordinates are taken as they are");
    else if (model.crs.empty()) model.crs = g.crs;
    else if (!srsFrom(model.crs, path).IsSame(&static_cast<const OGRSpatialReference&>(srsFrom(g.crs, path))))
        throw InputError(path + ": the DEM's CRS differs from the scene's (reproject one of them first)");
    CityObject ground;
    ground.id = std::filesystem::path(path).filename().string();
    ground.type = "TINRelief";
    ground.role = CityRole::Terrain;
    ground.colour = packColour(cityTypeColour("TINRelief"));
    model.objects.push_back(ground);
    const std::uint32_t object = std::uint32_t(model.objects.size() - 1);
    // One vertex per pixel centre (NaN ones included, never used), two triangles per quad.
    const std::uint32_t first = std::uint32_t(model.vertices.size());
    for (int j = 0; j < g.h; ++j)
        for (int i = 0; i < g.w; ++i) model.vertices.push_back(dvec3(pixelCentre(g.gt, i, j), g.z[std::size_t(j) * g.w + i]));
    auto valid = [&](int i, int j) { return !std::isnan(g.z[std::size_t(j) * g.w + i]); };
    auto id = [&](int i, int j) { return first + std::uint32_t(j * g.w + i); };
    std::size_t skipped = 0;
    for (int j = 0; j + 1 < g.h; ++j)
        for (int i = 0; i + 1 < g.w; ++i) {
            if (!valid(i, j) || !valid(i + 1, j) || !valid(i, j + 1) || !valid(i + 1, j + 1)) {
                ++skipped;
                continue;
            }
            model.triangles.push_back({{id(i, j), id(i + 1, j), id(i + 1, j + 1)}, object});
            model.triangles.push_back({{id(i, j), id(i + 1, j + 1), id(i, j + 1)}, object});
        }
    if (skipped) model.notes.push_back(path + ": " + std::to_string(skipped) + " DEM cells with a nodata corner left out");
}

DemSampler::DemSampler(const std::string& path, int maxSamples) {
    Grid g = readElevations(path, maxSamples);
    crs_ = std::move(g.crs);
    width_ = g.w;
    height_ = g.h;
    std::copy(g.gt, g.gt + 6, gt_);
    if (!GDALInvGeoTransform(gt_, inv_)) throw FileError(path + ": its geotransform cannot be inverted");
    z_ = std::move(g.z);
}

double DemSampler::at(double x, double y) const {
    // Continuous pixel coordinates; pixel centres at +0.5.
    const double fi = inv_[0] + x * inv_[1] + y * inv_[2] - 0.5, fj = inv_[3] + x * inv_[4] + y * inv_[5] - 0.5;
    if (!(fi >= 0.0 && fj >= 0.0 && fi <= width_ - 1 && fj <= height_ - 1)) return kNaN;
    const int i = std::min(int(fi), width_ - 2 < 0 ? 0 : width_ - 2), j = std::min(int(fj), height_ - 2 < 0 ? 0 : height_ - 2);
    const int i1 = std::min(i + 1, width_ - 1), j1 = std::min(j + 1, height_ - 1);
    const double ti = fi - i, tj = fj - j;
    auto z = [&](int a, int b) { return z_[std::size_t(b) * width_ + a]; };
    return (z(i, j) * (1 - ti) + z(i1, j) * ti) * (1 - tj) + (z(i, j1) * (1 - ti) + z(i1, j1) * ti) * tj;
}

CityTexture readTexture(const std::string& path, const std::string& crs, const Box3& bounds, int maxPixels) {
    GDALDatasetUniquePtr ds = openRaster(path);
    GdalMessages messages;
    const std::string srcCrs = crsOf(*ds);
    if (srcCrs.empty()) throw InputError(path + ": the texture raster has no CRS, so it cannot be placed on the terrain");
    // The source, read whole at most 4096 pixels per edge.
    const int sw = std::min(ds->GetRasterXSize(), 4096), sh = std::min(ds->GetRasterYSize(), 4096);
    double gt[6];
    scaledTransform(*ds, path, sw, sh, gt);
    double inv[6];
    if (!GDALInvGeoTransform(gt, inv)) throw FileError(path + ": its geotransform cannot be inverted");
    const int bands = ds->GetRasterCount();
    std::vector<std::uint8_t> px(std::size_t(sw) * sh * 4, 255);
    GDALColorTable* table = bands == 1 ? ds->GetRasterBand(1)->GetColorTable() : nullptr;
    const int use = bands >= 4 ? 4 : (bands >= 3 ? 3 : 1);
    for (int b = 0; b < use; ++b) {
        if (ds->GetRasterBand(b + 1)->RasterIO(GF_Read, 0, 0, ds->GetRasterXSize(), ds->GetRasterYSize(), px.data() + b, sw, sh,
                                              GDT_Byte, 4, 4 * sw) != CE_None)
            throw FileError(path + ": cannot read band " + std::to_string(b + 1) + ": " + GdalMessages::last());
    }
    int hasNoData = 0;
    const double noData = ds->GetRasterBand(1)->GetNoDataValue(&hasNoData);
    std::vector<std::uint32_t> colour(std::size_t(sw) * sh);
    for (std::size_t k = 0; k < colour.size(); ++k) {
        std::uint8_t* p = &px[4 * k];
        if (use == 1) {
            if (table) {
                const GDALColorEntry* e = table->GetColorEntry(p[0]);
                p[1] = e ? std::uint8_t(e->c2) : 0;
                p[2] = e ? std::uint8_t(e->c3) : 0;
                p[3] = e ? std::uint8_t(e->c4) : 0;
                p[0] = e ? std::uint8_t(e->c1) : 0;
            } else {
                p[1] = p[2] = p[0];
            }
        }
        const bool none = hasNoData && double(px[4 * k]) == noData && use != 4 && !table;
        colour[k] = std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(none ? 0 : p[3]) << 24;
    }
    // The target grid over the bounds, square pixels.
    CityTexture t;
    const dvec3 ext = bounds.size();
    const double pixel = std::max(ext.x, ext.y) / double(std::max(1, maxPixels));
    if (!(pixel > 0.0) || !std::isfinite(pixel)) return t;
    t.width = std::max(1, int(std::ceil(ext.x / pixel)));
    t.height = std::max(1, int(std::ceil(ext.y / pixel)));
    t.pixel = dvec2(pixel);
    t.origin = dvec2(bounds.lo.x, bounds.lo.y + t.height * pixel);
    const OGRSpatialReference target = srsFrom(crs, "the scene"), source = srsFrom(srcCrs, path);
    std::unique_ptr<OGRCoordinateTransformation> toSource(OGRCreateCoordinateTransformation(&target, &source));
    if (!toSource) throw InputError(path + ": no transformation from the scene's CRS to the texture's");
    const std::size_t n = std::size_t(t.width) * t.height;
    std::vector<double> xs(n), ys(n);
    std::vector<int> ok(n, 0);
    for (int j = 0; j < t.height; ++j)
        for (int i = 0; i < t.width; ++i) {
            xs[std::size_t(j) * t.width + i] = t.origin.x + (i + 0.5) * pixel;
            ys[std::size_t(j) * t.width + i] = t.origin.y - (j + 0.5) * pixel;
        }
    toSource->Transform(n, xs.data(), ys.data(), nullptr, ok.data());
    t.rgba.assign(n, 0);
    std::size_t inside = 0;
    for (std::size_t k = 0; k < n; ++k) {
        if (!ok[k]) continue;
        const double fi = inv[0] + xs[k] * inv[1] + ys[k] * inv[2], fj = inv[3] + xs[k] * inv[4] + ys[k] * inv[5];
        if (!(fi >= 0.0 && fj >= 0.0 && fi < sw && fj < sh)) continue;
        t.rgba[k] = colour[std::size_t(int(fj)) * sw + std::size_t(int(fi))];
        inside += (t.rgba[k] >> 24) != 0;
    }
    if (inside == 0) throw InputError(path + ": the texture does not cover the scene (no pixel of it falls on the terrain's extent)");
    return t;
}

}  // namespace octrace::io::detail
