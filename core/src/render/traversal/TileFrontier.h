#pragma once
// Private to core: the exact per-tile frontier of the tile renderer (docs/dev/tile-renderer.md,
// whose numbered steps are cited below), shared with the exact trajectory-coherence variants
// (docs/dev/coherence.md), which use it to certify a start at the branch node.
#include "render/traversal/PixelRays.h"

#include "octrace/render/DiscreteTraversal.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

namespace octrace::detail {

/// A frontier node: an inner node of the tree that may hold a voxel some ray of the tile visits.
struct FrontierNode {
    StartNode start;
    int x0 = 0, x1 = 0, y0 = 0, y1 = 0;  ///< the pixels whose rays can visit a cell of the node (step 4)
    bool rect = false;                  ///< whether x0 .. y1 are computed
    bool projected = false;             ///< whether they bound the projection (not every pixel for want of one)
    /// Whether some pixel of columns x0 .. x1-1 and rows y0 .. y1-1 lies in the rectangle (a
    /// node projected between pixel centres has an empty one: no pixel's ray visits it).
    bool rectMeets(int x0, int y0, int x1, int y1) const {
        // Both tests, without a branch between them.
        return unsigned(std::max(this->x0, x0) <= std::min(this->x1, x1 - 1)) & unsigned(std::max(this->y0, y0) <= std::min(this->y1, y1 - 1));
    }
    /// Unused: with it every byte of the 40 is a member, so a copy moves the node in pieces at
    /// 0, 16 and 32 (without it, GCC's last piece overlapped the second, and reading a node just
    /// copied stalled on store forwarding).
    std::uint16_t spare = 0;
};

/// children sorted by popcount(c ^ s) per sign pattern s: front to back for every ray of
/// that sign pattern (step 3).
struct ChildOrder {
    std::array<std::array<std::uint8_t, 8>, 8> order{};
    ChildOrder() {
        for (unsigned s = 0; s < 8; ++s) {
            std::array<std::uint8_t, 8> o{0, 1, 2, 3, 4, 5, 6, 7};
            std::stable_sort(o.begin(), o.end(),
                             [s](std::uint8_t a, std::uint8_t b) { return std::popcount(a ^ s) < std::popcount(b ^ s); });
            order[s] = o;
        }
    }
};
/// children sorted by popcount(c ^ s) per sign pattern s (ChildOrder::order).
const ChildOrder& childOrder();

/// The union of a tile's rays as five half-spaces g_i . (p - apex) + h_i >= 0 in octree space
/// (step 1), and the conservative test of a node box against it (step 2).
struct TileFrustum {
    dvec3 apex;
    std::array<dvec3, 5> g;
    std::array<double, 5> h{};
    double pad = 0.0;  ///< how far every box is widened on each side: 2 x the quantization bound
    // Per form and level: h_i + |g_i|_1 (half side + pad), the most the form gains from a box's
    // centre to a corner of the widened box. Filled by prepare() (left uninitialized before: a
    // frustum is made per tile).
    std::array<std::array<double, Octree::kMaxDepth + 1>, 5> reach;

    void prepare() {
        for (int i = 0; i < 5; ++i) {
            const dvec3& gi = g[std::size_t(i)];
            for (int level = 0; level <= Octree::kMaxDepth; ++level)
                reach[std::size_t(i)][std::size_t(level)] =
                    h[std::size_t(i)] + (std::abs(gi.x) + std::abs(gi.y) + std::abs(gi.z)) * (double(1 << (Octree::kIntBits - level)) * 0.5 + pad);
        }
    }

    /// Bit c: meets(child c of the node, level + 1) (child c: cell * 2 + (c >> 2, c >> 1 & 1,
    /// c & 1)), the eight at once in AVX-512 where the processor has it, bit for bit the same.
    unsigned meetsChildren(const ivec3& cell, int level) const;

