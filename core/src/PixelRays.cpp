#include "PixelRays.h"

#include <algorithm>
#include <cmath>

namespace octrace::detail {

PixelRays::PixelRays(const Octree& tree, const Camera& camera)
    : tree_(tree), gen_(camera), spans_(std::size_t(std::max(camera.height, 0)), {0, camera.width - 1}) {
    // The cube's corners in pixel coordinates.
    struct P {
        double x, y;
    };
    std::vector<P> pts;
    int behind = 0;
    for (int k = 0; k < 8; ++k) {
        const dvec3 c = tree.cubeOrigin + tree.cubeSide * dvec3((k >> 2) & 1, (k >> 1) & 1, k & 1);
        behind += glm::dot(c - gen_.eye(), gen_.back()) > 0.0;
    }
    if (behind == 8) {  // the whole cube behind the eye (or the orthographic view plane)
        std::fill(spans_.begin(), spans_.end(), std::pair<int, int>{1, 0});
        return;
    }
    for (int k = 0; k < 8; ++k) {
        const dvec3 corner = tree.cubeOrigin + tree.cubeSide * dvec3((k >> 2) & 1, (k >> 1) & 1, k & 1);
        const dvec3 rel = corner - gen_.eye();
        const double cx = glm::dot(rel, gen_.right()), cy = glm::dot(rel, gen_.up()), cz = glm::dot(rel, gen_.back());
        // A corner at or behind the eye plane: the outline is unbounded; keep every pixel.
        if (!gen_.orthographic() && !(cz < -1e-9 * tree.cubeSide)) return;
        P p;
        gen_.toPixel(cx, cy, cz, p.x, p.y);
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) return;
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
    for (int y = 0; y < camera.height; ++y) {
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
            spans_[std::size_t(y)] = {1, 0};  // the band misses the outline
            continue;
        }
        // Pixel x has its centre at x + 0.5.
        const double x0 = std::floor(lo - 0.5) - 1.0, x1 = std::ceil(hi - 0.5) + 1.0;
        spans_[std::size_t(y)] = {int(std::clamp(x0, -1.0, double(camera.width))),
                                  int(std::clamp(x1, -1.0, double(camera.width)))};
    }
}

}  // namespace octrace::detail
