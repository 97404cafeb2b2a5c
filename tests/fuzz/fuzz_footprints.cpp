// Fuzz target: building footprints as GeoJSON through OGR in memory (/vsimem/), the height
// and base attributes, polygon extrusion and triangulation, and the voxelizer at a small
// depth. The input is the bytes of a .geojson file.
#include "city/FootprintReader.h"
#include "CityFuzz.h"
#include "FuzzSupport.h"
#include "octrace/util/Error.h"

#include <cpl_vsi.h>

#include <string>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string path = "/vsimem/fuzz_footprints.geojson";
    VSILFILE* f = VSIFileFromMemBuffer(path.c_str(), const_cast<GByte*>(data), vsi_l_offset(size), FALSE);
    if (!f) return 0;
    VSIFCloseL(f);
    octrace::io::CityRequest req;
    req.heightAttr = "height";
    for (const char* base : {"", "base"}) {
        req.baseAttr = base;
        try {
            octrace::CityModel m;
            octrace::io::detail::addFootprints(m, path, req);
            octrace::fuzz::voxelizeSmall(m);
        } catch (const octrace::Error&) {
            // A clean refusal: what we want for broken input.
        }
    }
    VSIUnlink(path.c_str());
    return 0;
}
