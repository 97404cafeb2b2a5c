#include "city/CityJson.h"

#include "octrace/octree/Octree.h"
#include "octrace/util/Error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <unordered_map>

namespace octrace::io::detail {
namespace {

using nlohmann::json;

std::string lodText(const json& g) {
    if (!g.contains("lod")) return "";
    const json& l = g["lod"];
    if (l.is_string()) return l.get<std::string>();
    if (l.is_number_integer()) return std::to_string(l.get<long long>());
    if (l.is_number()) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%g", l.get<double>());
        return buf;
    }
    return "";
}

struct Parser {
    const std::string& name;
    CityModel model;
    std::vector<dvec3> points;  // the file's vertices, transformed
    CityNotes notes;

    [[noreturn]] void broken(const std::string& what) const { throw FileError(name + ": " + what); }

    dvec3 vertex(const json& index, const std::string& object) const {
        if (!index.is_number_integer()) broken("object '" + object + "': a vertex index is not an integer");
        const long long i = index.get<long long>();
        if (i < 0 || std::size_t(i) >= points.size())
            broken("object '" + object + "': vertex index " + std::to_string(i) + " out of range (the file has " +
                   std::to_string(points.size()) + " vertices)");
        return points[std::size_t(i)];
    }

    /// One surface: [outer ring, holes...], each ring a list of vertex indices.
    void surface(const json& s, std::uint32_t object, const std::string& id) {
        if (!s.is_array() || s.empty()) broken("object '" + id + "': a surface is not an array of rings");
        std::vector<std::vector<dvec3>> rings;
        for (const json& r : s) {
            if (!r.is_array()) broken("object '" + id + "': a ring is not an array of vertex indices");
            std::vector<dvec3> ring;
            for (const json& i : r) ring.push_back(vertex(i, id));
            rings.push_back(std::move(ring));
        }
        if (!model.addPolygon(rings, object)) notes.add("polygons without area or self-intersecting, left out", id);
    }

    void surfaces(const json& list, std::uint32_t object, const std::string& id) {
        if (!list.is_array()) broken("object '" + id + "': boundaries are not an array");
        for (const json& s : list) surface(s, object, id);
    }

    /// A solid: [outer shell, inner shells...]; reports a shell that is not closed.
    void solid(const json& shells, std::uint32_t object, const std::string& id) {
        if (!shells.is_array()) broken("object '" + id + "': a solid is not an array of shells");
        for (const json& shell : shells) {
            const std::size_t first = model.triangles.size();
            surfaces(shell, object, id);
            if (model.triangles.size() > first && !isClosedSurface(model, first, model.triangles.size()))
                notes.add("solids with an open shell, voxelized as their surfaces", id);
        }
    }

    void geometry(const json& g, std::uint32_t object, const std::string& id) {
        const std::string type = g.value("type", "");
        if (!g.contains("boundaries")) {
            if (type == "GeometryInstance") notes.add("geometry instances (templates), left out", id);
            return;
        }
        const json& b = g["boundaries"];
        if (type == "MultiSurface" || type == "CompositeSurface") surfaces(b, object, id);
        else if (type == "Solid") solid(b, object, id);
        else if (type == "MultiSolid" || type == "CompositeSolid") {
            if (!b.is_array()) broken("object '" + id + "': boundaries are not an array");
            for (const json& s : b) solid(s, object, id);
        } else if (type == "GeometryInstance") notes.add("geometry instances (templates), left out", id);
        else notes.add("geometries of type " + (type.empty() ? std::string("(none)") : type) + " (points, lines), left out", id);
    }
};

}  // namespace

std::string crsFromReference(const std::string& ref) {
    const auto epsg = ref.find("EPSG");
    if (epsg == std::string::npos) return ref;
    const auto digits = ref.find_last_not_of("0123456789");
    if (digits == std::string::npos || digits + 1 >= ref.size()) return ref;
    return "EPSG:" + ref.substr(digits + 1);
}

bool lodMatches(const std::string& lod, const std::string& wanted) {
    return lod == wanted || (lod.rfind(wanted, 0) == 0 && lod.size() > wanted.size() && lod[wanted.size()] == '.');
}

