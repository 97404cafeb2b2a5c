// Fuzz target: CityJSON text through the parser (transform, vertices, objects, geometries of
// every type, levels of detail), the polygon triangulation, the watertightness check and the
// voxelizer at a small depth. The input is the bytes of a .city.json file.
#include "city/CityJson.h"
#include "CityFuzz.h"
#include "FuzzSupport.h"

#include <string>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    octrace::fuzz::parseAndVoxelize(data, size, [](const std::string& text, const char* lod) {
        return octrace::io::detail::parseCityJson(text, "fuzz.city.json", lod);
    });
    return 0;
}
