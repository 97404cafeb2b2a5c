#include "octrace/build/Volume.h"

#include "build/TreeAssembly.h"
#include "octrace/util/Error.h"

#include <bit>

namespace octrace {

VoxelCount countVoxels(const Octree& tree) {
    VoxelCount n;
    if (tree.nodes().empty()) return n;
    struct Item { std::uint32_t node; int level; };
    std::vector<Item> stack{{0u, 0}};
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        const OctreeNode& nd = tree.nodes()[it.node];
        const unsigned terms = nd.termMask, kids = nd.childMask & ~nd.termMask;
        if (it.level == tree.depth - 1) {
            n.interior += unsigned(detail::kPopcount8.v[terms]);
            n.boundary += unsigned(detail::kPopcount8.v[kids]);
            continue;
        }
        if (tree.form == OctreeForm::Shell) n.boundary += unsigned(detail::kPopcount8.v[terms]);  // coarse leaves (Octree.h)
        else n.interior += std::uint64_t(detail::kPopcount8.v[terms]) << (3 * (tree.depth - it.level - 1));
        std::uint32_t slot = nd.firstChild;
        for (int c = 0; c < 8; ++c) {
            if (!(nd.childMask & (1u << c))) continue;
            if (kids & (1u << c)) stack.push_back({slot, it.level + 1});
            ++slot;
        }
    }
    return n;
}

CellState cellSlot(const Octree& tree, const ivec3& cell, std::uint32_t& slot) {
    slot = 0xFFFFFFFFu;
    const int n = 1 << tree.depth;
    if (tree.nodes().empty() || cell.x < 0 || cell.y < 0 || cell.z < 0 || cell.x >= n || cell.y >= n || cell.z >= n)
        return CellState::Empty;
    std::uint32_t node = 0;
    for (int level = 0; level < tree.depth; ++level) {
        const int shift = tree.depth - 1 - level;
        const unsigned c = unsigned((((cell.x >> shift) & 1) << 2) | (((cell.y >> shift) & 1) << 1) | ((cell.z >> shift) & 1));
        const OctreeNode& nd = tree.nodes()[node];
        if (!(nd.childMask & (1u << c))) return CellState::Empty;
        const bool term = nd.termMask & (1u << c);
        const std::uint32_t child = nd.firstChild + childRank(nd.childMask, c);
        if (level == tree.depth - 1) {
            slot = child;
            return term ? CellState::Interior : CellState::Boundary;
        }
        if (term) return CellState::Interior;
        node = child;
    }
    return CellState::Empty;
}

CellState cellState(const Octree& tree, const ivec3& cell, std::uint32_t* voxel) {
    std::uint32_t slot;
    const CellState s = cellSlot(tree, cell, slot);
    if (voxel) *voxel = s == CellState::Boundary ? slot : 0xFFFFFFFFu;
    return s;
}

Octree extractShell(const Octree& volume) {
    if (volume.form == OctreeForm::Shell) return volume.copy();
    Octree out = volume.emptyCopy();
    out.form = OctreeForm::Shell;
    detail::TreeAssembly pool;
    using detail::Octant;
    const bool values = !volume.voxelValues().empty(), colours = volume.hasColours();
    auto copy = [&](auto&& self, std::uint32_t node, int level, OctreeNode& dst) -> Octant {
        const OctreeNode& nd = volume.nodes()[node];
        std::uint32_t slot = nd.firstChild;
        if (level == volume.depth - 1) {
            unsigned mask = 0;
            Voxel vox[8];
            float val[8] = {};
            std::uint32_t col[8] = {};
            for (int c = 0; c < 8; ++c) {
                if (!(nd.childMask & (1u << c))) continue;
                if (!(nd.termMask & (1u << c))) {
                    vox[c] = volume.voxels()[slot];
                    if (values) val[c] = volume.voxelValues()[slot];
                    if (colours) col[c] = volume.colours()[slot];
                    mask |= 1u << c;
                }
                ++slot;
            }
            return pool.leaf(mask, 0u, vox, dst, values ? val : nullptr, colours ? col : nullptr);
        }
        OctreeNode kids[8];
        Octant kinds[8] = {};
        for (int c = 0; c < 8; ++c) {
            if (!(nd.childMask & (1u << c))) continue;
            if (!(nd.termMask & (1u << c))) kinds[c] = self(self, slot, level + 1, kids[c]);
            ++slot;
        }
        return pool.node(kinds, kids, dst);
    };
    OctreeNode root;
    if (volume.nodes().empty() || !pool.finish(copy(copy, 0u, 0, root), root, out))
        throw EmptyResultError(std::string(volume.source()).append(": the solid has no boundary voxel"));
    return out;
}

}  // namespace octrace
