// Fuzz target: city scene files (`.scene.json`): the JSON parser and our checks of every key
// (sources, paths, roles, depths, colours, the CRS and texture entries). The input is the bytes
// of a scene file; the sources it names are not opened (what reading them does is the other
// city targets').
#include "city/CityScene.h"
#include "FuzzSupport.h"
#include "octrace/util/Error.h"

#include <cstdlib>
#include <string>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    octrace::fuzz::quietLogs();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        const auto scene = octrace::io::detail::parseCityScene(text, "fuzz.scene.json");
        // What parses holds what the checks promise.
        if (scene.sources.empty()) std::abort();
        for (const auto& s : scene.sources)
            if (s.path.empty() || s.depth < 0 || s.depth > 14 || (!s.role.empty() && s.role != "terrain" && s.role != "solid")) std::abort();
    } catch (const octrace::Error&) {
        // A clean refusal: what we want for broken input.
    }
    return 0;
}
