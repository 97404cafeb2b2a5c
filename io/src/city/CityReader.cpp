#include "octrace/io/CityReader.h"

#include "city/CityGml.h"
#include "city/CityJson.h"
#include "city/CityScene.h"
#include "city/CityRaster.h"
#include "city/FootprintReader.h"
#include "input/InputFile.h"
#include "octrace/util/Error.h"

#include <ogr_spatialref.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

namespace octrace::io {
namespace {

std::string extensionOf(const std::string& path) { return detail::lower(std::filesystem::path(path).extension().string()); }

std::string readAll(const std::string& path) {
    detail::requireReadableFile(path);
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    if (!in && !in.eof()) throw FileError(path + ": read error");
    if (s.str().empty()) throw FileError(path + ": file is empty (0 bytes)");
    return s.str();
}

/// A CRS from user text or a file's; throws InputError naming `what` when OSR does not know it.
OGRSpatialReference spatialReference(const std::string& text, const std::string& what) {
    OGRSpatialReference srs;
    if (srs.SetFromUserInput(text.c_str()) != OGRERR_NONE)
        throw InputError(what + ": unknown coordinate reference system '" + text + "'");
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return srs;
}

/// "EPSG:N" when the CRS has an EPSG code, else its name.
std::string crsName(const OGRSpatialReference& srs) {
    OGRSpatialReference copy(srs);
    copy.AutoIdentifyEPSG();
    const char* auth = copy.GetAuthorityName(nullptr);
    const char* code = copy.GetAuthorityCode(nullptr);
    if (auth && code) return std::string(auth) + ":" + code;
    const char* name = copy.GetName();
    return name ? name : "unnamed CRS";
}

/// The UTM zone (WGS 84) of a longitude, latitude.
std::string utmZone(double lon, double lat) {
    const int zone = std::clamp(int(std::floor((lon + 180.0) / 6.0)) + 1, 1, 60);
    return "EPSG:" + std::to_string((lat >= 0.0 ? 32600 : 32700) + zone);
}

/// Brings the model into the request's CRS (see CityRequest::crs).
void toProjectedCrs(CityModel& m, const std::string& requested, const std::string& path) {
    if (m.crs.empty()) {
        if (requested.empty()) {
            m.notes.push_back(path + ": no coordinate reference system given; coordinates taken as they are");
            return;
        }
        const OGRSpatialReference target = spatialReference(requested, "`crs`");
        m.crs = crsName(target);
        m.notes.push_back(path + ": no coordinate reference system given; taken to be in " + m.crs + " (`crs`)");
        return;
    }
    const OGRSpatialReference source = spatialReference(m.crs, path);
    std::string target = requested;
    if (target.empty()) {
        if (source.IsProjected() || source.IsLocal()) {
            m.crs = crsName(source);
            return;
        }
        // Geographic: the UTM zone of the centre.
        const Box3 b = m.bounds();
        OGRSpatialReference wgs84;
        wgs84.SetWellKnownGeogCS("WGS84");
        wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
        std::unique_ptr<OGRCoordinateTransformation> toWgs(OGRCreateCoordinateTransformation(&source, &wgs84));
        dvec3 c = b.centre();
        if (!toWgs || !toWgs->Transform(1, &c.x, &c.y, &c.z))
            throw InputError(path + ": cannot place its centre in longitude/latitude from " + crsName(source));
        target = utmZone(c.x, c.y);
        m.notes.push_back(path + ": " + crsName(source) + " is geographic; reprojected to " + target + " (UTM, metres; `crs` to choose)");
    }
    const OGRSpatialReference dest = spatialReference(target, "`crs`");
    if (!dest.IsProjected() && !dest.IsLocal())
        throw InputError("`crs` " + target + ": not a projected CRS (octrace needs metres-like units on all three axes)");
    if (source.IsSame(&dest)) {
        m.crs = crsName(dest);
        return;
    }
    std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&source, &dest));
    if (!t) throw InputError(path + ": no transformation from " + crsName(source) + " to " + crsName(dest));
    std::vector<double> x(m.vertices.size()), y(m.vertices.size()), z(m.vertices.size());
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
        x[i] = m.vertices[i].x;
        y[i] = m.vertices[i].y;
        z[i] = m.vertices[i].z;
    }
    std::vector<int> ok(m.vertices.size(), 0);
    t->Transform(m.vertices.size(), x.data(), y.data(), z.data(), ok.data());
    std::size_t failed = 0;
    for (std::size_t i = 0; i < m.vertices.size(); ++i) {
        if (!ok[i] || !std::isfinite(x[i]) || !std::isfinite(y[i])) ++failed;
        else m.vertices[i] = dvec3(x[i], y[i], z[i]);
    }
    if (failed == m.vertices.size() && failed > 0)
        throw InputError(path + ": no coordinate could be transformed from " + crsName(source) + " to " + crsName(dest) +
                         " (is the file's CRS right?)");
    if (failed) {
        // Triangles with a vertex that could not be placed are left out.
        std::vector<std::uint8_t> bad(m.vertices.size(), 0);
        for (std::size_t i = 0; i < m.vertices.size(); ++i) bad[i] = !ok[i] || !std::isfinite(x[i]) || !std::isfinite(y[i]);
        std::erase_if(m.triangles, [&](const CityTriangle& tr) { return bad[tr.v[0]] || bad[tr.v[1]] || bad[tr.v[2]]; });
        m.notes.push_back(path + ": " + std::to_string(failed) + " vertices could not be transformed to " + crsName(dest) + "; their triangles left out");
    }
    m.crs = crsName(dest);
}

}  // namespace

