#pragma once
/// @file Octree.h
/// The voxel octree: a compact node pool (no pointers), children addressed by index.
///
/// Layout. Node 0 is the root (level 0); the finest level is `depth`, whose cells are the
/// voxels. Every inner node stores an 8-bit child mask (bit c set = child c is not empty;
/// child index c = 4*x + 2*y + z) and the index of its first non-empty child; the non-empty
/// children of a node are stored contiguously in child-index order, so child c lives at
/// firstChild + popcount(childMask & ((1 << c) - 1)).
///   - At levels 0 .. depth-2 the children are nodes (in `nodes()`), except those whose
///     `termMask` bit is set: those are interior "terms" (octants wholly inside the object,
///     volume form only) and occupy a slot in `nodes()` with childMask 0.
///   - At level depth-1 the children are voxels: firstChild indexes `voxels()`.
/// Leaf kinds: empty (mask bit clear), interior term, boundary voxel, coarse leaf. The shell
/// form built by OctreeBuilder has no terms.
///   - Coarse leaves (shell form, mixed depth: a city's terrain shallower than its buildings,
///     CityVoxelizer.h): in the shell form a term bit at a node of level < depth-1 marks a
///     boundary leaf larger than a voxel, drawn as a solid cube of its level. Its slot in
///     `nodes()` has childMask 0 and its firstChild indexes `voxels()` (and the per-voxel
///     attributes): the leaf's normal and colour. Every renderer draws it (hits report it with
///     TraversalHit::leafShift); forEachLeaf visits it.
///   - Volume form (OctreeForm::Volume, see build/Volume.h): the solid's interior is kept as
///     terms; at level depth-1 a term bit marks an *interior voxel*, which occupies a slot in
///     `voxels()` like a boundary voxel (its normal is unused, 0). Renderers draw the shell
///     form: a volume octree is turned into one by extractShell (Volume.h) first.
///
/// Spaces. World space (the field's units, e.g. km or mm); octree integer space, where the
/// cube is [0, 2^kIntBits)^3 (`toOctreeSpace`); cell space, where voxel (i,j,k) is
/// [i, i+1) x [j, j+1) x [k, k+1) with i in [0, 2^depth).
///
/// Invariants. The topology is private (nodes(), voxels(); setTopology hands a new one over),
/// and so is what is indexed like it: the per-voxel attributes (VoxelAttributes: colours,
/// values, baked light, materials), each empty or one per voxel, and the node summaries, empty
/// or one per node. Their setters refuse any other length, so no reader has to check it.
/// Provenance (field, source, CRS, ...) is a string map, metadata(), with well-known keys in
/// octree_key; what the octree means (depth, cube, form, iso) stays in typed members.
#include "octrace/util/Math.h"

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
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

/// What a boundary voxel is a part of (Octree::voxelMaterials()): the isosurface, or the sea
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

/// Smooth surfaces (render/SmoothSurface.h, VoxelAttributes::corners): the 8 corner values of
/// a voxel (corner q = 4x + 2y + z, as child indices) relative to `iso`, in 8 signed bytes: (value - iso) / max |value - iso| x 127, rounded, a corner below iso never
/// rounded up to 0 (so the sides of the corners are kept exactly; the surface inside the voxel
/// does not depend on the scale). Byte q is bits 8q .. 8q+7. 0 only when every corner equals iso.
std::uint64_t encodeCorners(const float values[8], float iso);
/// The scaled corner values in [-1, 1] (all 0 for the code 0).
void decodeCorners(std::uint64_t code, double d[8]);

/// Well-known keys of Octree::metadata(): what the octree was made from, for info and stats.
/// Other keys may be set freely (they are carried by emptyCopy and copy like these).
namespace octree_key {
inline constexpr std::string_view kFieldName = "field_name";    ///< the field's variable, e.g. "thetao"
inline constexpr std::string_view kFieldUnits = "field_units";  ///< its units, e.g. "degC"
inline constexpr std::string_view kSource = "source";  ///< what it was made from (input, region, operations)
/// Coordinate reference system of world space (city models), e.g. "EPSG:7415"; absent: none.
inline constexpr std::string_view kCrs = "crs";
/// What Octree::voxelValues() are when they are a second variable (colour by); absent otherwise.
inline constexpr std::string_view kValueName = "value_name";
inline constexpr std::string_view kValueUnits = "value_units";
inline constexpr std::string_view kValueStandardName = "value_standard_name";
}  // namespace octree_key

