#include "octrace/render/Surfels.h"

#include "octrace/render/ImageCompare.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"
#include "octrace/util/Parallel.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace octrace {

float surfelRadius(double side) { return float(0.5 * std::sqrt(3.0) * side); }

std::vector<Surfel> extractSurfels(const Octree& tree, const RenderSettings& settings, int level) {
    if (level < 0) level = tree.depth;
    if (level > tree.depth)
        throw UsageError("surfels at level " + std::to_string(level) + ": the octree has depth " +
                         std::to_string(tree.depth));
    const bool voxels = level == tree.depth;
    if (!voxels && !tree.hasSummaries())
        throw UsageError("surfels at level " + std::to_string(level) + " need the node summaries (Octree::computeSummaries)");
    const Albedo albedo(tree, settings);

    // The order first (one cheap serial walk), then the surfels in parallel.
    struct Item {
        ivec3 cell;
        std::uint32_t index;
        int shift;  // at the voxel level: the leaf's side is 2^shift voxels (coarse leaves, Octree.h)
    };
    std::vector<Item> items;
    items.reserve(voxels ? tree.voxels().size() : 0);
    if (voxels)
        tree.forEachLeaf([&](const ivec3& cell, int shift, std::uint32_t index) { items.push_back({cell, index, shift}); });
    else
        tree.forEachAtLevel(level, [&](const ivec3& cell, std::uint32_t index) {
            if (tree.summaries()[index].voxelCount > 0) items.push_back({cell, index, 0});
        });

    const double side = tree.cubeSide / std::ldexp(1.0, level);
    std::vector<Surfel> out(items.size());
    constexpr std::size_t kChunk = 4096;
    parallelFor((items.size() + kChunk - 1) / kChunk, settings.threads, [&](std::size_t chunk) {
        const std::size_t end = std::min(items.size(), (chunk + 1) * kChunk);
        for (std::size_t i = chunk * kChunk; i < end; ++i) {
            const Item& it = items[i];
            Surfel& s = out[i];
            const double size = std::ldexp(1.0, it.shift);
            s.position = vec3(tree.cubeOrigin + (dvec3(it.cell) + 0.5 * size) * side);
            s.radius = surfelRadius(side * size);
            float zCells;
            std::uint32_t voxel = it.index;
            if (voxels) {
                s.normal = decodeNormal(tree.voxels()[it.index].normal);
                zCells = float(it.cell.z) + 0.5f;
            } else {
                const NodeSummary& summary = tree.summaries()[it.index];
                s.normal = decodeNormal(summary.normal);
                zCells = summary.meanZ;
                voxel = summary.firstVoxel;
            }
            const vec3 c = albedo.at(voxel, zCells);
            s.rgba = {linearToSrgb8(c.r), linearToSrgb8(c.g), linearToSrgb8(c.b), 255};
        }
    });
    return out;
}

}  // namespace octrace
