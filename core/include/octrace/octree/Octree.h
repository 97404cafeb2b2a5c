#pragma once
/// @file Octree.h
/// The voxel octree: a compact node pool (no pointers), children addressed by index.
///
/// Layout. Node 0 is the root (level 0); the finest level is `depth`, whose cells are the
/// voxels. Every inner node stores an 8-bit child mask (bit c set = child c is not empty;
/// child index c = 4*x + 2*y + z) and the index of its first non-empty child; the non-empty
/// children of a node are stored contiguously in child-index order, so child c lives at
/// firstChild + popcount(childMask & ((1 << c) - 1)).
///   - At levels 0 .. depth-2 the children are nodes (in `nodes`), except those whose
///     `termMask` bit is set: those are interior "terms" (octants wholly inside the object,
///     volume form only) and occupy a slot in `nodes` with childMask 0.
///   - At level depth-1 the children are voxels: firstChild indexes `voxels`.
/// Leaf kinds: empty (mask bit clear), interior term, boundary voxel, coarse leaf. The shell
/// form built by OctreeBuilder has no terms.
///   - Coarse leaves (shell form, mixed depth: a city's terrain shallower than its buildings,
///     CityVoxelizer.h): in the shell form a term bit at a node of level < depth-1 marks a
///     boundary leaf larger than a voxel, drawn as a solid cube of its level. Its slot in
///     `nodes` has childMask 0 and its firstChild indexes `voxels` (and `colours` etc.): the
///     leaf's normal and colour. Every renderer draws it (hits report it with
///     TraversalHit::leafShift); forEachLeaf visits it.
///   - Volume form (OctreeForm::Volume, see build/Volume.h): the solid's interior is kept as
///     terms; at level depth-1 a term bit marks an *interior voxel*, which occupies a slot in
///     `voxels` like a boundary voxel (its normal is unused, 0). Renderers draw the shell form:
///     a volume octree is turned into one by extractShell (Volume.h) first.
///
/// Spaces. World space (the field's units, e.g. km or mm); octree integer space, where the
/// cube is [0, 2^kIntBits)^3 (`toOctreeSpace`); cell space, where voxel (i,j,k) is
/// [i, i+1) x [j, j+1) x [k, k+1) with i in [0, 2^depth).
#include "octrace/util/Math.h"

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace octrace {

struct OctreeNode {
    std::uint32_t firstChild = 0;
    std::uint8_t childMask = 0;
    std::uint8_t termMask = 0;
    std::uint16_t reserved = 0;
};
static_assert(sizeof(OctreeNode) == 8);

namespace detail {
struct Popcount8 {
    std::uint8_t v[256];
    constexpr Popcount8() : v() {
        for (int i = 0; i < 256; ++i) v[i] = std::uint8_t((i & 1) + ((i >> 1) & 1) + ((i >> 2) & 1) + ((i >> 3) & 1) +
                                                       ((i >> 4) & 1) + ((i >> 5) & 1) + ((i >> 6) & 1) + ((i >> 7) & 1));
    }
};
inline constexpr Popcount8 kPopcount8{};
}  // namespace detail

/// Position of child c among the non-empty children of a node with this child mask (a table:
/// no POPCNT instruction is assumed of the target).
inline unsigned childRank(unsigned childMask, unsigned c) { return detail::kPopcount8.v[childMask & ((1u << c) - 1u)]; }

/// What an octree holds: the boundary voxels only (shell) or the solid with its interior.
enum class OctreeForm : std::uint8_t { Shell = 0, Volume = 1 };

/// A boundary voxel: its quantized unit normal (octahedral, 16+16 bits).
struct Voxel {
    std::uint32_t normal = 0;
};

/// What an inner node carries for multi-resolution rendering: the average of its subtree's
/// boundary voxels. A renderer that stops at the node draws it as a solid box with these.
struct NodeSummary {
    std::uint32_t normal = 0;      ///< average unit normal (octahedral code); +z when they cancel
    std::uint32_t voxelCount = 0;  ///< boundary voxels below
    std::uint32_t firstVoxel = 0;  ///< a boundary voxel below (the first depth-first): the hit id shown
    float meanZ = 0.0f;            ///< mean voxel-centre z in cell space (colour by height)
};

/// What a boundary voxel is a part of (Octree::voxelMaterials): the isosurface, or the sea
/// floor / land drawn under it (build/Layers.h). Renderers colour a material through Shading.h.
enum class VoxelMaterial : std::uint8_t { Surface = 0, Floor = 1 };
/// A colour packed in 32 bits: 8-bit sRGB red, green, blue in the low three bytes (red lowest),
/// alpha in the top byte.
std::uint32_t packColour(vec3 srgb);
/// The packed colour's red, green, blue, sRGB in [0,1].
vec3 unpackColour(std::uint32_t packed);

/// Octahedral encoding of a unit vector in 32 bits (max angular error ~0.005 degrees).
std::uint32_t encodeNormal(vec3 n);
vec3 decodeNormal(std::uint32_t code);

class Octree {
public:
    /// Side of the cube in octree integer space is 2^kIntBits.
    static constexpr int kIntBits = 14;
    static constexpr int kMaxDepth = kIntBits;

    Octree() = default;
    Octree(Octree&&) noexcept = default;
    Octree& operator=(Octree&&) noexcept = default;
    Octree(const Octree&) = delete;
    Octree& operator=(const Octree&) = delete;

    int depth = 0;            ///< level of the voxels (root = 0)
    dvec3 cubeOrigin{0.0};    ///< world position of the cube's minimum corner
    double cubeSide = 1.0;    ///< world edge length of the cube

    std::vector<OctreeNode> nodes;  ///< nodes[0] = root
    std::vector<Voxel> voxels;      ///< boundary voxels
    /// Optional per-voxel colour beside the octree (same index as `voxels`, packColour), e.g. a
    /// city's texture and building colours; empty: the renderers' uniform colour or colour map.
    /// Every renderer shades through Albedo (Shading.h), so all of them use it alike.
    std::vector<std::uint32_t> colours;
    bool hasColours() const { return !voxels.empty() && colours.size() == voxels.size(); }
    /// Per boundary voxel (same index as `voxels`), empty when absent (and in octree files): a
    /// value that Shading.h colours the voxel by. Either the field's own value just inside the
    /// surface, greyed by a display window (RenderSettings::window; filled when the build asks
    /// for it, BuildOptions::voxelValues), or a second variable sampled at the voxel's centre
    /// and mapped by a colour map (colour by: sampleAtVoxels in OctreeBuilder.h; NaN where the
    /// sample touches a masked cell or lies outside its grid; valueName etc. say what it is).
    std::vector<float> voxelValues;
    /// Per voxel (same index as `voxels`), baked diffuse light 0..255 = 0..1 (lighting/Bake.h);
    /// empty when none was baked. Shell form only.
    std::vector<std::uint8_t> baked;
    /// Per node (same index as `nodes`), filled by computeSummaries(); empty until then.
    std::vector<NodeSummary> summaries;

    OctreeForm form = OctreeForm::Shell;

    /// What voxelValues are when they are a second variable (colour by); empty otherwise.
    std::string valueName, valueUnits, valueStandardName;
    /// Per boundary voxel (same index as `voxels`): its material (values of VoxelMaterial);
    /// empty = every voxel VoxelMaterial::Surface (and in octree files). Shading.h colours by it.
    std::vector<std::uint8_t> voxelMaterials;
    VoxelMaterial material(std::uint32_t voxel) const {
        return voxelMaterials.empty() ? VoxelMaterial::Surface : VoxelMaterial(voxelMaterials[voxel]);
    }

    // Provenance, for info and stats.
    std::string fieldName, fieldUnits;
    double iso = 0.0;
    bool insideBelow = false;  ///< volume form: the solid is value < iso (else value >= iso)
    std::string source;        ///< what it was made from (input, region, operations), for info
    std::string crs;           ///< coordinate reference system of world space (city models), e.g. "EPSG:7415"; empty: none

    /// An octree with this one's depth, cube, form and provenance (field, iso, source, the
    /// voxel values' name and units) but no nodes, voxels or per-voxel attributes: the start
    /// of an operation that makes a new node pool over the same cube.
    Octree emptyCopy() const;
    /// A deep copy: emptyCopy() and every node, voxel and per-voxel buffer (normals, colours,
    /// values, materials, baked light) and the node summaries. The one way to copy an octree
    /// (it is move-only, since its buffers are large).
    Octree copy() const;

    std::size_t boundaryVoxels() const { return voxels.size(); }
    /// Capacity in bytes of every buffer the octree owns.
    std::size_t bytes() const;
    double bytesPerVoxel() const { return voxels.empty() ? 0.0 : double(bytes()) / double(voxels.size()); }

    /// World edge length of one voxel.
    double voxelSize() const { return cubeSide / double(1u << depth); }
    /// World -> octree integer space (continuous).
    dvec3 toOctreeSpace(const dvec3& world) const {
        return (world - cubeOrigin) * (double(1u << kIntBits) / cubeSide);
    }
    dvec3 worldFromOctreeSpace(const dvec3& p) const {
        return cubeOrigin + p * (cubeSide / double(1u << kIntBits));
    }
    /// World box of voxel (i,j,k) (cell space).
    Box3 voxelBox(const ivec3& cell) const;

    /// Index of the boundary voxel at cell (i,j,k) (or of the coarse leaf holding it), or
    /// 0xFFFFFFFF when that cell is not a boundary voxel (or lies outside). O(depth).
    std::uint32_t findVoxel(const ivec3& cell) const;

    /// Smallest cell-space box [lo, hi] (inclusive) holding every boundary voxel; lo > hi
    /// when there is none. Computed without entering nodes that lie inside the box found so
    /// far: O(voxels) at worst.
    void occupiedCells(ivec3& lo, ivec3& hi) const;
    /// World box of the occupied cells (the surface's bounding box).
    Box3 occupiedBounds() const;

    /// Calls f(cell, voxelIndex) for every entry of `voxels` (depth-first order); a coarse leaf
    /// counts as the voxel at its lowest cell (forEachLeaf tells its size).
    template <class F>
    void forEachVoxel(F&& f) const {
        forEachLeaf([&](const ivec3& cell, int, std::uint32_t v) { f(cell, v); });
    }
    /// Whether the shell octree has coarse leaves (boundary leaves above the voxel level).
    bool hasCoarseLeaves() const;
    /// Calls f(cell, shift, voxelIndex) for every boundary leaf (depth-first order): a voxel
    /// (shift 0) or a coarse leaf of side 2^shift voxels whose lowest voxel cell is `cell`.
    template <class F>
    void forEachLeaf(F&& f) const;
    /// Calls f(cell, index) for every non-empty octant at `level` (cell coordinates at that
    /// level, 0 .. 2^level - 1), in the depth-first order of forEachVoxel: at level == depth
    /// the boundary voxels (index into `voxels`), at 0 <= level < depth the nodes (index into
    /// `nodes` and `summaries`; interior terms included, their subtrees not entered). Nothing
    /// for a level outside [0, depth].
    template <class F>
    void forEachAtLevel(int level, F&& f) const;

    /// Depth-first over the non-empty children: enter(level, cell, slot, term) for each (its
    /// level and cell, its slot, whether its term bit is set); descends where it returns true.
    template <class F>
    void descend(F&& enter) const;

    /// Fills `summaries` bottom-up in O(nodes + voxels). Needed by --lod / --level.
    void computeSummaries();
    bool hasSummaries() const { return !nodes.empty() && summaries.size() == nodes.size(); }
    /// Fraction of the node's cell-space volume (8^(depth-level) cells) that is boundary voxels.
    double occupancy(std::uint32_t node, int level) const {
        return double(summaries[node].voxelCount) / std::ldexp(1.0, 3 * (depth - level));
    }

    /// Structural checks (masks, index ranges, every node reachable once). Throws Error.
    void validate() const;
};

template <class F>
void Octree::descend(F&& enter) const {
    if (nodes.empty()) return;
    struct Item { std::uint32_t node; int level; ivec3 cell; };
    std::vector<Item> stack{{0u, 0, ivec3(0)}};
    while (!stack.empty()) {
        Item it = stack.back();
        stack.pop_back();
        const OctreeNode& n = nodes[it.node];
        std::uint32_t slot = n.firstChild;
        for (int c = 0; c < 8; ++c) {
            if (!(n.childMask & (1u << c))) continue;
            const ivec3 cc = it.cell * 2 + ivec3((c >> 2) & 1, (c >> 1) & 1, c & 1);
            if (enter(it.level + 1, cc, slot, (n.termMask & (1u << c)) != 0)) stack.push_back({slot, it.level + 1, cc});
            ++slot;
        }
    }
}

template <class F>
void Octree::forEachAtLevel(int level, F&& f) const {
    if (nodes.empty() || level < 0 || level > depth) return;
    if (level == 0) {
        if (depth > 0) f(ivec3(0), 0u);
        return;
    }
    descend([&](int l, const ivec3& cell, std::uint32_t slot, bool term) {
        if (l < level) return !term;
        f(cell, slot);
        return false;
    });
}

template <class F>
void Octree::forEachLeaf(F&& f) const {
    if (depth < 1) return;
    descend([&](int l, const ivec3& cell, std::uint32_t slot, bool term) {
        if (l == depth) {
            f(cell, 0, slot);  // volume form: interior voxels too, as forEachAtLevel(depth)
            return false;
        }
        if (!term) return true;
        if (form == OctreeForm::Shell) f(cell << (depth - l), depth - l, nodes[slot].firstChild);  // a coarse leaf
        return false;
    });
}

}  // namespace octrace
