// The tile renderer: an exact conservative pre-pass per screen tile, then each ray traced from
// the tile's frontier nodes instead of the root. Exactness argument: docs/dev/tile-renderer.md
// (the numbered steps there are cited below).
#include "render/traversal/TileRenderer.h"
#include "render/PerPixel.h"
#include "render/traversal/PixelRays.h"

#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/Lod.h"
#include "octrace/render/Shading.h"
#include "octrace/render/SmoothSurface.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <vector>

namespace octrace::detail {
namespace {

constexpr int N = Octree::kIntBits;

/// A frontier node: an inner node of the tree that may hold a voxel some ray of the tile visits.
struct FrontierNode {
    StartNode start;
    int x0 = 0, x1 = 0, y0 = 0, y1 = 0;  ///< the pixels whose rays can visit a cell of the node (step 4)
    bool rect = false;                  ///< whether x0 .. y1 are computed
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
const ChildOrder& childOrder() {
    static const ChildOrder c;
    return c;
}

/// The union of a tile's rays as five half-spaces g_i . (p - apex) + h_i >= 0 in octree space
/// (step 1), and the conservative test of a node box against it (step 2).
struct TileFrustum {
    dvec3 apex;
    std::array<dvec3, 5> g;
    std::array<double, 5> h{};
    double pad = 0.0;  ///< how far every box is widened on each side: 2 x the quantization bound
    // Per form and level: h_i + |g_i|_1 (half side + pad), the most the form gains from a box's
    // centre to a corner of the widened box.
    std::array<std::array<double, Octree::kMaxDepth + 1>, 5> reach{};

    void prepare() {
        for (int i = 0; i < 5; ++i) {
            const dvec3& gi = g[std::size_t(i)];
            for (int level = 0; level <= Octree::kMaxDepth; ++level)
                reach[std::size_t(i)][std::size_t(level)] =
                    h[std::size_t(i)] + (std::abs(gi.x) + std::abs(gi.y) + std::abs(gi.z)) * (double(1 << (N - level)) * 0.5 + pad);
        }
    }

