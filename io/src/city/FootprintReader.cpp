#include "city/FootprintReader.h"

#include "city/CityJson.h"
#include "city/CityRaster.h"
#include "input/GdalSupport.h"
#include "input/InputFile.h"
#include "octrace/util/Error.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>

namespace octrace::io::detail {
namespace {

std::optional<double> number(OGRFeature& f, int field) {
    if (field < 0 || !f.IsFieldSetAndNotNull(field)) return std::nullopt;
    const OGRFieldType t = f.GetFieldDefnRef(field)->GetType();
    if (t != OFTReal && t != OFTInteger && t != OFTInteger64 && t != OFTString) return std::nullopt;
    const char* text = f.GetFieldAsString(field);
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    if (end == text || !std::isfinite(v)) return std::nullopt;
    return v;
}

std::vector<std::vector<dvec2>> rings(const OGRPolygon& p) {
    std::vector<std::vector<dvec2>> out;
    auto ring = [&](const OGRLinearRing* r) {
        std::vector<dvec2> pts;
        if (r)
            for (int i = 0; i < r->getNumPoints(); ++i) pts.push_back(dvec2(r->getX(i), r->getY(i)));
        out.push_back(std::move(pts));
    };
    ring(p.getExteriorRing());
    for (int i = 0; i < p.getNumInteriorRings(); ++i) ring(p.getInteriorRing(i));
    return out;
}

}  // namespace

bool isFootprintExtension(const std::string& path) {
    const std::string ext = lower(std::filesystem::path(path).extension().string());
    return ext == ".geojson" || ext == ".shp" || ext == ".gpkg" || ext == ".fgb";
}

void addFootprints(CityModel& model, const std::string& path, const CityRequest& req) {
    registerGdal();
    GdalMessages messages;
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!ds) throw FormatNotSupported(path + ": OGR cannot open it as vector data: " + GdalMessages::last());
    if (ds->GetLayerCount() < 1) throw FileError(path + ": no layer");
    std::optional<DemSampler> dem;
    if (req.baseAttr.empty() && !req.dem.empty()) dem.emplace(req.dem, req.maxSamples);
    CityNotes notes;
    std::size_t polygons = 0;
    bool baseZeroSaid = false;
    for (int l = 0; l < ds->GetLayerCount(); ++l) {
        OGRLayer* layer = ds->GetLayer(l);
        OGRFeatureDefn* defn = layer->GetLayerDefn();
        // The height attribute.
        int heightField = -1;
        std::string heightName = req.heightAttr;
        if (heightName.empty()) {
            for (const char* n : {"height", "HEIGHT", "hauteur", "HAUTEUR", "measuredHeight", "building:height"})
                if (defn->GetFieldIndex(n) >= 0) {
                    heightName = n;
                    break;
                }
        }
        heightField = heightName.empty() ? -1 : defn->GetFieldIndex(heightName.c_str());
        if (heightField < 0) {
            std::string fields;
            for (int i = 0; i < defn->GetFieldCount(); ++i) fields += std::string(i ? ", " : "") + defn->GetFieldDefn(i)->GetNameRef();
            throw InputError(path + ": " +
                             (req.heightAttr.empty() ? std::string("no height attribute found; give `height_attr`")
                                                     : "no attribute '" + req.heightAttr + "' (`height_attr`)") +
                             " (its attributes: " + (fields.empty() ? std::string("none") : fields) + ")");
        }
        const int baseField = req.baseAttr.empty() ? -1 : defn->GetFieldIndex(req.baseAttr.c_str());
        if (!req.baseAttr.empty() && baseField < 0) throw InputError(path + ": no attribute '" + req.baseAttr + "' (`base_attr`)");
        const int idField = defn->GetFieldIndex("ID") >= 0 ? defn->GetFieldIndex("ID") : defn->GetFieldIndex("id");
        // The layer's CRS, and the way to the DEM's.
        const OGRSpatialReference* srs = layer->GetSpatialRef();
        if (srs) {
            char* wkt = nullptr;
            srs->exportToWkt(&wkt);
            if (model.crs.empty()) model.crs = wkt ? wkt : "";
            CPLFree(wkt);
        }
        std::unique_ptr<OGRCoordinateTransformation> toDem;
        if (dem && srs && !dem->crs().empty()) {
            OGRSpatialReference demSrs;
            demSrs.SetFromUserInput(dem->crs().c_str());
            demSrs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
            OGRSpatialReference layerSrs(*srs);
            layerSrs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
            if (!layerSrs.IsSame(&demSrs)) toDem.reset(OGRCreateCoordinateTransformation(&layerSrs, &demSrs));
        }
        layer->ResetReading();
        for (OGRFeatureUniquePtr f(layer->GetNextFeature()); f; f.reset(layer->GetNextFeature())) {
            const std::string id = idField >= 0 ? f->GetFieldAsString(idField) : "feature " + std::to_string(f->GetFID());
            const OGRGeometry* g = f->GetGeometryRef();
            if (!g) {
                notes.add("features without geometry, left out", id);
                continue;
            }
            std::vector<const OGRPolygon*> parts;
            const OGRwkbGeometryType type = wkbFlatten(g->getGeometryType());
            if (type == wkbPolygon) parts.push_back(g->toPolygon());
            else if (type == wkbMultiPolygon)
                for (const OGRPolygon* p : *g->toMultiPolygon()) parts.push_back(p);
            else {
                notes.add("features that are not polygons, left out", id);
                continue;
            }
            const std::optional<double> height = number(*f, heightField);
            if (!height || !(*height > 0.0)) {
                notes.add("footprints without a height (" + heightName + " missing or not positive), left out", id);
                continue;
            }
            double base = 0.0;
            if (baseField >= 0) {
                const std::optional<double> b = number(*f, baseField);
                if (!b) {
                    notes.add("footprints without a base (" + req.baseAttr + " missing), left out", id);
                    continue;
                }
                base = *b;
            } else if (dem) {
                double lowest = std::numeric_limits<double>::infinity();
                for (const OGRPolygon* p : parts)
                    for (const auto& r : rings(*p))
                        for (dvec2 q : r) {
                            if (toDem && !toDem->Transform(1, &q.x, &q.y)) continue;
                            lowest = std::min(lowest, dem->at(q.x, q.y));  // NaN outside: min keeps the other
                        }
                if (!std::isfinite(lowest)) {
                    notes.add("footprints outside the DEM (no ground height), left out", id);
                    continue;
                }
                base = lowest;
            } else if (!baseZeroSaid) {
                model.notes.push_back(path + ": no `base_attr` or `dem`: the footprints stand on z = 0");
                baseZeroSaid = true;
            }
            CityObject o;
            o.id = id;
            o.type = "Building";
            o.role = CityRole::Solid;
            o.colour = cityObjectColour("Building", id);
            model.objects.push_back(o);
            const std::uint32_t index = std::uint32_t(model.objects.size() - 1);
            bool any = false;
            for (const OGRPolygon* p : parts) {
                if (model.addPrism(rings(*p), base, base + *height, index)) any = true;
                else notes.add("footprint polygons self-intersecting or without area, left out", id);
            }
            if (!any) model.objects.pop_back();
            polygons += any;
        }
    }
    notes.appendTo(model.notes, path);
    if (polygons == 0) {
        std::string why = model.notes.empty() ? std::string() : " (" + model.notes.back().substr(path.size() + 2) + ")";
        throw EmptyResultError(path + ": no usable building footprint" + why);
    }
}

}  // namespace octrace::io::detail