    /// False only if no point of the box widened by `pad` satisfies all five: then no
    /// quantized ray of the tile visits a cell of the box.
    bool meets(const ivec3& cell, int level) const {
        const double side = double(1 << (Octree::kIntBits - level));
        const dvec3 c = (dvec3(cell) + 0.5) * side - apex;
        for (std::size_t i = 0; i < 5; ++i)
            if (glm::dot(g[i], c) + reach[i][std::size_t(level)] < 0.0) return false;
        return true;
    }
};

/// Per frame: what every tile's frustum shares (apex, pad) and the slopes (perspective) or
/// offsets (orthographic) of every column and row of the image, computed once, at row 0 and
/// column 0 (the value of a column computed at another row differs by a few units in the last
/// place, which the pad's 1e-9 far covers: step 2).
struct ScreenSlopes {
    TileFrustum base;
    std::vector<double> x, y;
    ScreenSlopes(const Octree& tree, const RayGenerator& gen, const PixelRays& rays, int width, int height, bool widen) {
        const dvec3 right = gen.right(), up = gen.up(), back = gen.back();
        base.apex = tree.toOctreeSpace(gen.eye());
        x.resize(std::size_t(width));
        y.resize(std::size_t(height));
        for (int i = 0; i < width; ++i)
            x[std::size_t(i)] = gen.orthographic() ? glm::dot(rays.originOS(i, 0) - base.apex, right)
                                                   : glm::dot(gen.direction(i, 0), right) / -glm::dot(gen.direction(i, 0), back);
        for (int j = 0; j < height; ++j)
            y[std::size_t(j)] = gen.orthographic() ? glm::dot(rays.originOS(0, j) - base.apex, up)
                                                   : glm::dot(gen.direction(0, j), up) / -glm::dot(gen.direction(0, j), back);
        // Step 2: a quantized ray's points lie within 2^-11 lattice units of its exact ray (or of
        // its origin); the directions and the forms above carry rounding errors relative to the
        // distances involved, far below 1e-9 of the farthest point of the cube from the apex.
        const double far = glm::length(base.apex - dvec3(0.5 * std::ldexp(1.0, Octree::kIntBits))) + std::ldexp(1.0, Octree::kIntBits);
        base.pad = widen ? 2.0 * (std::ldexp(1.0, -10) + 1e-9 * far) : 0.0;
    }
};

/// Tiles per side of a group: a group's frontier (step 3) is where each of its tiles' starts.
constexpr int kTileGroup = 4;

/// The most nodes a tile's frontier keeps (step 3), for tiles of `tileSize` pixels a side (a group
/// of kTileGroup x kTileGroup tiles keeps kTileGroup^2 times as many): enough to cut the empty space out, few
/// enough that the rays do not test too many boxes. T^2/8 for the default 8 (the packets of step 6
/// walk a node's subtree for several rays at once, so coarser nodes cost less than when each ray
/// walked them alone: CT skin and the molecule drew faster with 8 nodes than with 16).
inline std::size_t frontierCap(int tileSize) { return std::size_t(std::max(8, tileSize * tileSize / 8)); }

TileFrustum tileFrustum(const RayGenerator& gen, const ScreenSlopes& sl, int x0, int y0, int x1, int y1);

/// Step 3: the tile's frontier, front to back for sign pattern s: from `list` (the root, or the
/// frontier of a larger tile holding this one, filtered by this tile's frustum), each node
/// replaced by its non-empty children that meet the frustum (level by level), as long as the
/// list stays within `cap` nodes; nodes at depth-1 and nodes with a coarse leaf stay whole.
void refineFrontier(const Octree& tree, const TileFrustum& f, unsigned s, std::size_t cap, int keepLevel,
                    std::vector<FrontierNode>& list, std::vector<FrontierNode>& next);

/// Step 4: the pixels of the image whose exact rays meet the node's box widened by the pad: the
/// bounding rectangle of its corners' projections, a hundredth of a pixel wider; every pixel
/// when a corner is not in front of a perspective eye (or a projection is out of range).
/// The corners are projected eight at once in AVX-512 where the processor has it (bit for bit
/// the scalar code, which `scalar` forces: for tests).
void pixelRect(const Octree& tree, const RayGenerator& gen, const TileFrustum& f, FrontierNode& fn, int w, int h,
               bool scalar = false);

/// The nodes of `from` (in order) that may hold a cell some ray of the tile x0 .. x1-1, y0 .. y1-1
/// visits, into `list`: a node whose pixel rectangle is known is kept when the rectangle meets
/// the tile (step 4; the frustum test would add nothing to a rectangle bounding the node's
/// projection), any other when it meets the frustum `f` (step 2).
void filterFrontier(const TileFrustum& f, const std::vector<FrontierNode>& from, std::vector<FrontierNode>& list, int x0,
                    int y0, int x1, int y1);

/// Steps 3 and 4 for the tile x0 .. x1-1, y0 .. y1-1 of a w x h image with frustum `f`: `from`
/// (its group's frontier, with rectangles) filtered, refined for sign pattern s within `cap`,
/// every node's rectangle computed, and the nodes whose rectangle misses the tile dropped, into
/// `list` (`next`: scratch). What the tile renderer and ImageFrontier both build per tile.
void tileFrontier(const Octree& tree, const RayGenerator& gen, const TileFrustum& f, const std::vector<FrontierNode>& from,
                  unsigned s, std::size_t cap, int keepLevel, int x0, int y0, int x1, int y1, int w, int h,
                  std::vector<FrontierNode>& list, std::vector<FrontierNode>& next);

/// Every tile's frontier for one frame (steps 1-4 as the tile renderer builds them: tiles of
/// `tileSize` pixels in groups of 4 x 4, each group's frontier refined for each of its tiles,
/// nodes whose pixel rectangle misses the tile dropped), each built the first time it is asked
/// for (a tile no ray asks about costs nothing) and then kept for the frame. What the exact
/// trajectory-coherence variants read to certify a start (docs/dev/coherence.md). Cover and
/// order (step 3) hold for each tile's list and those of the tile's rays whose sign pattern is
/// sign(x, y). Thread-safe (a list is built once, under std::call_once; its content does not
/// depend on which thread builds it). Keeps a reference to `tree`. `tileSize` is a power of two
/// (a pixel's tile by shifts: the divisions took a tenth of a traced pixel's time).
class ImageFrontier {
public:
    ImageFrontier(const Octree& tree, const Camera& camera, const PixelRays& rays, int tileSize);
    /// The frontier of the tile holding pixel (x, y), front to back for sign(x, y); a pixel
    /// outside a node's rectangle (x0..x1, y0..y1) visits no cell of it.
    const std::vector<FrontierNode>& nodes(int x, int y) const { return tile(x, y).nodes; }
    /// Calls f(node) for the nodes of nodes(x, y) whose rectangle holds pixel (x, y), in list
    /// order, until f returns false; false if it did.
    template <class F>
    bool forEachNode(int x, int y, F&& f) const {
        const Tile& t = tile(x, y);
        if (t.masked) {
            // Bit i of the pixel's mask: node i's rectangle holds the pixel.
            const std::size_t bit = std::size_t(((y & tileMask_) << tileShift_) + (x & tileMask_));
            for (std::uint64_t m = t.pixelNodes[bit]; m; m &= m - 1)
                if (!f(t.nodes[std::size_t(std::countr_zero(m))])) return false;
            return true;
        }
        for (const FrontierNode& fn : t.nodes)
            if (x >= fn.x0 && x <= fn.x1 && y >= fn.y0 && y <= fn.y1 && !f(fn)) return false;
        return true;
    }
    /// The sign pattern that orders that tile's list (its group's middle ray's).
    unsigned sign(int x, int y) const { return signs_[group(x >> tileShift_, y >> tileShift_)]; }

private:
    static constexpr int kGroup = kTileGroup;
    std::size_t group(int tx, int ty) const {
        return std::size_t(ty / kGroup) * std::size_t(groupsX_) + std::size_t(tx / kGroup);
    }
    const std::vector<FrontierNode>& groupNodes(std::size_t g) const;
    struct Tile {
        std::vector<FrontierNode> nodes;
        bool masked = false;  ///< at most 64 nodes and 64 pixels: pixelNodes holds, per pixel, its nodes
        std::vector<std::uint64_t> pixelNodes;
    };
    const Tile& tile(int x, int y) const;

    const Octree& tree_;
    RayGenerator gen_;
    ScreenSlopes slopes_;
    int width_, height_, tileSize_, tileShift_, tileMask_, tilesX_, groupsX_, keepLevel_;
    std::size_t cap_;
    std::vector<std::uint8_t> signs_;  // per group
    mutable std::vector<Tile> tiles_;
    mutable std::vector<std::vector<FrontierNode>> groups_;
    mutable std::unique_ptr<std::once_flag[]> tileOnce_, groupOnce_;
};

}  // namespace octrace::detail