    /// False only if no point of the box widened by `pad` satisfies all five: then no
    /// quantized ray of the tile visits a cell of the box.
    bool meets(const ivec3& cell, int level) const {
        const double side = double(1 << (N - level));
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
        const double far = glm::length(base.apex - dvec3(0.5 * std::ldexp(1.0, N))) + std::ldexp(1.0, N);
        base.pad = widen ? 2.0 * (std::ldexp(1.0, -10) + 1e-9 * far) : 0.0;
    }
};

TileFrustum tileFrustum(const RayGenerator& gen, const ScreenSlopes& sl, int x0, int y0, int x1, int y1) {
    TileFrustum f = sl.base;
    const dvec3 right = gen.right(), up = gen.up(), back = gen.back();
    // The extent of the tile's pixels across right and up: per unit of depth (perspective: the
    // directions' slopes) or in octree units (orthographic: the origins' offsets), over every
    // row and column of the tile (the computed values, not an interpolation of the corners).
    const auto [xl, xh] = std::minmax_element(sl.x.begin() + x0, sl.x.begin() + x1);
    const auto [yl, yh] = std::minmax_element(sl.y.begin() + y0, sl.y.begin() + y1);
    if (gen.orthographic()) {
        f.g = {right, -right, up, -up, -back};
        f.h = {-*xl, *xh, -*yl, *yh, 0.0};
    } else {
        f.g = {right + *xl * back, -right - *xh * back, up + *yl * back, -up - *yh * back, -back};
    }
    f.prepare();
    return f;
}

/// Step 3: the tile's frontier, front to back for sign pattern s: from `list` (the root, or the
/// frontier of a larger tile holding this one, filtered by this tile's frustum), each node
/// replaced by its non-empty children that meet the frustum (level by level), as long as the
/// list stays within `cap` nodes; nodes at depth-1 and nodes with a coarse leaf stay whole.
void refineFrontier(const Octree& tree, const TileFrustum& f, unsigned s, std::size_t cap, int keepLevel,
                    std::vector<FrontierNode>& list, std::vector<FrontierNode>& next) {
    if (list.empty()) return;
    const auto& order = childOrder().order[s];
    const bool shell = tree.form == OctreeForm::Shell;
    for (;;) {
        next.clear();
        bool refined = false;
        for (const FrontierNode& fn : list) {
            const OctreeNode& nd = tree.nodes()[fn.start.node];
            if (fn.start.level >= keepLevel || (shell && (nd.termMask & nd.childMask))) {
                next.push_back(fn);
                continue;
            }
            refined = true;
            for (unsigned c : order) {
                if (!(nd.childMask & (1u << c)) || (nd.termMask & (1u << c))) continue;  // empty, or an interior term (volume form)
                const ivec3 cell = fn.start.cell * 2 + ivec3(int(c >> 2), int((c >> 1) & 1), int(c & 1));
                if (f.meets(cell, fn.start.level + 1))
                    next.push_back({{nd.firstChild + childRank(nd.childMask, c), fn.start.level + 1, cell}});
            }
            if (next.size() > cap) return;  // keep the coarser list
        }
        list.swap(next);
        if (!refined || list.empty()) return;
    }
}

/// Step 4: the pixels of the image whose exact rays meet the node's box widened by the pad: the
/// bounding rectangle of its corners' projections, a hundredth of a pixel wider; every pixel
/// when a corner is not in front of a perspective eye (or a projection is out of range).
void pixelRect(const Octree& tree, const RayGenerator& gen, const TileFrustum& f, FrontierNode& fn, int w, int h) {
    fn.rect = true;
    const double side = std::ldexp(1.0, N - fn.start.level), k = tree.cubeSide / std::ldexp(1.0, N);
    const dvec3 lo = dvec3(fn.start.cell) * side - dvec3(f.pad) - f.apex;
    const double s = side + 2.0 * f.pad;
    double xl = std::numeric_limits<double>::infinity(), xh = -xl, yl = xl, yh = -xl;
    bool all = false;
    for (int c = 0; c < 8 && !all; ++c) {
        const dvec3 rel = (lo + dvec3((c & 4) ? s : 0.0, (c & 2) ? s : 0.0, (c & 1) ? s : 0.0)) * k;
        const double cx = glm::dot(rel, gen.right()), cy = glm::dot(rel, gen.up()), cz = glm::dot(rel, gen.back());
        if (!gen.orthographic() && !(cz < -1e-9 * glm::length(rel))) {
            all = true;
            break;
        }
        double px, py;
        gen.toPixel(cx, cy, cz, px, py);
        if (!(std::abs(px) < 1e7 && std::abs(py) < 1e7)) all = true;
        xl = std::min(xl, px);
        xh = std::max(xh, px);
        yl = std::min(yl, py);
        yh = std::max(yh, py);
    }
    if (all) {
        fn.x0 = fn.y0 = 0;
        fn.x1 = w - 1;
        fn.y1 = h - 1;
        return;
    }
    // Pixel x has its centre at x + 0.5.
    constexpr double m = 0.01;
    fn.x0 = int(std::max(std::ceil(xl - m - 0.5), -1.0));
    fn.x1 = int(std::min(std::floor(xh + m - 0.5), double(w)));
    fn.y0 = int(std::max(std::ceil(yl - m - 0.5), -1.0));
    fn.y1 = int(std::min(std::floor(yh + m - 0.5), double(h)));
}

}  // namespace

/// Pixels x0 .. x1-1 of row y as background, as writePixelHit writes a miss, counting the rays
/// that meet the cube (certain inside the cube's inner outline, quantized between it and the
/// outline, none outside).
void fillBackground(Frame& frame, const PixelRays& rays, const RenderSettings& settings, int y, int x0, int x1,
                    RenderStats& st) {
    const std::size_t p = frame.pixel(x0, y), n = std::size_t(x1 - x0);
    std::fill_n(frame.flags.data() + p, n, std::uint8_t(Frame::kTraced));
    std::fill_n(frame.rgba.data() + p, n, settings.background);
    std::fill_n(frame.depth.data() + p, n, std::numeric_limits<float>::infinity());
    std::fill_n(frame.hitId.data() + p, n, kNoHit);
    st.pixels += n;
    st.raysFull += n;
    const auto [innerLo, innerHi] = rays.cubeInnerSpan(y);
    const auto [cubeLo, cubeHi] = rays.cubeSpan(y);
    for (int x = std::max(x0, cubeLo); x < x1 && x <= cubeHi; ++x)
        if ((x >= innerLo && x <= innerHi) || rays.meetsCube(x, y)) ++st.rays;
}

/// The nodes of `from` (in order) that meet the frustum `f` of the tile x0 .. x1-1, y0 .. y1-1,
/// into `list`; a node whose pixel rectangle is known and misses the tile is left out at once
/// (step 4: no ray of the tile visits a cell of it).
void filterFrontier(const TileFrustum& f, const std::vector<FrontierNode>& from, std::vector<FrontierNode>& list, int x0,
                    int y0, int x1, int y1) {
    list.clear();
    for (const FrontierNode& fn : from) {
        if (fn.rect && !(fn.x1 >= x0 && fn.x0 < x1 && fn.y1 >= y0 && fn.y0 < y1)) continue;
        if (f.meets(fn.start.cell, fn.start.level)) list.push_back(fn);
    }
}

RenderStats TileRenderer::render(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                                 Frame& frame) const {
    // A multi-resolution cut (--lod, --level) draws nodes whole: the frontier stays above the
    // coarsest level the cut can stop at, and the traversals from it honour the cut.
    const LodCut cut(tree, camera, settings.detail.lodPixels, settings.detail.level);
    const LodCut* cutp = cut.active() ? &cut : nullptr;
    camera.validate();
    Timer timer;
    frame.reshape(camera.width, camera.height);  // every pixel is written below
    const Shader shader(tree, camera, settings);
    const SmoothSurface& smooth = shader.smooth();
    const PixelRays rays(tree, camera, cut.coarsestLevel());
    const RayGenerator gen(camera);
    const ScreenSlopes slopes(tree, gen, rays, camera.width, camera.height, widen_);
    const int T = std::max(settings.tileSize, 1);
    const int tilesX = (camera.width + T - 1) / T, tilesY = (camera.height + T - 1) / T;
    // Frontier size: enough nodes to cut the empty space out, few enough that a ray that
    // misses them all does not test too many boxes.
    const std::size_t cap = std::size_t(std::max(8, T * T / 4));
    // Nodes at this level stay whole: their children are voxels, or nodes a cut may draw whole.
    const int keepLevel = std::min(tree.depth, cut.coarsestLevel()) - 1;
    std::vector<RenderStats> tileStats(std::size_t(tilesX) * std::size_t(tilesY));
    // Tiles in groups of G x G: the group's frontier (a larger cap) is where each tile's
    // refinement starts, so the coarse levels are walked once per group.
    constexpr int G = 4;
    const int groupsX = (tilesX + G - 1) / G, groupsY = (tilesY + G - 1) / G;
    const std::vector<FrontierNode> root{{StartNode{}}};
    parallelFor(std::size_t(groupsX) * std::size_t(groupsY), settings.threads, [&](std::size_t g) {
        std::vector<FrontierNode> group, list, next;
        std::vector<StartNode> starts;
        std::vector<std::uint64_t> colMask, rowMask;
        const int gx = int(g % std::size_t(groupsX)), gy = int(g / std::size_t(groupsX));
        const int gx0 = gx * G * T, gy0 = gy * G * T;
        const int gx1 = std::min(gx0 + G * T, camera.width), gy1 = std::min(gy0 + G * T, camera.height);
        // The sign pattern of the group's middle ray orders the frontiers.
        const dvec3 mid = gen.direction((gx0 + gx1) / 2, (gy0 + gy1) / 2);
        const unsigned s = (mid.x < 0.0 ? 4u : 0u) | (mid.y < 0.0 ? 2u : 0u) | (mid.z < 0.0 ? 1u : 0u);
        if (!tree.nodes().empty()) {
            const TileFrustum gf = tileFrustum(gen, slopes, gx0, gy0, gx1, gy1);
            filterFrontier(gf, root, group, gx0, gy0, gx1, gy1);
            refineFrontier(tree, gf, s, G * G * cap, keepLevel, group, next);
            // The group's nodes' rectangles (every frustum has the same apex and pad), so that
            // each tile leaves out the nodes whose rectangle misses it before the frustum test.
            for (FrontierNode& fn : group) pixelRect(tree, gen, gf, fn, camera.width, camera.height);
        }
        for (int ty = gy * G; ty < std::min((gy + 1) * G, tilesY); ++ty)
            for (int tx = gx * G; tx < std::min((gx + 1) * G, tilesX); ++tx) {
            RenderStats& st = tileStats[std::size_t(ty) * std::size_t(tilesX) + std::size_t(tx)];
            TraversalCounters counters;
            const int x0 = tx * T, y0 = ty * T;
            const int x1 = std::min(x0 + T, camera.width), y1 = std::min(y0 + T, camera.height);
            const TileFrustum fr = tileFrustum(gen, slopes, x0, y0, x1, y1);
            filterFrontier(fr, group, list, x0, y0, x1, y1);
            refineFrontier(tree, fr, s, cap, keepLevel, list, next);
            // Step 4: the nodes whose rectangle misses the tile are dropped.
            std::size_t kept = 0;
            for (FrontierNode& fn : list) {
                if (!fn.rect) pixelRect(tree, gen, fr, fn, camera.width, camera.height);
                if (fn.x1 >= x0 && fn.x0 < x1 && fn.y1 >= y0 && fn.y0 < y1) list[kept++] = fn;
            }
            list.resize(kept);
            if (starts.size() < kept) starts.resize(kept);
            if (list.empty()) {
                // Step 5: no ray of the tile visits a boundary voxel.
                for (int y = y0; y < y1; ++y) fillBackground(frame, rays, settings, y, x0, x1, st);
                st.nodesVisited = counters.nodes;
                continue;
            }
            // Step 4 per pixel: bit i of colMask[x - x0] & rowMask[y - y0] says whether the
            // pixel lies in node i's rectangle (lists of up to 64 nodes; longer ones test each).
            const bool masked = kept <= 64;
            if (masked) {
                colMask.assign(std::size_t(x1 - x0), 0);
                rowMask.assign(std::size_t(y1 - y0), 0);
                for (std::size_t i = 0; i < kept; ++i) {
                    const FrontierNode& fn = list[i];
                    const std::uint64_t bit = std::uint64_t(1) << i;
                    for (int x = std::max(fn.x0, x0); x <= std::min(fn.x1, x1 - 1); ++x) colMask[std::size_t(x - x0)] |= bit;
                    for (int y = std::max(fn.y0, y0); y <= std::min(fn.y1, y1 - 1); ++y) rowMask[std::size_t(y - y0)] |= bit;
                }
            }
            for (int y = y0; y < y1; ++y)
                for (int x = x0; x < x1; ++x) {
                    const dvec3 dir = gen.direction(x, y);
                    TraversalHit hit;
                    const std::uint64_t mask = masked ? colMask[std::size_t(x - x0)] & rowMask[std::size_t(y - y0)] : ~std::uint64_t(0);
                    if (!rays.mayHitSurface(x, y) || mask == 0) {
                        // Step 5: nothing the ray can visit holds a boundary voxel (outside the
                        // surface's outline, or outside every frontier node's rectangle).
                        if (rays.mayMeetCube(x, y) && rays.meetsCube(x, y)) ++st.rays;
                        ++st.raysFull;
                    } else {
                        const QuantizedRay q = rays.quantized(x, y, dir);
                        if (q.meetsCube) ++st.rays;
                        // Smooth surfaces: the interpolant's test runs inside the traversal, on
                        // the boundary voxels in the ray's visiting order (the same as full's,
                        // by cover and order), instead of proposing the first and starting over
                        // from the root when it is passed (writePixelHit then keeps the hit).
                        SmoothSurface::RayState sray;
                        VoxelFilter filter;
                        if (smooth.active()) {
                            sray.world = rays.world(x, y, dir);
                            filter = smooth.filter(sray);
                        }
                        const VoxelFilter* fp = smooth.active() ? &filter : nullptr;
                        if (q.sign != s) {
                            // Another sign pattern: the frontier's order may not be this ray's.
                            ++st.raysFull;
                            hit = traverseDiscrete(tree, q, counters, cutp, fp);
                        } else {
                            ++st.raysCommonPath;
                            std::size_t n = 0;
                            if (masked) {
                                for (std::uint64_t m = mask; m; m &= m - 1) starts[n++] = list[std::size_t(std::countr_zero(m))].start;
                            } else {
                                for (const FrontierNode& fn : list)
                                    if (x >= fn.x0 && x <= fn.x1 && y >= fn.y0 && y <= fn.y1) starts[n++] = fn.start;
                            }
                            hit = traverseFromNodes(tree, q, starts.data(), n, counters, fp, cutp);
                        }
                    }
                    writePixelHit(frame, x, y, hit, shader, rays, dir, settings, st, counters, cutp);
                }
            st.nodesVisited = counters.nodes;
        }
    });
    return RenderStats::total(name(), tileStats, timer.ms());
}

}  // namespace octrace::detail
