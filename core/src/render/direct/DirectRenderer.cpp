// The direct renderers: the octree drawn object-order, voxel by voxel, without rays through
// the hierarchy (paper A's comparison renderer, Table 1's last column).
//
// Visibility order. For a point eye, a child octant can hide another only if it lies on the
// eye's side of every plane through the node's centre that separates them; so the children
// sorted by how many of those planes put them away from the eye (0 = the octant holding the
// eye's side on all three axes) are in front-to-back order, and reversed in back-to-front
// order. An orthographic camera has its eye at infinity: the order comes from the viewing
// direction and is the same for every node.
//
// Footprint. Each boundary voxel covers exactly the pixels whose ray (the camera's ray of the
// pixel centre, as the ray casters trace it) meets its box: the cube's projected hexagon,
// found with a slab test over the pixels of the projected bounding rectangle. Every pixel of a
// voxel gets that voxel's shade (the shading is per voxel, see Shading.h). So a pixel shows
// the first voxel along its ray, as in ray casting, and depth is where the ray enters it.
//
// back-to-front (`direct`): painter's algorithm, every visible voxel overwrites what is behind.
// front-to-back (`direct-f2b`): a pixel is written once; a subtree whose projected rectangle is
// wholly covered already is skipped (occlusion culling the back-to-front order cannot do).
//
// Parallel over screen tiles: each tile traverses the tree on its own, culling nodes whose
// rectangle misses it, and writes only its own pixels, so the image is the same for any
// number of threads.
#include "render/direct/DirectRenderer.h"

#include "octrace/render/Lod.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace octrace::detail {
namespace {

constexpr int kTile = 64;

/// kOrder[near][k]: the k-th child in front-to-back order when `near` is the eye's octant.
struct ChildOrder {
    std::array<std::array<std::uint8_t, 8>, 8> v{};
    ChildOrder() {
        for (int near = 0; near < 8; ++near) {
            int k = 0;
            for (int bits = 0; bits <= 3; ++bits)
                for (int c = 0; c < 8; ++c)
                    if (__builtin_popcount(unsigned(c ^ near)) == bits) v[std::size_t(near)][std::size_t(k++)] = std::uint8_t(c);
        }
    }
};
const ChildOrder kOrder;

struct Rect {
    int x0, y0, x1, y1;  // inclusive pixel range; empty when x0 > x1 or y0 > y1
    bool empty() const { return x0 > x1 || y0 > y1; }
};

class TileRenderer {
public:
    TileRenderer(const Octree& tree, const Camera& camera, const Shader& shader, const LodCut& cut, bool f2b, Frame& frame,
                 int x0, int y0, int x1, int y1)
        : tree_(tree), gen_(camera), shader_(shader), cut_(cut), f2b_(f2b), frame_(frame),
          tx0_(x0), ty0_(y0), tx1_(x1), ty1_(y1), tw_(x1 - x0 + 1) {
        if (f2b_) covered_.assign(std::size_t(tw_) * std::size_t(y1 - y0 + 1), 0);
        for (int a = 0; a < 3; ++a) {
            axisR_[a] = gen_.right()[a];
            axisU_[a] = gen_.up()[a];
            axisB_[a] = gen_.back()[a];
        }
        if (gen_.orthographic()) {
            const dvec3 b = gen_.back();
            orthoNear_ = (b.x > 0 ? 4 : 0) | (b.y > 0 ? 2 : 0) | (b.z > 0 ? 1 : 0);
        }
        levelSide_.resize(std::size_t(tree.depth + 1));
        for (int l = 0; l <= tree.depth; ++l) levelSide_[std::size_t(l)] = tree.cubeSide / double(1u << l);
    }

