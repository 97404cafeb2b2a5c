#pragma once
// City scene files (`NAME.scene.json`, internal to octrace_io): several city sources — CityJSON,
// CityGML, footprints, DEM rasters — combined into one model, each with its own depth, colour
// and role, plus a texture draped on the terrain. docs/user/cli.md describes the format.
#include "octrace/build/CityModel.h"
#include "octrace/io/CityReader.h"

#include <cstdint>
#include <string>
#include <vector>

namespace octrace::io::detail {

struct CitySceneSource {
    std::string path;                 ///< as written (relative to the scene file's folder)
    std::string lod, heightAttr, baseAttr;
    std::string role;                 ///< "", "terrain" or "solid": overrides the objects' roles
    bool hasColour = false;
    std::uint32_t colour = 0;         ///< packColour, for every object of the source
    int depth = 0;                    ///< 0: the build's (CityObject::depth)
};

struct CityScene {
    std::string crs, texture;
    std::vector<CitySceneSource> sources;
};

/// Whether the path names a scene file (`.scene.json`).
bool isCitySceneFile(const std::string& path);

/// Parses and checks the scene text (every key known, types, depths in 1..Octree::kMaxDepth,
/// colours in [0,1], at least one source). Throws FileError naming `name` and the key.
CityScene parseCityScene(const std::string& text, const std::string& name);

/// Reads every source of the scene file (`path`, its contents `text`) into one model: the first source fixes the CRS (the
/// scene's "crs", or `req.crs`, which wins), the others are brought into it; each source's
/// depth, colour and role are set on its objects. `texture` receives the scene's texture path
/// (resolved), empty when none. A source that is itself a scene file is refused.
CityModel readCityScene(const std::string& path, const std::string& text, const CityRequest& req, std::string& texture);

}  // namespace octrace::io::detail