/// The per-voxel attributes beside the topology, each indexed like Octree::voxels(). Each is
/// either empty (absent) or exactly one entry per voxel: Octree's setters refuse any other
/// length, so a renderer may index one by a voxel index as soon as it is not empty.
struct VoxelAttributes {
    /// Per-voxel colour (packColour), e.g. a city's texture and building colours; empty: the
    /// renderers' uniform colour or colour map. Every renderer shades through Albedo
    /// (Shading.h), so all of them use it alike.
    std::vector<std::uint32_t> colours;
    /// A value that Shading.h colours the voxel by (empty in octree files). Either the field's
    /// own value just inside the surface, greyed by a display window (RenderSettings::window;
    /// filled when the build asks for it, BuildOptions::voxelValues), or a second variable
    /// sampled at the voxel's centre and mapped by a colour map (colour by: sampleAtVoxels in
    /// OctreeBuilder.h; NaN where the sample touches a masked cell or lies outside its grid;
    /// the metadata keys octree_key::kValueName etc. say what it is).
    std::vector<float> voxelValues;
    /// Baked diffuse light 0..255 = 0..1 (lighting/Bake.h); empty when none was baked. Shell
    /// form only.
    std::vector<std::uint8_t> baked;
    /// The voxel's material (values of VoxelMaterial); empty = every voxel
    /// VoxelMaterial::Surface (and in octree files). Shading.h colours by it.
    std::vector<std::uint8_t> voxelMaterials;
    /// Smooth surfaces (render/SmoothSurface.h): per voxel the field's values at its 8 corners
    /// relative to the iso value, quantized (encodeCorners); code 0 = none (drawn as a voxel,
    /// e.g. a floor voxel merged in). Empty: every voxel is drawn as its box (mesh-derived
    /// scenes, volume forms, octree files of format version 1 and 2).
    std::vector<std::uint64_t> corners;
};

/// Ordered, so that listings and comparisons of the metadata are stable.
using OctreeMetadata = std::map<std::string, std::string, std::less<>>;

/// The octree. Its topology (nodes, voxels) and what is indexed like it (per-voxel attributes,
/// per-node summaries) are private, so that their lengths always agree: readers get const
/// references (inline, no copy: the renderers' hot loops read them directly), writers build
/// vectors of their own and hand them over (setTopology, setColours, ...), which check them.
class Octree {
public:
    /// Side of the cube in octree integer space is 2^kIntBits.
    static constexpr int kIntBits = 14;
    static constexpr int kMaxDepth = kIntBits;

    Octree();
    Octree(Octree&&) noexcept;
    Octree& operator=(Octree&&) noexcept;
    ~Octree();
    Octree(const Octree&) = delete;
    Octree& operator=(const Octree&) = delete;

    int depth = 0;            ///< level of the voxels (root = 0)
    dvec3 cubeOrigin{0.0};    ///< world position of the cube's minimum corner
    double cubeSide = 1.0;    ///< world edge length of the cube
    OctreeForm form = OctreeForm::Shell;
    double iso = 0.0;          ///< the isovalue the surface (or solid) was built at
    bool insideBelow = false;  ///< volume form: the solid is value < iso (else value >= iso)

    // ---- topology --------------------------------------------------------------------------
    const std::vector<OctreeNode>& nodes() const { return nodes_; }  ///< nodes()[0] = root
    const std::vector<Voxel>& voxels() const { return voxels_; }     ///< boundary voxels
    /// Replaces the node pool and the voxels (taken over, not copied). Each per-voxel attribute
    /// whose length still equals the new voxel count is kept (the caller vouches that it is
    /// indexed alike, e.g. when only the normals changed); the others are dropped. The node
    /// summaries are always dropped (they describe the old nodes: computeSummaries again). Does
    /// not validate: call validate() where the topology comes from outside (a file).
    void setTopology(std::vector<OctreeNode> nodes, std::vector<Voxel> voxels);
    /// Sets one voxel's normal (octahedral code, encodeNormal), e.g. when they are decoded after
    /// the topology. `voxel` < voxels().size() (unchecked).
    void setVoxelNormal(std::uint32_t voxel, std::uint32_t normal) { voxels_[voxel].normal = normal; }

    // ---- per-voxel attributes (VoxelAttributes) ---------------------------------------------
    const VoxelAttributes& attributes() const { return attributes_; }
    const std::vector<std::uint32_t>& colours() const { return attributes_.colours; }
    const std::vector<float>& voxelValues() const { return attributes_.voxelValues; }
    const std::vector<std::uint8_t>& baked() const { return attributes_.baked; }
    const std::vector<std::uint8_t>& voxelMaterials() const { return attributes_.voxelMaterials; }
    const std::vector<std::uint64_t>& corners() const { return attributes_.corners; }
    bool hasColours() const { return !attributes_.colours.empty(); }
    VoxelMaterial material(std::uint32_t voxel) const {
        return attributes_.voxelMaterials.empty() ? VoxelMaterial::Surface : VoxelMaterial(attributes_.voxelMaterials[voxel]);
    }
    /// Each setter takes the vector over; an empty one removes the attribute. Throws Error
    /// (naming the attribute and both lengths) when it is neither empty nor voxels().size()
    /// long; the octree is then unchanged.
    void setColours(std::vector<std::uint32_t> colours);
    void setVoxelValues(std::vector<float> values);
    void setBaked(std::vector<std::uint8_t> baked);
    void setVoxelMaterials(std::vector<std::uint8_t> materials);
    void setCorners(std::vector<std::uint64_t> corners);
    /// All of them at once, checked as the setters do (nothing is set when one is refused).
    void setAttributes(VoxelAttributes attributes);
    /// Moves the attributes out, leaving none: for an operation that edits them in place and
    /// hands them back with setAttributes (no copy of buffers that may be large).
    VoxelAttributes takeAttributes();

