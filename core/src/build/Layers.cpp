#include "octrace/build/Layers.h"

#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace octrace {
namespace {

/// Morton code of a cell at `depth` (child index c = 4x + 2y + z per level, root first).
std::uint64_t mortonCode(const ivec3& c, int depth) {
    std::uint64_t m = 0;
    for (int b = depth - 1; b >= 0; --b)
        m = (m << 3) | std::uint64_t(((c.x >> b) & 1) << 2 | ((c.y >> b) & 1) << 1 | ((c.z >> b) & 1));
    return m;
}

struct Entry {
    std::uint64_t code;
    Voxel voxel;
    float value;
    std::uint8_t material;
    std::uint64_t corners;  // 0: none (Octree::corners)
};

void collect(const Octree& t, std::vector<Entry>& out) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    t.forEachVoxel([&](const ivec3& c, std::uint32_t v) {
        out.push_back({mortonCode(c, t.depth), t.voxels()[v], t.voxelValues().empty() ? nan : t.voxelValues()[v],
                       std::uint8_t(t.material(v)), t.corners().empty() ? 0 : t.corners()[v]});
    });
}

}  // namespace

ScalarField solidFromMask(const ScalarField& field) {
    ScalarField s;
    s.name = "solid";
    s.source = field.source;
    s.dims = field.dims;
    s.origin = field.origin;
    s.spacing = field.spacing;
    s.direction = field.direction;
    s.coords = field.coords;
    s.notes = field.notes;
    s.geographic = field.geographic;
    s.values.resize(field.sampleCount());
    std::size_t masked = 0;
    for (std::size_t i = 0; i < s.values.size(); ++i) {
        const bool solid = !field.isValid(i) || !std::isfinite(field.values[i]);
        s.values[i] = solid ? 1.0f : 0.0f;
        masked += solid;
    }
    if (masked == 0) throw EmptyResultError(field.source + ": '" + field.name + "' has no masked sample: no sea floor or land to draw");
    return s;
}

std::size_t extendColumnsDown(ScalarField& field) {
    if (!field.geographic.valid)
        throw UsageError(field.source + ": extending water columns down needs a geographic field (longitude, latitude, depth)");
    if (field.valid.empty()) return 0;
    std::size_t filled = 0;
    for (int j = 0; j < field.dims.y; ++j)
        for (int i = 0; i < field.dims.x; ++i) {
            bool water = false;
            float last = 0.0f;
            for (int k = field.dims.z - 1; k >= 0; --k) {  // from the surface down
                const std::size_t n = field.index(i, j, k);
                if (field.isValid(n) && std::isfinite(field.values[n])) {
                    water = true;
                    last = field.values[n];
                } else if (water) {
                    field.values[n] = last;
                    field.valid[n] = 1;
                    ++filled;
                }
            }
        }
    return filled;
}

void setMaterial(Octree& tree, VoxelMaterial material) {
    tree.setVoxelMaterials(std::vector<std::uint8_t>(tree.voxels().size(), std::uint8_t(material)));
}

Octree mergeShells(const Octree& top, const Octree& under) {
    if (top.form != OctreeForm::Shell || under.form != OctreeForm::Shell)
        throw UsageError("merging surfaces: both octrees must be shell octrees");
    if (top.depth != under.depth || top.cubeOrigin != under.cubeOrigin || top.cubeSide != under.cubeSide)
        throw UsageError("merging surfaces: the octrees differ in depth or cube (build them over the same grid and depth)");
    std::vector<Entry> all;
    all.reserve(top.voxels().size() + under.voxels().size());
    collect(top, all);
    collect(under, all);
    // Stable: of two entries with one code, top's (collected first) comes first and is kept.
    std::stable_sort(all.begin(), all.end(), [](const Entry& a, const Entry& b) { return a.code < b.code; });
    all.erase(std::unique(all.begin(), all.end(), [](const Entry& a, const Entry& b) { return a.code == b.code; }), all.end());

    Octree out = top.emptyCopy();
    const int depth = out.depth;
    // Prefix codes per level (level L: code >> 3 (depth - L)), breadth-first: nodes of level L
    // in code order, so that each node's children are contiguous and in child-index order.
    std::vector<std::vector<std::uint64_t>> levels(std::size_t(depth) + 1);
    levels[std::size_t(depth)].reserve(all.size());
    for (const Entry& e : all) levels[std::size_t(depth)].push_back(e.code);
    for (int l = depth - 1; l >= 0; --l) {
        auto& up = levels[std::size_t(l)];
        for (std::uint64_t c : levels[std::size_t(l) + 1])
            if (up.empty() || up.back() != (c >> 3)) up.push_back(c >> 3);
    }
    if (all.empty()) levels[0].assign(1, 0);  // an empty octree keeps its root
    std::vector<std::size_t> base(std::size_t(depth) + 1, 0);
    for (int l = 1; l < depth; ++l) base[std::size_t(l)] = base[std::size_t(l) - 1] + levels[std::size_t(l) - 1].size();
    std::vector<OctreeNode> nodes(depth > 0 ? base[std::size_t(depth) - 1] + levels[std::size_t(depth) - 1].size() : 0);
    for (int l = 0; l < depth; ++l) {
        const auto& parents = levels[std::size_t(l)];
        const auto& children = levels[std::size_t(l) + 1];
        const std::size_t childBase = l + 1 == depth ? 0 : base[std::size_t(l) + 1];
        std::size_t k = 0;
        for (std::size_t p = 0; p < parents.size(); ++p) {
            OctreeNode& n = nodes[base[std::size_t(l)] + p];
            n.firstChild = std::uint32_t(childBase + k);
            while (k < children.size() && (children[k] >> 3) == parents[p]) n.childMask |= std::uint8_t(1u << (children[k++] & 7u));
        }
    }
    std::vector<Voxel> voxels;
    std::vector<float> voxelValues;
    std::vector<std::uint8_t> voxelMaterials;
    std::vector<std::uint64_t> corners;
    voxels.reserve(all.size());
    // Smooth surfaces: the voxels of the one with corners keep them, the others draw as boxes.
    const bool withCorners = !top.corners().empty() || !under.corners().empty();
    const bool values = !top.voxelValues().empty() || !under.voxelValues().empty();
    const bool materials = !top.voxelMaterials().empty() || !under.voxelMaterials().empty();
    for (const Entry& e : all) {
        voxels.push_back(e.voxel);
        if (values) voxelValues.push_back(e.value);
        if (materials) voxelMaterials.push_back(e.material);
        if (withCorners) corners.push_back(e.corners);
    }
    out.setTopology(std::move(nodes), std::move(voxels));
    out.setVoxelValues(std::move(voxelValues));
    out.setVoxelMaterials(std::move(voxelMaterials));
    out.setCorners(std::move(corners));
    out.validate();
    return out;
}

}  // namespace octrace
