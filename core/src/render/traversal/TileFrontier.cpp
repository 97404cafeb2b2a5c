// The exact per-tile frontier (docs/dev/tile-renderer.md, steps 1-4): moved unchanged from
// TileRenderer.cpp so that the exact trajectory-coherence variants can use it too.
#include "render/traversal/TileFrontier.h"

#include <limits>

namespace octrace::detail {
namespace {
constexpr int N = Octree::kIntBits;
}  // namespace

const ChildOrder& childOrder() {
    static const ChildOrder c;
    return c;
}

TileFrustum tileFrustum(const RayGenerator& gen, const ScreenSlopes& sl, int x0, int y0, int x1, int y1) {
    // Only what every frustum shares (a copy of the whole, reach included, is a string move).
    TileFrustum f;
    f.apex = sl.base.apex;
    f.pad = sl.base.pad;
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

ImageFrontier::ImageFrontier(const Octree& tree, const Camera& camera, const PixelRays& rays, int tileSize)
    : tree_(tree), gen_(camera), slopes_(tree, gen_, rays, camera.width, camera.height, true), width_(camera.width),
      height_(camera.height), tileSize_(std::max(tileSize, 1)), keepLevel_(tree.depth - 1) {
    const int T = tileSize_;
    tilesX_ = (width_ + T - 1) / T;
    const int tilesY = (height_ + T - 1) / T;
    groupsX_ = (tilesX_ + kGroup - 1) / kGroup;
    const int groupsY = (tilesY + kGroup - 1) / kGroup;
    // The tile renderer's sizes: the cap per tile, kGroup^2 times the cap per group.
    cap_ = frontierCap(T);
    tiles_.resize(std::size_t(tilesX_) * std::size_t(tilesY));
    groups_.resize(std::size_t(groupsX_) * std::size_t(groupsY));
    tileOnce_.reset(new std::once_flag[tiles_.size()]);
    groupOnce_.reset(new std::once_flag[groups_.size()]);
    signs_.resize(groups_.size());
    for (std::size_t g = 0; g < groups_.size(); ++g) {
        const int gx0 = int(g % std::size_t(groupsX_)) * kGroup * T, gy0 = int(g / std::size_t(groupsX_)) * kGroup * T;
        const int gx1 = std::min(gx0 + kGroup * T, width_), gy1 = std::min(gy0 + kGroup * T, height_);
        const dvec3 mid = gen_.direction((gx0 + gx1) / 2, (gy0 + gy1) / 2);
        signs_[g] = std::uint8_t((mid.x < 0.0 ? 4u : 0u) | (mid.y < 0.0 ? 2u : 0u) | (mid.z < 0.0 ? 1u : 0u));
    }
}

const std::vector<FrontierNode>& ImageFrontier::groupNodes(std::size_t g) const {
    std::call_once(groupOnce_[g], [&] {
        if (tree_.nodes().empty()) return;
        const int T = tileSize_;
        const int gx0 = int(g % std::size_t(groupsX_)) * kGroup * T, gy0 = int(g / std::size_t(groupsX_)) * kGroup * T;
        const int gx1 = std::min(gx0 + kGroup * T, width_), gy1 = std::min(gy0 + kGroup * T, height_);
        const std::vector<FrontierNode> root{{StartNode{}}};
        std::vector<FrontierNode> next;
        const TileFrustum gf = tileFrustum(gen_, slopes_, gx0, gy0, gx1, gy1);
        filterFrontier(gf, root, groups_[g], gx0, gy0, gx1, gy1);
        refineFrontier(tree_, gf, signs_[g], std::size_t(kGroup * kGroup) * cap_, keepLevel_, groups_[g], next);
        // The group's nodes' rectangles (every frustum has the same apex and pad), as the tile
        // renderer computes them: each tile leaves out those that miss it.
        for (FrontierNode& fn : groups_[g]) pixelRect(tree_, gen_, gf, fn, width_, height_);
    });
    return groups_[g];
}

const ImageFrontier::Tile& ImageFrontier::tile(int x, int y) const {
    const int tx = x / tileSize_, ty = y / tileSize_;
    const std::size_t t = std::size_t(ty) * std::size_t(tilesX_) + std::size_t(tx);
    std::call_once(tileOnce_[t], [&] {
        const std::size_t g = group(tx, ty);
        const std::vector<FrontierNode>& from = groupNodes(g);
        Tile& tl = tiles_[t];
        std::vector<FrontierNode>& list = tl.nodes;
        std::vector<FrontierNode> next;
        const int x0 = tx * tileSize_, y0 = ty * tileSize_;
        const int x1 = std::min(x0 + tileSize_, width_), y1 = std::min(y0 + tileSize_, height_);
        const TileFrustum fr = tileFrustum(gen_, slopes_, x0, y0, x1, y1);
        filterFrontier(fr, from, list, x0, y0, x1, y1);
        refineFrontier(tree_, fr, signs_[g], cap_, keepLevel_, list, next);
        // Step 4: the nodes whose rectangle misses the tile are dropped.
        std::size_t kept = 0;
        for (FrontierNode& fn : list) {
            if (!fn.rect) pixelRect(tree_, gen_, fr, fn, width_, height_);
            if (fn.x1 >= x0 && fn.x0 < x1 && fn.y1 >= y0 && fn.y0 < y1) list[kept++] = fn;
        }
        list.resize(kept);
        // Per pixel, the nodes whose rectangle holds it, as a bit mask over the list.
        tl.masked = list.size() <= 64 && tileSize_ <= 8;
        if (tl.masked) {
            tl.pixelNodes.assign(std::size_t(tileSize_ * tileSize_), 0);
            for (std::size_t i = 0; i < list.size(); ++i) {
                const FrontierNode& fn = list[i];
                for (int py = std::max(fn.y0, y0); py <= std::min(fn.y1, y1 - 1); ++py)
                    for (int px = std::max(fn.x0, x0); px <= std::min(fn.x1, x1 - 1); ++px)
                        tl.pixelNodes[std::size_t((py - y0) * tileSize_ + (px - x0))] |= std::uint64_t(1) << i;
            }
        }
    });
    return tiles_[t];
}

}  // namespace octrace::detail