    // ---- metadata (provenance) --------------------------------------------------------------
    /// Every key and value (well-known keys: octree_key). An empty value is never stored.
    const OctreeMetadata& metadata() const { return metadata_; }
    /// The value of `key`, empty when it has none.
    const std::string& metadata(std::string_view key) const;
    /// Sets `key` to `value`; an empty value removes the key (absent and empty are one).
    void setMetadata(std::string_view key, std::string value);
    const std::string& fieldName() const { return metadata(octree_key::kFieldName); }
    const std::string& fieldUnits() const { return metadata(octree_key::kFieldUnits); }
    const std::string& source() const { return metadata(octree_key::kSource); }
    const std::string& crs() const { return metadata(octree_key::kCrs); }
    const std::string& valueName() const { return metadata(octree_key::kValueName); }
    const std::string& valueUnits() const { return metadata(octree_key::kValueUnits); }
    const std::string& valueStandardName() const { return metadata(octree_key::kValueStandardName); }

    /// An octree with this one's depth, cube, form, iso and metadata (provenance: field, source,
    /// crs, the voxel values' name and units) but no nodes, voxels or per-voxel attributes: the
    /// start of an operation that makes a new node pool over the same cube.
    Octree emptyCopy() const;
    /// A deep copy: emptyCopy() and every node, voxel and per-voxel buffer (normals, colours,
    /// values, materials, baked light) and the node summaries. The one way to copy an octree
    /// (it is move-only, since its buffers are large).
    Octree copy() const;

    std::size_t boundaryVoxels() const { return voxels_.size(); }
    /// Capacity in bytes of every buffer the octree owns.
    std::size_t bytes() const;
    double bytesPerVoxel() const { return voxels_.empty() ? 0.0 : double(bytes()) / double(voxels_.size()); }

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
    /// far: O(voxels) at worst; then kept for the same nodes, depth and form (renderers ask
    /// for it every frame). Thread-safe.
    void occupiedCells(ivec3& lo, ivec3& hi) const;
    /// World box of the occupied cells (the surface's bounding box).
    Box3 occupiedBounds() const;

    /// Calls f(cell, voxelIndex) for every entry of `voxels()` (depth-first order); a coarse
    /// leaf counts as the voxel at its lowest cell (forEachLeaf tells its size).
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
    /// the boundary voxels (index into `voxels()`), at 0 <= level < depth the nodes (index
    /// into `nodes()` and `summaries()`; interior terms included, their subtrees not entered).
    /// Nothing for a level outside [0, depth].
    template <class F>
    void forEachAtLevel(int level, F&& f) const;

    /// Depth-first over the non-empty children: enter(level, cell, slot, term) for each (its
    /// level and cell, its slot, whether its term bit is set); descends where it returns true.
    template <class F>
    void descend(F&& enter) const;

    // ---- per-node summaries -----------------------------------------------------------------
    /// Per node (same index as `nodes()`): empty until computeSummaries(), then one per node
    /// (setTopology drops them).
    const std::vector<NodeSummary>& summaries() const { return summaries_; }
    /// Fills `summaries()` bottom-up in O(nodes + voxels). Needed by --lod / --level.
    void computeSummaries();
    bool hasSummaries() const { return !nodes_.empty() && summaries_.size() == nodes_.size(); }
    /// Fraction of the node's cell-space volume (8^(depth-level) cells) that is boundary voxels.
    double occupancy(std::uint32_t node, int level) const {
        return double(summaries_[node].voxelCount) / std::ldexp(1.0, 3 * (depth - level));
    }

    /// Structural checks (masks, index ranges, every node reachable once) and the lengths of
    /// the attributes and summaries. Throws Error.
    void validate() const;

private:
    /// occupiedCells' answer and what it was found for (Octree.cpp).
    struct OccupiedCache;
    void forgetOccupiedCells();
    void findOccupiedCells(ivec3& lo, ivec3& hi) const;  ///< occupiedCells without the cache
    std::vector<OctreeNode> nodes_;
    std::vector<Voxel> voxels_;
    VoxelAttributes attributes_;
    std::vector<NodeSummary> summaries_;
    OctreeMetadata metadata_;
    /// Null in an octree moved from, and in one a moved-from octree was assigned to: they answer
    /// occupiedCells without keeping it.
    std::unique_ptr<OccupiedCache> occupied_;
};

template <class F>
void Octree::descend(F&& enter) const {
    if (nodes_.empty()) return;
    struct Item { std::uint32_t node; int level; ivec3 cell; };
    std::vector<Item> stack{{0u, 0, ivec3(0)}};
    while (!stack.empty()) {
        Item it = stack.back();
        stack.pop_back();
        const OctreeNode& n = nodes_[it.node];
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
    if (nodes_.empty() || level < 0 || level > depth) return;
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
        if (form == OctreeForm::Shell) f(cell << (depth - l), depth - l, nodes_[slot].firstChild);  // a coarse leaf
        return false;
    });
}

}  // namespace octrace
