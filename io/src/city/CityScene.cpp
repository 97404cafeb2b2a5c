#include "city/CityScene.h"

#include "input/InputFile.h"
#include "octrace/io/CityReader.h"
#include "octrace/octree/Octree.h"
#include "octrace/util/Error.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace octrace::io::detail {
namespace {

using nlohmann::json;

std::string text(const json& v, const std::string& key, const std::string& where, const std::string& name) {
    if (!v.is_string() || v.get<std::string>().empty())
        throw FileError(name + ": " + where + "\"" + key + "\" must be a non-empty string");
    return v.get<std::string>();
}

CitySceneSource source(const json& s, std::size_t index, const std::string& name) {
    const std::string where = "sources[" + std::to_string(index) + "].";
    if (!s.is_object()) throw FileError(name + ": sources[" + std::to_string(index) + "] is not an object");
    CitySceneSource out;
    for (const auto& [key, v] : s.items()) {
        if (key == "path") out.path = text(v, key, where, name);
        else if (key == "lod") out.lod = text(v, key, where, name);
        else if (key == "height_attr") out.heightAttr = text(v, key, where, name);
        else if (key == "base_attr") out.baseAttr = text(v, key, where, name);
        else if (key == "role") {
            out.role = text(v, key, where, name);
            if (out.role != "terrain" && out.role != "solid")
                throw FileError(name + ": " + where + "\"role\" must be \"terrain\" or \"solid\", got \"" + out.role + "\"");
        } else if (key == "depth") {
            if (!v.is_number_integer() || v.get<long long>() < 1 || v.get<long long>() > Octree::kMaxDepth)
                throw FileError(name + ": " + where + "\"depth\" must be an integer in 1.." + std::to_string(Octree::kMaxDepth));
            out.depth = int(v.get<long long>());
        } else if (key == "colour" || key == "color") {
            if (!v.is_array() || v.size() != 3) throw FileError(name + ": " + where + "\"" + key + "\" must be [r, g, b] in [0, 1]");
            vec3 c;
            for (int k = 0; k < 3; ++k) {
                if (!v[std::size_t(k)].is_number() || !(v[std::size_t(k)].get<double>() >= 0.0 && v[std::size_t(k)].get<double>() <= 1.0))
                    throw FileError(name + ": " + where + "\"" + key + "\" must be [r, g, b] in [0, 1]");
                c[k] = float(v[std::size_t(k)].get<double>());
            }
            out.colour = packColour(c);
            out.hasColour = true;
        } else {
            throw FileError(name + ": " + where + "\"" + key + "\" is not a source key (path, lod, height_attr, base_attr, role, depth, colour)");
        }
    }
    if (out.path.empty()) throw FileError(name + ": sources[" + std::to_string(index) + "] has no \"path\"");
    return out;
}

}  // namespace

bool isCitySceneFile(const std::string& path) { return lower(std::filesystem::path(path).filename().string()).ends_with(".scene.json"); }

CityScene parseCityScene(const std::string& textIn, const std::string& name) {
    json doc;
    try {
        doc = json::parse(textIn);
    } catch (const json::exception& e) {
        // Not only syntax errors: a number beyond double's range is out_of_range (406).
        throw FileError(name + ": not valid JSON (" + std::string(e.what()) + ")");
    }
    if (!doc.is_object()) throw FileError(name + ": a scene file is a JSON object");
    CityScene scene;
    bool sources = false;
    for (const auto& [key, v] : doc.items()) {
        if (key == "crs") scene.crs = text(v, key, "", name);
        else if (key == "texture") scene.texture = text(v, key, "", name);
        else if (key == "sources") {
            if (!v.is_array() || v.empty()) throw FileError(name + ": \"sources\" must be a non-empty array");
            for (std::size_t i = 0; i < v.size(); ++i) scene.sources.push_back(source(v[i], i, name));
            sources = true;
        } else {
            throw FileError(name + ": \"" + key + "\" is not a scene key (sources, crs, texture)");
        }
    }
    if (!sources) throw FileError(name + ": no \"sources\" array");
    return scene;
}

CityModel readCityScene(const std::string& path, const std::string& text, const CityRequest& req, std::string& texture) {
    const CityScene scene = parseCityScene(text, path);
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    auto resolve = [&](const std::string& p) { return std::filesystem::path(p).is_absolute() ? p : (dir / p).string(); };
    CityModel m;
    m.source = path;
    m.format = "city scene (" + std::to_string(scene.sources.size()) + " sources)";
    std::string crs = req.crs.empty() ? scene.crs : req.crs;
    for (const CitySceneSource& s : scene.sources) {
        const std::string p = resolve(s.path);
        if (isCitySceneFile(p)) throw FileError(path + ": source " + s.path + " is a scene file itself");
        CityRequest r;
        r.lod = s.lod.empty() ? req.lod : s.lod;
        r.crs = crs;
        r.heightAttr = s.heightAttr;
        r.baseAttr = s.baseAttr;
        r.maxSamples = req.maxSamples;
        CityModel part = readCityModel(p, r);
        crs = part.crs;  // the others follow the first
        for (CityObject& o : part.objects) {
            if (s.hasColour) o.colour = s.colour;
            if (!s.role.empty()) o.role = s.role == "terrain" ? CityRole::Terrain : CityRole::Solid;
            o.depth = s.depth;
        }
        m.append(part);
        m.crs = crs;
    }
    texture = scene.texture.empty() ? std::string() : resolve(scene.texture);
    return m;
}

}  // namespace octrace::io::detail