    void run(RenderStats& st) {
        if (tree_.nodes().empty() || tree_.depth < 1) return;
        visit(0, 0, ivec3(0), st);
    }

private:
    /// The tile's per-pixel ray terms, computed at the first voxel drawn (most tiles of a
    /// typical view show only background and never need them).
    void prepareRays() {
        const std::size_t n = std::size_t(tw_) * std::size_t(ty1_ - ty0_ + 1);
        invDir_.resize(n);
        if (gen_.orthographic()) origin_.resize(n);
        for (int y = ty0_; y <= ty1_; ++y)
            for (int x = tx0_; x <= tx1_; ++x) {
                const std::size_t i = local(x, y);
                const dvec3 d = gen_.direction(x, y);
                invDir_[i] = dvec3(1.0 / d.x, 1.0 / d.y, 1.0 / d.z);  // +-inf for a zero component
                axisParallel_ = axisParallel_ || d.x == 0.0 || d.y == 0.0 || d.z == 0.0;
                if (gen_.orthographic()) origin_[i] = gen_.origin(x, y);
            }
    }

    std::size_t local(int x, int y) const { return std::size_t(y - ty0_) * std::size_t(tw_) + std::size_t(x - tx0_); }

    /// Pixels of the tile that the box's projection may cover; the whole tile when the box
    /// reaches behind a perspective eye; empty when it lies wholly behind the view.
    Rect project(const dvec3& lo, double side) const {
        const dvec3 rel = lo - gen_.eye();
        const double r0 = glm::dot(rel, gen_.right()), u0 = glm::dot(rel, gen_.up()), b0 = glm::dot(rel, gen_.back());
        double pxMin = std::numeric_limits<double>::infinity(), pxMax = -pxMin, pyMin = pxMin, pyMax = -pxMin;
        int behind = 0, straddles = 0;
        const double eps = 1e-9 * side;
        for (int k = 0; k < 8; ++k) {
            const double ox = (k & 4) ? side : 0.0, oy = (k & 2) ? side : 0.0, oz = (k & 1) ? side : 0.0;
            const double cx = r0 + ox * axisR_[0] + oy * axisR_[1] + oz * axisR_[2];
            const double cy = u0 + ox * axisU_[0] + oy * axisU_[1] + oz * axisU_[2];
            const double cz = b0 + ox * axisB_[0] + oy * axisB_[1] + oz * axisB_[2];
            if (cz >= 0.0) ++behind;
            if (!gen_.orthographic() && cz > -eps) {
                ++straddles;
                continue;
            }
            double px, py;
            gen_.toPixel(cx, cy, cz, px, py);
            pxMin = std::min(pxMin, px);
            pxMax = std::max(pxMax, px);
            pyMin = std::min(pyMin, py);
            pyMax = std::max(pyMax, py);
        }
        if (behind == 8) return {1, 1, 0, 0};
        if (straddles) return {tx0_, ty0_, tx1_, ty1_};
        // Pixel x is covered when its centre x + 0.5 lies in [pxMin, pxMax].
        Rect r;
        r.x0 = int(std::clamp(std::ceil(pxMin - 0.5), double(tx0_), double(tx1_) + 1.0));
        r.x1 = int(std::clamp(std::floor(pxMax - 0.5), double(tx0_) - 1.0, double(tx1_)));
        r.y0 = int(std::clamp(std::ceil(pyMin - 0.5), double(ty0_), double(ty1_) + 1.0));
        r.y1 = int(std::clamp(std::floor(pyMax - 0.5), double(ty0_) - 1.0, double(ty1_)));
        return r;
    }

    bool whollyCovered(const Rect& r) const {
        for (int y = r.y0; y <= r.y1; ++y)
            for (int x = r.x0; x <= r.x1; ++x)
                if (!covered_[local(x, y)]) return false;
        return true;
    }