void requireSurfaces(const CityModel& model, const std::string& name, const std::string& lod, std::size_t chosen) {
    if (!model.triangles.empty()) return;
    std::string why = chosen == 0 && !lod.empty() ? " (no object has a geometry of LoD " + lod + ")" : "";
    if (why.empty() && !model.notes.empty()) why = " (" + model.notes.front().substr(name.size() + 2) + ")";
    throw EmptyResultError(name + ": no surface with area to voxelize" + why);
}

vec3 cityTypeColour(const std::string& type) {
    static const std::unordered_map<std::string, vec3> colours = {
        {"Building", {0.88f, 0.52f, 0.40f}},        {"BuildingPart", {0.88f, 0.52f, 0.40f}},
        {"BuildingInstallation", {0.80f, 0.50f, 0.40f}}, {"Bridge", {0.62f, 0.58f, 0.55f}},
        {"BridgePart", {0.62f, 0.58f, 0.55f}},      {"Tunnel", {0.5f, 0.5f, 0.5f}},
        {"TINRelief", {0.62f, 0.70f, 0.48f}},       {"Road", {0.55f, 0.55f, 0.56f}},
        {"Railway", {0.50f, 0.45f, 0.42f}},         {"TransportSquare", {0.66f, 0.65f, 0.63f}},
        {"WaterBody", {0.36f, 0.56f, 0.80f}},       {"PlantCover", {0.42f, 0.64f, 0.34f}},
        {"SolitaryVegetationObject", {0.30f, 0.55f, 0.25f}}, {"LandUse", {0.82f, 0.80f, 0.70f}},
        {"GenericCityObject", {0.64f, 0.62f, 0.60f}}, {"CityFurniture", {0.45f, 0.45f, 0.50f}},
        {"RoofSurface", {0.45f, 0.43f, 0.46f}},
    };
    auto it = colours.find(type);
    return it != colours.end() ? it->second : vec3(0.7f, 0.7f, 0.7f);
}

CityRole cityTypeRole(const std::string& type) {
    static const char* terrain[] = {"TINRelief", "Road", "Railway", "TransportSquare", "WaterBody", "PlantCover",
                                    "LandUse", "GenericCityObject", "Waterway", "TrafficArea", "AuxiliaryTrafficArea"};
    for (const char* t : terrain)
        if (type == t) return CityRole::Terrain;
    return CityRole::Solid;
}

std::uint32_t cityObjectColour(const std::string& type, const std::string& id) {
    vec3 c = cityTypeColour(type);
    if (cityTypeRole(type) == CityRole::Solid) {
        // FNV-1a of the id: a stable shade in [-6%, +6%].
        std::uint32_t h = 2166136261u;
        for (unsigned char ch : id) h = (h ^ ch) * 16777619u;
        c *= 0.94f + 0.12f * float(h % 1000u) / 999.0f;
    }
    return packColour(c);
}

void CityNotes::add(const std::string& kind, const std::string& object) {
    auto& k = kinds_[kind];
    if (k.second.empty() || (k.second.back() != object && k.second.size() < 3)) k.second.push_back(object);
    ++k.first;
}

void CityNotes::appendTo(std::vector<std::string>& notes, const std::string& name) const {
    for (const auto& [kind, k] : kinds_) {
        std::string s = name + ": " + std::to_string(k.first) + " " + kind + " (";
        for (std::size_t i = 0; i < k.second.size(); ++i) s += (i ? ", " : "") + k.second[i];
        s += k.first > k.second.size() ? ", ...)" : ")";
        notes.push_back(s);
    }
}

bool isClosedSurface(const CityModel& model, std::size_t first, std::size_t end) {
    // Edges by position (the readers duplicate shared vertices per polygon).
    std::map<std::pair<std::array<double, 3>, std::array<double, 3>>, int> edges;
    auto key = [&](std::uint32_t i) { const dvec3& p = model.vertices[i]; return std::array<double, 3>{p.x, p.y, p.z}; };
    for (std::size_t t = first; t < end; ++t)
        for (int k = 0; k < 3; ++k) {
            auto a = key(model.triangles[t].v[std::size_t(k)]), b = key(model.triangles[t].v[std::size_t((k + 1) % 3)]);
            if (b < a) std::swap(a, b);
            ++edges[{a, b}];
        }
    return std::all_of(edges.begin(), edges.end(), [](const auto& e) { return e.second == 2; });
}

