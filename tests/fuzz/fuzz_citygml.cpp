// Fuzz target: CityGML text through GDAL's XML parser and ours (namespaces, city objects, lodN
// properties, roofs, xlink references, posList/pos/coordinates, srsName forms), the polygon
// triangulation and the voxelizer at a small depth. The input is the bytes of a .gml file.
#include "CityFuzz.h"
#include "city/CityGml.h"
#include "FuzzSupport.h"

#include <string>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    octrace::fuzz::parseAndVoxelize(data, size, [](const std::string& text, const char* lod) {
        return octrace::io::detail::parseCityGml(text, "fuzz.gml", lod);
    });
    return 0;
}