    void visit(std::uint32_t nodeIndex, int level, const ivec3& cell, RenderStats& st) {
        ++st.nodesVisited;
        const OctreeNode& node = tree_.nodes()[nodeIndex];
        const double childSide = levelSide_[std::size_t(level + 1)];
        const dvec3 lo = tree_.cubeOrigin + dvec3(cell) * levelSide_[std::size_t(level)];
        int near = orthoNear_;
        if (!gen_.orthographic()) {
            const dvec3 c = lo + dvec3(childSide);
            const dvec3& e = gen_.eye();
            near = (e.x >= c.x ? 4 : 0) | (e.y >= c.y ? 2 : 0) | (e.z >= c.z ? 1 : 0);
        }
        const auto& order = kOrder.v[std::size_t(near)];
        for (int k = 0; k < 8; ++k) {
            const unsigned c = order[std::size_t(f2b_ ? k : 7 - k)];
            if (!(node.childMask & (1u << c))) continue;
            if (f2b_ && coveredCount_ == covered_.size()) return;
            const ivec3 childCell = cell * 2 + ivec3(int(c >> 2) & 1, int(c >> 1) & 1, int(c) & 1);
            const dvec3 childLo = tree_.cubeOrigin + dvec3(childCell) * childSide;
            const Rect r = project(childLo, childSide);
            if (r.empty()) continue;
            if (f2b_ && whollyCovered(r)) continue;
            const std::uint32_t slot = node.firstChild + childRank(node.childMask, c);
            if (level + 1 == tree_.depth) splat(slot, kNoHit, childCell, 0, childLo, childSide, r, st);
            else if (node.termMask & (1u << c)) {
                // A coarse leaf (shell form) is drawn as a solid cube of its level; an interior
                // term (volume form) is not drawn.
                if (tree_.form == OctreeForm::Shell)
                    splat(tree_.nodes()[slot].firstChild, kNoHit, childCell << (tree_.depth - level - 1), tree_.depth - level - 1,
                          childLo, childSide, r, st);
            }
            else if (cut_.stops(level + 1, childCell)) splat(tree_.summaries()[slot].firstVoxel, slot, childCell, 0, childLo, childSide, r, st);
            else visit(slot, level + 1, childCell, st);
        }
    }

    /// Writes the voxel (or a coarse leaf of side 2^leafShift voxels, or, multi-resolution,
    /// the inner node drawn whole) into every pixel of r whose ray meets its box.
    void splat(std::uint32_t voxel, std::uint32_t node, const ivec3& cell, int leafShift, const dvec3& lo, double side,
               const Rect& r, RenderStats& st) {
        const dvec3 hi = lo + dvec3(side);
        if (invDir_.empty()) prepareRays();
        const bool ortho = gen_.orthographic();
        // Perspective rays share the eye: the box's offsets from it are per voxel, and with no
        // axis-parallel ray in the tile the slab test needs no special case.
        const bool fast = !ortho && !axisParallel_;
        const dvec3 L = lo - gen_.eye(), H = hi - gen_.eye();
        bool shaded = false;
        vec4 colour{};
        const bool smooth = shader_.smooth().active() && node == kNoHit && leafShift == 0;
        for (int y = r.y0; y <= r.y1; ++y)
            for (int x = r.x0; x <= r.x1; ++x) {
                const std::size_t i = local(x, y);
                if (f2b_ && covered_[i]) continue;
                const dvec3& inv = invDir_[i];
                double tmin, tmax;
                if (fast) {
                    const double ax = L.x * inv.x, bx = H.x * inv.x, ay = L.y * inv.y, by = H.y * inv.y;
                    const double az = L.z * inv.z, bz = H.z * inv.z;
                    tmin = std::max({std::min(ax, bx), std::min(ay, by), std::min(az, bz)});
                    tmax = std::min({std::max(ax, bx), std::max(ay, by), std::max(az, bz)});
                } else {
                    const dvec3& o = ortho ? origin_[i] : gen_.eye();
                    tmin = -std::numeric_limits<double>::infinity();
                    tmax = std::numeric_limits<double>::infinity();
                    bool inside = true;
                    for (int a = 0; a < 3 && inside; ++a) {
                        if (std::isinf(inv[a])) {
                            inside = o[a] >= lo[a] && o[a] <= hi[a];
                            continue;
                        }
                        double t0 = (lo[a] - o[a]) * inv[a], t1 = (hi[a] - o[a]) * inv[a];
                        if (t0 > t1) std::swap(t0, t1);
                        tmin = std::max(tmin, t0);
                        tmax = std::min(tmax, t1);
                    }
                    if (!inside) continue;
                }
                if (tmin > tmax || tmax < 0.0) continue;
                const std::size_t p = frame_.pixel(x, y);
                if (smooth) {
                    // Smooth surfaces (SmoothSurface.h): the pixel shows the voxel only where its
                    // ray crosses the field's interpolant in it; else what lies behind stays.
                    TraversalHit h;
                    h.voxel = voxel;
                    h.cell = cell;
                    SmoothSurface::RayState ray{Ray{gen_.origin(x, y), glm::normalize(gen_.direction(x, y))}};
                    if (!shader_.smooth().test(ray, h)) continue;
                    writeSplat(p, i, shader_.shade(h, &st.secondaryRays), float(h.distance), voxel);
                    ++st.voxelsSplatted;
                    continue;
                }
                if (!shaded) {
                    colour = node == kNoHit ? shader_.shade(voxel, cell, leafShift, &st.secondaryRays) : shader_.shadeNode(node);
                    shaded = true;
                    ++st.voxelsSplatted;
                }
                writeSplat(p, i, colour, float(std::max(tmin, 0.0) * glm::length(gen_.direction(x, y))), voxel);
            }
    }

