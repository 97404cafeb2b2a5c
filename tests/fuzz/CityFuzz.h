#pragma once
// What the city fuzz targets do with a model they read: voxelize it small and check the tree.
#include "octrace/build/CityVoxelizer.h"
#include "octrace/util/Error.h"

#include <cstdint>
#include <string>

namespace octrace::fuzz {

inline void voxelizeSmall(const CityModel& m) {
    CityBuildOptions o;
    o.depth = 5;
    o.threads = 1;
    voxelizeCity(m, o).validate();
}

/// The bytes as a file's text through `parse(text, lod)` at the default LoD and at LoD 1, each
/// model voxelized small; a clean refusal (octrace::Error) is what broken input should give.
template <class Parse>
void parseAndVoxelize(const std::uint8_t* data, std::size_t size, Parse&& parse) {
    const std::string text(reinterpret_cast<const char*>(data), size);
    for (const char* lod : {"", "1"}) {
        try {
            voxelizeSmall(parse(text, lod));
        } catch (const Error&) {
        }
    }
}

}  // namespace octrace::fuzz