CityModel parseCityJson(const std::string& text, const std::string& name, const std::string& lod) {
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) {
        // Not only syntax errors: a number beyond double's range is out_of_range (406).
        throw FileError(name + ": not valid JSON (" + std::string(e.what()) + ")");
    }
    if (!doc.is_object() || doc.value("type", json()).is_null() || !doc["type"].is_string() || doc["type"] != "CityJSON")
        throw FormatNotSupported(name + ": not CityJSON (no \"type\": \"CityJSON\")");
    Parser p{name, {}, {}, {}};
    p.model.source = name;
    p.model.format = "CityJSON";
    dvec3 scale(1.0), translate(0.0);
    if (doc.contains("transform")) {
        const json& t = doc["transform"];
        auto vec = [&](const char* key, dvec3& out) {
            if (!t.contains(key)) return;
            const json& a = t[key];
            if (!a.is_array() || a.size() != 3 || !a[0].is_number() || !a[1].is_number() || !a[2].is_number())
                p.broken(std::string("transform.") + key + " is not an array of 3 numbers");
            out = dvec3(a[0].get<double>(), a[1].get<double>(), a[2].get<double>());
        };
        vec("scale", scale);
        vec("translate", translate);
    }
    if (!doc.contains("vertices") || !doc["vertices"].is_array()) p.broken("no \"vertices\" array");
    for (const json& v : doc["vertices"]) {
        if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
            p.broken("vertex " + std::to_string(p.points.size()) + " is not an array of 3 numbers");
        const dvec3 q = dvec3(v[0].get<double>(), v[1].get<double>(), v[2].get<double>()) * scale + translate;
        if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z)) p.broken("vertex " + std::to_string(p.points.size()) + " is not finite");
        p.points.push_back(q);
    }
    if (doc.contains("metadata") && doc["metadata"].is_object()) {
        const json& m = doc["metadata"];
        if (m.contains("referenceSystem") && m["referenceSystem"].is_string())
            p.model.crs = crsFromReference(m["referenceSystem"].get<std::string>());
    }
    if (!doc.contains("CityObjects") || !doc["CityObjects"].is_object()) p.broken("no \"CityObjects\" object");
    std::size_t chosen = 0;
    for (const auto& [id, o] : doc["CityObjects"].items()) {
        if (!o.is_object()) p.broken("object '" + id + "' is not a JSON object");
        const std::string type = o.value("type", json()).is_string() ? o["type"].get<std::string>() : std::string();
        if (!o.contains("geometry") || !o["geometry"].is_array() || o["geometry"].empty()) continue;  // e.g. a parent
        // The chosen LoD: the wanted one, or the object's highest.
        const json* pick = nullptr;
        std::string best;
        for (const json& g : o["geometry"]) {
            if (!g.is_object()) p.broken("object '" + id + "': a geometry is not a JSON object");
            const std::string l = lodText(g);
            if (lod.empty() ? (pick == nullptr || l > best) : lodMatches(l, lod) && (pick == nullptr || l > best)) {
                pick = &g;
                best = l;
            }
        }
        if (!pick) {
            p.notes.add("objects without a geometry of LoD " + lod + ", left out", id);
            continue;
        }
        CityObject obj;
        obj.id = id;
        obj.type = type;
        obj.role = cityTypeRole(type);
        obj.colour = cityObjectColour(type, id);
        p.model.objects.push_back(obj);
        const std::uint32_t index = std::uint32_t(p.model.objects.size() - 1);
        p.geometry(*pick, index, id);
        ++chosen;
    }
    p.notes.appendTo(p.model.notes, name);
    requireSurfaces(p.model, name, lod, chosen);
    return std::move(p.model);
}

}  // namespace octrace::io::detail