    void writeSplat(std::size_t p, std::size_t i, const vec4& colour, float depth, std::uint32_t voxel) {
        frame_.rgba[p] = colour;
        frame_.depth[p] = depth;
        frame_.hitId[p] = voxel;
        frame_.flags[p] = Frame::kSplatted;
        if (f2b_) {
            covered_[i] = 1;
            ++coveredCount_;
        }
    }

    const Octree& tree_;
    const RayGenerator gen_;
    const Shader& shader_;
    const LodCut& cut_;
    const bool f2b_;
    Frame& frame_;
    const int tx0_, ty0_, tx1_, ty1_, tw_;
    std::vector<dvec3> invDir_, origin_;
    std::vector<std::uint8_t> covered_;
    std::size_t coveredCount_ = 0;
    bool axisParallel_ = false;  // some ray of the tile has a zero direction component
    double axisR_[3], axisU_[3], axisB_[3];
    int orthoNear_ = 0;
    std::vector<double> levelSide_;
};

}  // namespace

std::string DirectRenderer::name() const { return frontToBack_ ? "direct-f2b" : "direct"; }

RenderStats DirectRenderer::render(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                                   Frame& frame) const {
    camera.validate();
    Timer timer;
    frame.resize(camera.width, camera.height);
    std::fill(frame.rgba.begin(), frame.rgba.end(), settings.background);
    const Shader shader(tree, camera, settings);
    const LodCut cut(tree, camera, settings.detail.lodPixels, settings.detail.level);
    const int tilesX = (camera.width + kTile - 1) / kTile, tilesY = (camera.height + kTile - 1) / kTile;
    std::vector<RenderStats> tileStats(std::size_t(tilesX) * std::size_t(tilesY));
    parallelFor(tileStats.size(), settings.threads, [&](std::size_t t) {
        const int x0 = int(t % std::size_t(tilesX)) * kTile, y0 = int(t / std::size_t(tilesX)) * kTile;
        const int x1 = std::min(x0 + kTile, camera.width) - 1, y1 = std::min(y0 + kTile, camera.height) - 1;
        TileRenderer tile(tree, camera, shader, cut, frontToBack_, frame, x0, y0, x1, y1);
        RenderStats& st = tileStats[t];
        tile.run(st);
        st.pixels = std::uint64_t(x1 - x0 + 1) * std::uint64_t(y1 - y0 + 1);
        for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) st.hits += frame.hitId[frame.pixel(x, y)] != kNoHit;
    });
    RenderStats total;
    total.renderer = name();
    for (const auto& s : tileStats) total.add(s);
    total.renderMs = timer.ms();
    return total;
}

}  // namespace octrace::detail
