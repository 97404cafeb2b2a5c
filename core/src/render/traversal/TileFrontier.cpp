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

}  // namespace octrace::detail
