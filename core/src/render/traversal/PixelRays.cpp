#include "render/traversal/PixelRays.h"

#include <algorithm>
#include <cmath>

namespace octrace::detail {

PixelRays::PixelRays(const Octree& tree, const Camera& camera, int surfaceLevel) : tree_(tree), gen_(camera) {
    const Box3 cube{tree.cubeOrigin, tree.cubeOrigin + dvec3(tree.cubeSide)};
    cubeSpans_ = outline(cube, camera.width, camera.height, &cubeInnerSpans_);
    ivec3 lo, hi;
    tree.occupiedCells(lo, hi);
    if (lo.x > hi.x) {
        surfaceSpans_.assign(std::size_t(std::max(camera.height, 0)), {1, 0});  // no surface at all
        return;
    }
    if (surfaceLevel >= 0 && surfaceLevel < tree.depth) {
        const int shift = tree.depth - surfaceLevel;
        lo = ivec3(lo.x >> shift, lo.y >> shift, lo.z >> shift) * (1 << shift);
        hi = (ivec3(hi.x >> shift, hi.y >> shift, hi.z >> shift) + 1) * (1 << shift) - 1;
    }
    const double v = tree.voxelSize();
    surfaceSpans_ = outline(Box3{tree.cubeOrigin + dvec3(lo) * v, tree.cubeOrigin + dvec3(hi + 1) * v}, camera.width,
                            camera.height);
}

PixelRays::Spans PixelRays::outline(const Box3& box, int width, int height, Spans* inner) const {
    Spans spans(std::size_t(std::max(height, 0)), {0, width - 1});
    if (inner) inner->assign(spans.size(), {1, 0});  // until the hull is known: none certain
    const double size = std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z});
    // The cube's corners in pixel coordinates.
    struct P {
        double x, y;
    };
    std::vector<P> pts;
    int behind = 0;
    for (int k = 0; k < 8; ++k) {
        const dvec3 c((k & 4) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 1) ? box.hi.z : box.lo.z);
        behind += glm::dot(c - gen_.eye(), gen_.back()) > 0.0;
    }
    if (behind == 8) {  // the whole cube behind the eye (or the orthographic view plane)
        std::fill(spans.begin(), spans.end(), std::pair<int, int>{1, 0});
        return spans;
    }
    for (int k = 0; k < 8; ++k) {
        const dvec3 corner((k & 4) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 1) ? box.hi.z : box.lo.z);
        const dvec3 rel = corner - gen_.eye();
        const double cx = glm::dot(rel, gen_.right()), cy = glm::dot(rel, gen_.up()), cz = glm::dot(rel, gen_.back());
        // A corner at or behind the eye plane: the outline is unbounded; keep every pixel.
        if (!gen_.orthographic() && !(cz < -1e-9 * size)) return spans;
        P p;
        gen_.toPixel(cx, cy, cz, p.x, p.y);
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) return spans;
        pts.push_back(p);
    }
    // Convex hull (monotone chain), counter-clockwise in pixel coordinates.
    std::sort(pts.begin(), pts.end(), [](const P& a, const P& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    auto cross = [](const P& o, const P& a, const P& b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); };
    std::vector<P> hull(16);
    std::size_t k = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        while (k >= 2 && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
        hull[k++] = pts[i];
    }
    for (std::size_t i = pts.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(hull[k - 2], hull[k - 1], pts[i]) <= 0) --k;
        hull[k++] = pts[i];
    }
    hull.resize(k > 1 ? k - 1 : k);
    // Per row, the hull's x extent over the band of pixel centres within one pixel of the row's
    // centre, widened by one more pixel: rounding can never exclude a pixel whose ray meets it.
    for (int y = 0; y < height; ++y) {
        const double b0 = y + 0.5 - 1.0, b1 = y + 0.5 + 1.0;
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (std::size_t i = 0; i < hull.size(); ++i) {
            const P& a = hull[i];
            const P& b = hull[(i + 1) % hull.size()];
            if (a.y >= b0 && a.y <= b1) {
                lo = std::min(lo, a.x);
                hi = std::max(hi, a.x);
            }
            for (double yb : {b0, b1})
                if ((a.y - yb) * (b.y - yb) < 0.0) {
                    const double x = a.x + (b.x - a.x) * (yb - a.y) / (b.y - a.y);
                    lo = std::min(lo, x);
                    hi = std::max(hi, x);
                }
        }
        if (!(lo <= hi)) {
            spans[std::size_t(y)] = {1, 0};  // the band misses the outline
            continue;
        }
        if (inner) {
            // The hull's extent on both edges of the band; the hull is convex, so every line of
            // the band holds the intersection of the two. A centre a further pixel inside it
            // is inside the hull by more than a pixel.
            double ilo = -std::numeric_limits<double>::infinity(), ihi = -ilo;
            for (double yb : {b0, b1}) {
                double l = std::numeric_limits<double>::infinity(), h = -l;
                for (std::size_t i = 0; i < hull.size(); ++i) {
                    const P& a = hull[i];
                    const P& b = hull[(i + 1) % hull.size()];
                    if (a.y == yb) {
                        l = std::min(l, a.x);
                        h = std::max(h, a.x);
                    }
                    if ((a.y - yb) * (b.y - yb) < 0.0) {
                        const double x = a.x + (b.x - a.x) * (yb - a.y) / (b.y - a.y);
                        l = std::min(l, x);
                        h = std::max(h, x);
                    }
                }
                ilo = std::max(ilo, l);
                ihi = std::min(ihi, h);
            }
            if (ilo <= ihi && std::isfinite(ilo) && std::isfinite(ihi)) {
                const double x0 = std::ceil(ilo - 0.5) + 1.0, x1 = std::floor(ihi - 0.5) - 1.0;
                if (x0 <= x1)
                    (*inner)[std::size_t(y)] = {int(std::clamp(x0, 0.0, double(width))),
                                                int(std::clamp(x1, -1.0, double(width - 1)))};
            }
        }
        // Pixel x has its centre at x + 0.5.
        const double x0 = std::floor(lo - 0.5) - 1.0, x1 = std::ceil(hi - 0.5) + 1.0;
        spans[std::size_t(y)] = {int(std::clamp(x0, -1.0, double(width))), int(std::clamp(x1, -1.0, double(width)))};
    }
    return spans;
}

}  // namespace octrace::detail
