#pragma once
// What the city fuzz targets do with a model they read: voxelize it small and check the tree.
#include "octrace/build/CityVoxelizer.h"

namespace octrace::fuzz {

inline void voxelizeSmall(const CityModel& m) {
    CityBuildOptions o;
    o.depth = 5;
    o.threads = 1;
    voxelizeCity(m, o).validate();
}

}  // namespace octrace::fuzz
