// Coastlines from any vector file OGR reads: line strings and polygon rings, in WGS84
// longitude/latitude (reprojected when the layer says another CRS).
#include "octrace/io/Coastline.h"

#include "input/GdalSupport.h"

#include "octrace/util/Error.h"

#include <gdal_priv.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <filesystem>
#include <memory>

namespace octrace::io {
namespace {

using detail::GdalMessages;

/// The lines of a geometry: each line string and each polygon ring, through multi-geometries
/// and collections. Points are skipped.
void collectLines(const OGRGeometry* g, std::vector<std::vector<dvec2>>& out) {
    if (!g || g->IsEmpty()) return;
    const OGRwkbGeometryType type = wkbFlatten(g->getGeometryType());
    if (OGR_GT_IsSubClassOf(type, wkbCurve)) {
        std::unique_ptr<OGRLineString> ls(g->toCurve()->CurveToLine());
        std::vector<dvec2>& line = out.emplace_back();
        for (int i = 0; i < ls->getNumPoints(); ++i) line.push_back({ls->getX(i), ls->getY(i)});
    } else if (OGR_GT_IsSubClassOf(type, wkbCurvePolygon)) {
        for (const OGRCurve* ring : *g->toCurvePolygon()) collectLines(ring, out);
    } else if (OGR_GT_IsSubClassOf(type, wkbGeometryCollection)) {
        for (const OGRGeometry* part : *g->toGeometryCollection()) collectLines(part, out);
    }
}

}  // namespace

Coastlines readVectorCoastlines(const std::string& path, const LonLatBox& region) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw FileError(path + ": no such coastline file");
    detail::registerGdal();
    GdalMessages messages;
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!ds)
        throw FormatNotSupported(path + ": OGR cannot open it as vector data (a shapefile, GeoPackage, GeoJSON, ... of coastlines "
                                        "in longitude/latitude): " + GdalMessages::last());
    Coastlines out;
    out.source = path;
    OGRSpatialReference wgs84;
    wgs84.SetWellKnownGeogCS("WGS84");
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::size_t lines = 0;
    std::vector<std::vector<dvec2>> found;
    for (int l = 0; l < ds->GetLayerCount(); ++l) {
        OGRLayer* layer = ds->GetLayer(l);
        std::unique_ptr<OGRCoordinateTransformation> toLonLat;
        if (const OGRSpatialReference* srs = layer->GetSpatialRef()) {
            OGRSpatialReference layerSrs(*srs);
            layerSrs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
            if (!layerSrs.IsSame(&wgs84)) {
                toLonLat.reset(OGRCreateCoordinateTransformation(&layerSrs, &wgs84));
                if (!toLonLat)
                    throw FileError(path + ": layer " + layer->GetName() + ": cannot reproject its CRS to WGS84 longitude/latitude: " +
                                    GdalMessages::last());
            }
        }
        for (OGRFeatureUniquePtr f(layer->GetNextFeature()); f; f.reset(layer->GetNextFeature())) {
            found.clear();
            collectLines(f->GetGeometryRef(), found);
            for (std::vector<dvec2>& line : found) {
                if (line.size() < 2) continue;
                ++lines;
                if (toLonLat) {
                    std::vector<double> x(line.size()), y(line.size());
                    for (std::size_t i = 0; i < line.size(); ++i) x[i] = line[i].x, y[i] = line[i].y;
                    if (!toLonLat->Transform(int(line.size()), x.data(), y.data()))
                        throw FileError(path + ": layer " + layer->GetName() + ": a line does not reproject to WGS84: " + GdalMessages::last());
                    for (std::size_t i = 0; i < line.size(); ++i) line[i] = {x[i], y[i]};
                }
                for (const dvec2& p : line)
                    if (!std::isfinite(p.x) || !std::isfinite(p.y) || std::abs(p.y) > 90.0)
                        throw FileError(path + ": layer " + layer->GetName() + ": a point (" + std::to_string(p.x) + ", " +
                                        std::to_string(p.y) + ") is not a longitude/latitude");
                // Unwrapped: a step of more than 180° is taken the short way round.
                for (std::size_t i = 1; i < line.size(); ++i) line[i].x -= 360.0 * std::round((line[i].x - line[i - 1].x) / 360.0);
                addWrappedCopies(line, region, out.lines);
            }
        }
    }
    if (lines == 0) throw InputError(path + ": no line or polygon in any layer: coastlines are lines or polygons in longitude/latitude");
    return out;
}

}  // namespace octrace::io
