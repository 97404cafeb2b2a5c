#pragma once
// Private to core: building an octree's node pool bottom-up, as a recursion that makes each
// node's children first and then stores them together (the layout of Octree.h).
#include "octrace/octree/Octree.h"

#include <cstdint>
#include <vector>

namespace octrace::detail {

/// What an octant became: nothing, a node with children, or an interior term (volume form).
enum class Octant : std::uint8_t { Empty, Node, Term };

/// The child and term masks of a node whose children are of these kinds.
inline void childMasks(const Octant kinds[8], unsigned& mask, unsigned& terms) {
    mask = terms = 0;
    for (int c = 0; c < 8; ++c) {
        if (kinds[c] != Octant::Empty) mask |= 1u << c;
        if (kinds[c] == Octant::Term) terms |= 1u << c;
    }
}

struct TreeAssembly {
    std::vector<OctreeNode> nodes{OctreeNode{}};  // slot 0: the root, filled by finish()
    std::vector<Voxel> voxels;
    std::vector<float> values;           // Octree::voxelValues(), when the leaves give them
    std::vector<std::uint32_t> colours;  // Octree::colours(), when the leaves give them

    /// The node whose children are `kids` of kinds `kinds`: Empty when all are, Term when all
    /// are terms (eight terms make one), else its children are appended and `out` set.
    Octant node(const Octant kinds[8], const OctreeNode kids[8], OctreeNode& out) {
        unsigned mask, terms;
        childMasks(kinds, mask, terms);
        if (!mask) return Octant::Empty;
        if (terms == 0xFFu) return Octant::Term;
        out = OctreeNode{};
        out.firstChild = std::uint32_t(nodes.size());
        out.childMask = std::uint8_t(mask);
        out.termMask = std::uint8_t(terms);
        for (int c = 0; c < 8; ++c)
            if (mask & (1u << c)) nodes.push_back(kinds[c] == Octant::Term ? OctreeNode{} : kids[c]);
        return Octant::Node;
    }

    /// The node at level depth-1 with voxels `mask`, of which `interior` are interior voxels
    /// (all eight interior: a term); `vals` and `cols` (may be null) their Octree::voxelValues()
    /// and Octree::colours().
    Octant leaf(unsigned mask, unsigned interior, const Voxel vox[8], OctreeNode& out, const float* vals = nullptr,
                const std::uint32_t* cols = nullptr) {
        if (!mask) return Octant::Empty;
        if (mask == 0xFFu && interior == 0xFFu) return Octant::Term;
        out = OctreeNode{};
        out.firstChild = std::uint32_t(voxels.size());
        out.childMask = std::uint8_t(mask);
        out.termMask = std::uint8_t(interior);
        for (int c = 0; c < 8; ++c)
            if (mask & (1u << c)) {
                voxels.push_back((interior & (1u << c)) ? Voxel{} : vox[c]);
                if (vals) values.push_back(vals[c]);
                if (cols) colours.push_back(cols[c]);
            }
        return Octant::Node;
    }

    /// Moves the pool into `tree` with `root` as its root; false (tree untouched) when the
    /// root is not a node or there is no voxel.
    bool finish(Octant kind, const OctreeNode& root, Octree& tree) {
        if (kind != Octant::Node || voxels.empty()) return false;
        nodes[0] = root;
        nodes.shrink_to_fit();
        voxels.shrink_to_fit();
        values.shrink_to_fit();
        colours.shrink_to_fit();
        // Values and colours are given by every leaf or by none: either way one per voxel or none.
        const std::size_t n = voxels.size();
        tree.setTopology(std::move(nodes), std::move(voxels));
        tree.setVoxelValues(values.size() == n ? std::move(values) : std::vector<float>{});
        tree.setColours(colours.size() == n ? std::move(colours) : std::vector<std::uint32_t>{});
        return true;
    }
};

}  // namespace octrace::detail