bool isCityInput(const std::string& path) {
    return extensionOf(path) == ".json" || detail::isRasterExtension(path) || detail::isFootprintExtension(path) ||
           detail::isCityGmlExtension(path);
}

CityModel readCityModel(const std::string& path, const CityRequest& req) {
    if (!req.crs.empty()) spatialReference(req.crs, "`crs`");  // a bad --crs before the long read
    CityModel m;
    m.source = path;
    std::string texture = req.texture;
    if (detail::isCitySceneFile(path)) {
        std::string sceneTexture;
        m = detail::readCityScene(path, readAll(path), req, sceneTexture);
        if (texture.empty()) texture = sceneTexture;  // --texture wins
    } else if (detail::isRasterExtension(path)) {
        m.format = "DEM raster (GDAL), terrain";
        detail::addDemTerrain(m, path, req.maxSamples);
    } else if (detail::isFootprintExtension(path)) {
        m.format = "building footprints (OGR)";
        detail::addFootprints(m, path, req);
    } else if (detail::isCityGmlExtension(path)) {
        m = detail::parseCityGml(readAll(path), path, req.lod);
    } else {
        const std::string text = readAll(path);
        try {
            m = detail::parseCityJson(text, path, req.lod);
        } catch (const FormatNotSupported&) {
            if (text.find("\"FeatureCollection\"") == std::string::npos) throw;
            m.format = "building footprints (OGR)";
            detail::addFootprints(m, path, req);  // GeoJSON named .json
        }
    }
    if (m.format != "building footprints (OGR)" && (!req.heightAttr.empty() || !req.baseAttr.empty()))
        throw InputError(path + ": `height_attr` and `base_attr` apply to building footprints, not to this " + m.format + " input");
    toProjectedCrs(m, req.crs, path);
    if (!req.dem.empty()) {
        CityModel dem;
        detail::addDemTerrain(dem, req.dem, req.maxSamples);
        toProjectedCrs(dem, m.crs, req.dem);
        m.append(dem);
    }
    if (m.triangles.empty()) throw EmptyResultError(path + ": no surface with area to voxelize");
    if (!texture.empty()) {
        if (m.crs.empty()) throw InputError(texture + ": the scene has no CRS to place the texture in (give `crs`)");
        Box3 terrain = m.bounds(CityRole::Terrain);
        if (!(terrain.hi.x >= terrain.lo.x)) throw InputError(texture + ": the scene has no terrain to drape the texture on");
        // A margin: voxel centres at the terrain's edge may lie half a voxel outside it.
        const double margin = 0.02 * std::max(terrain.size().x, terrain.size().y);
        terrain.lo -= dvec3(margin, margin, 0.0);
        terrain.hi += dvec3(margin, margin, 0.0);
        m.texture = detail::readTexture(texture, m.crs, terrain, req.maxSamples);
    }
    return m;
}

std::string describeCityInput(const std::string& path, const CityRequest& req) {
    const CityModel m = readCityModel(path, req);
    std::map<std::string, std::size_t> types;
    for (const auto& o : m.objects) ++types[o.type];
    const Box3 b = m.bounds();
    std::ostringstream s;
    s.precision(10);
    s << path << "\n  format: " << m.format << "\n  crs: " << (m.crs.empty() ? "(none)" : m.crs) << "\n  objects: " << m.objects.size()
      << " (" << m.objectCount(CityRole::Solid) << " solids, " << m.objectCount(CityRole::Terrain) << " terrain)\n";
    for (const auto& [type, n] : types) s << "    " << type << ": " << n << "\n";
    s << "  triangles: " << m.triangles.size() << "\n  world bounds: [" << b.lo.x << ", " << b.hi.x << "] x [" << b.lo.y
      << ", " << b.hi.y << "] x [" << b.lo.z << ", " << b.hi.z << "]\n";
    if (!m.texture.empty()) s << "  texture: " << (req.texture.empty() ? std::string("the scene's") : req.texture) << ", " << m.texture.width << " x " << m.texture.height << " pixels of " << m.texture.pixel.x << "\n";
    for (const auto& n : m.notes) s << "  note: " << n << "\n";
    return s.str();
}

}  // namespace octrace::io
