// The exact per-tile frontier (docs/dev/tile-renderer.md, steps 1-4): moved unchanged from
// TileRenderer.cpp so that the exact trajectory-coherence variants can use it too.
#include "render/traversal/TileFrontier.h"

#include <bit>
#include <limits>
#include <stdexcept>

#if defined(__x86_64__) && defined(__GNUC__)
// GCC 12's AVX-512 intrinsics pass an undefined register through (_mm512_undefined_pd) where
// all lanes are written; inlined into the reductions below it reports that register as "may be
// used uninitialized" at the header's line, where only a pragma around the header reaches it.
#if defined(__clang__)
#include <immintrin.h>
#else
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif
#define OCTRACE_FRONTIER_AVX512 1
#endif

namespace octrace::detail {
namespace {
constexpr int N = Octree::kIntBits;

/// A node box's corners in camera coordinates (along right, up, back from the apex): corner c
/// is c0 + (c & 4 ? ex : 0) + (c & 2 ? ey : 0) + (c & 1 ? ez : 0), summed in that order.
struct BoxCorners {
    dvec3 c0, ex, ey, ez;
};

/// The bounding rectangle [xl, xh] x [yl, yh] of the corners' projections in continuous pixel
/// coordinates (RayGenerator::toPixel's); false when a corner is not strictly in front of a
/// perspective eye (back below -1e-9 of its distance) or projects beyond 10^7 pixels.
bool cornerBounds(const RayGenerator& gen, const BoxCorners& b, double& xl, double& xh, double& yl, double& yh) {
    const bool ortho = gen.orthographic();
    double x0, y0, sx, sy;
    gen.pixelTerms(x0, y0, sx, sy);
    xl = yl = std::numeric_limits<double>::infinity();
    xh = yh = -xl;
    for (int c = 0; c < 8; ++c) {
        const dvec3 v = b.c0 + ((c & 4) ? b.ex : dvec3(0.0)) + ((c & 2) ? b.ey : dvec3(0.0)) + ((c & 1) ? b.ez : dvec3(0.0));
        double cx = v.x, cy = v.y;
        if (!ortho) {
            if (!(v.z < 0.0 && v.z * v.z > 1e-18 * ((v.x * v.x + v.y * v.y) + v.z * v.z))) return false;
            const double w = -1.0 / v.z;
            cx *= w;
            cy *= w;
        }
        const double px = x0 + cx * sx, py = y0 - cy * sy;
        if (!(std::abs(px) < 1e7 && std::abs(py) < 1e7)) return false;
        xl = std::min(xl, px);
        xh = std::max(xh, px);
        yl = std::min(yl, py);
        yh = std::max(yh, py);
    }
    return true;
}

#ifdef OCTRACE_FRONTIER_AVX512
/// Lane c's bits of a child or corner index c: c >> 2, c >> 1 & 1, c & 1 (as masks).
constexpr __mmask8 kBit4 = 0xF0, kBit2 = 0xCC, kBit1 = 0xAA;

/// One camera coordinate of the eight corners: c0 + (c & 4 ? ex : 0) + (c & 2 ? ey : 0) + (c & 1 ? ez : 0).
[[gnu::target("avx512f")]] inline __m512d cornerAxis(double c0, double ex, double ey, double ez) {
    __m512d v = _mm512_add_pd(_mm512_set1_pd(c0), _mm512_maskz_mov_pd(kBit4, _mm512_set1_pd(ex)));
    v = _mm512_add_pd(v, _mm512_maskz_mov_pd(kBit2, _mm512_set1_pd(ey)));
    return _mm512_add_pd(v, _mm512_maskz_mov_pd(kBit1, _mm512_set1_pd(ez)));
}

/// One coordinate of the eight children's centres relative to the apex: ((2 c + bit) + 1/2) side - apex.
[[gnu::target("avx512f")]] inline __m512d childCentres(int c, __mmask8 bit, __m512d side, double apex) {
    const __m512d twice = _mm512_set1_pd(double(2 * c));
    const __m512d v = _mm512_mask_add_pd(twice, bit, twice, _mm512_set1_pd(1.0));
    return _mm512_sub_pd(_mm512_mul_pd(_mm512_add_pd(v, _mm512_set1_pd(0.5)), side), _mm512_set1_pd(apex));
}

/// cornerBounds with the eight corners in the lanes of AVX-512 registers: the same operations on
/// the same operands (the build does not fuse multiply-adds), min and max exact, so the same
/// result bit for bit.
[[gnu::target("avx512f")]] bool cornerBoundsAvx512(const RayGenerator& gen, const BoxCorners& b, double& xl, double& xh,
                                                   double& yl, double& yh) {
    double x0, y0, sx, sy;
    gen.pixelTerms(x0, y0, sx, sy);
    __m512d vx = cornerAxis(b.c0.x, b.ex.x, b.ey.x, b.ez.x), vy = cornerAxis(b.c0.y, b.ex.y, b.ey.y, b.ez.y);
    if (!gen.orthographic()) {
        const __m512d vz = cornerAxis(b.c0.z, b.ex.z, b.ey.z, b.ez.z);
        const __m512d len2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(vx, vx), _mm512_mul_pd(vy, vy)), _mm512_mul_pd(vz, vz));
        const __mmask8 front = _mm512_cmp_pd_mask(vz, _mm512_setzero_pd(), _CMP_LT_OQ) &
                               _mm512_cmp_pd_mask(_mm512_mul_pd(vz, vz), _mm512_mul_pd(_mm512_set1_pd(1e-18), len2), _CMP_GT_OQ);
        if (front != 0xFF) return false;
        const __m512d w = _mm512_div_pd(_mm512_set1_pd(-1.0), vz);
        vx = _mm512_mul_pd(vx, w);
        vy = _mm512_mul_pd(vy, w);
    }
    const __m512d px = _mm512_add_pd(_mm512_set1_pd(x0), _mm512_mul_pd(vx, _mm512_set1_pd(sx)));
    const __m512d py = _mm512_sub_pd(_mm512_set1_pd(y0), _mm512_mul_pd(vy, _mm512_set1_pd(sy)));
    const __m512d lim = _mm512_set1_pd(1e7);
    if ((_mm512_cmp_pd_mask(_mm512_abs_pd(px), lim, _CMP_LT_OQ) & _mm512_cmp_pd_mask(_mm512_abs_pd(py), lim, _CMP_LT_OQ)) != 0xFF)
        return false;
    xl = _mm512_reduce_min_pd(px);
    xh = _mm512_reduce_max_pd(px);
    yl = _mm512_reduce_min_pd(py);
    yh = _mm512_reduce_max_pd(py);
    return true;
}

/// TileFrustum::meetsChildren in AVX-512: lane c computes meets(child c, level + 1)'s every
/// double by the same operation on the same operands (the child's integer coordinates and the
/// half are exact as doubles either way).
[[gnu::target("avx512f")]] unsigned meetsChildrenAvx512(const TileFrustum& f, const ivec3& cell, int level) {
    const int cl = level + 1;
    const __m512d side = _mm512_set1_pd(double(1 << (N - cl)));
    const __m512d cx = childCentres(cell.x, kBit4, side, f.apex.x), cy = childCentres(cell.y, kBit2, side, f.apex.y),
                  cz = childCentres(cell.z, kBit1, side, f.apex.z);
    __mmask8 pass = 0xFF;
    for (std::size_t i = 0; i < 5; ++i) {
        const dvec3& g = f.g[i];
        __m512d t = _mm512_add_pd(_mm512_mul_pd(_mm512_set1_pd(g.x), cx), _mm512_mul_pd(_mm512_set1_pd(g.y), cy));
        t = _mm512_add_pd(t, _mm512_mul_pd(_mm512_set1_pd(g.z), cz));
        t = _mm512_add_pd(t, _mm512_set1_pd(f.reach[i][std::size_t(cl)]));
        pass &= _mm512_cmp_pd_mask(t, _mm512_setzero_pd(), _CMP_NLT_UQ);  // meets: not (t < 0)
    }
    return pass;
}

bool hasAvx512() {
    static const bool avx512 = __builtin_cpu_supports("avx512f");
    return avx512;
}
#endif
}  // namespace

unsigned TileFrustum::meetsChildren(const ivec3& cell, int level) const {
#ifdef OCTRACE_FRONTIER_AVX512
    if (hasAvx512()) return meetsChildrenAvx512(*this, cell, level);
#endif
    unsigned pass = 0;
    for (unsigned c = 0; c < 8; ++c)
        if (meets(cell * 2 + ivec3(int(c >> 2), int((c >> 1) & 1), int(c & 1)), level + 1)) pass |= 1u << c;
    return pass;
}

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
            // Not empty, no interior term (volume form), meeting the frustum.
            const unsigned keep = nd.childMask & ~unsigned(nd.termMask) & f.meetsChildren(fn.start.cell, fn.start.level);
            if (keep)
                for (unsigned c : order) {
                    if (!(keep & (1u << c))) continue;
                    const ivec3 cell = fn.start.cell * 2 + ivec3(int(c >> 2), int((c >> 1) & 1), int(c & 1));
                    // Written in place: a node assembled on the stack and copied in 16-byte
                    // pieces waits for its own field stores (store forwarding).
                    next.emplace_back().start = {nd.firstChild + childRank(nd.childMask, c), fn.start.level + 1, cell};
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
void pixelRect(const Octree& tree, const RayGenerator& gen, const TileFrustum& f, FrontierNode& fn, int w, int h,
               bool scalar) {
    fn.rect = true;
    fn.projected = false;
    fn.x0 = fn.y0 = 0;
    fn.x1 = w - 1;
    fn.y1 = h - 1;
    const double side = std::ldexp(1.0, N - fn.start.level), k = tree.cubeSide / std::ldexp(1.0, N);
    const dvec3 lo = (dvec3(fn.start.cell) * side - dvec3(f.pad) - f.apex) * k;
    const double s = (side + 2.0 * f.pad) * k;
    // The corners' camera coordinates (right, up, back): the lowest corner's plus, per axis of
    // the box, that axis's edge (the forms are linear; right, up and back are orthonormal).
    const dvec3 right = gen.right(), up = gen.up(), back = gen.back();
    const BoxCorners b{dvec3(glm::dot(lo, right), glm::dot(lo, up), glm::dot(lo, back)), dvec3(right.x, up.x, back.x) * s,
                       dvec3(right.y, up.y, back.y) * s, dvec3(right.z, up.z, back.z) * s};
    double xl, xh, yl, yh;
#ifdef OCTRACE_FRONTIER_AVX512
    if (hasAvx512() && !scalar ? !cornerBoundsAvx512(gen, b, xl, xh, yl, yh) : !cornerBounds(gen, b, xl, xh, yl, yh)) return;
#else
    (void)scalar;
    if (!cornerBounds(gen, b, xl, xh, yl, yh)) return;
#endif
    // Pixel x has its centre at x + 0.5.
    constexpr double m = 0.01;
    fn.projected = true;
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
    // Written in place and kept by advancing the end (the rectangle test is unpredictable).
    list.resize(from.size());
    std::size_t kept = 0;
    for (const FrontierNode& fn : from) {
        const bool inRect = fn.rectMeets(x0, y0, x1, y1);
        list[kept] = fn;
        if (fn.projected)
            kept += inRect;
        else if ((!fn.rect || inRect) && f.meets(fn.start.cell, fn.start.level))
            ++kept;
    }
    list.resize(kept);
}

void tileFrontier(const Octree& tree, const RayGenerator& gen, const TileFrustum& f, const std::vector<FrontierNode>& from,
                  unsigned s, std::size_t cap, int keepLevel, int x0, int y0, int x1, int y1, int w, int h,
                  std::vector<FrontierNode>& list, std::vector<FrontierNode>& next) {
    filterFrontier(f, from, list, x0, y0, x1, y1);
    refineFrontier(tree, f, s, cap, keepLevel, list, next);
    // Step 4: the nodes whose rectangle misses the tile are dropped.
    for (FrontierNode& fn : list)
        if (!fn.rect) pixelRect(tree, gen, f, fn, w, h);
    std::size_t kept = 0;  // after the rectangles (a node copied just after its fields were written waits for them)
    for (const FrontierNode& fn : list)
        if (fn.rectMeets(x0, y0, x1, y1)) list[kept++] = fn;
    list.resize(kept);
}

ImageFrontier::ImageFrontier(const Octree& tree, const Camera& camera, const PixelRays& rays, int tileSize)
    : tree_(tree), gen_(camera), slopes_(tree, gen_, rays, camera.width, camera.height, true), width_(camera.width),
      height_(camera.height), tileSize_(tileSize), keepLevel_(tree.depth - 1) {
    if (tileSize < 1 || !std::has_single_bit(unsigned(tileSize)))
        throw std::invalid_argument("ImageFrontier: the tile size must be a power of two");
    tileShift_ = std::countr_zero(unsigned(tileSize));
    tileMask_ = tileSize - 1;
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
    const int tx = x >> tileShift_, ty = y >> tileShift_;
    const std::size_t t = std::size_t(ty) * std::size_t(tilesX_) + std::size_t(tx);
    std::call_once(tileOnce_[t], [&] {
        const std::size_t g = group(tx, ty);
        const std::vector<FrontierNode>& from = groupNodes(g);
        Tile& tl = tiles_[t];
        std::vector<FrontierNode>& list = tl.nodes;
        std::vector<FrontierNode> next;
        const int x0 = tx * tileSize_, y0 = ty * tileSize_;
        const int x1 = std::min(x0 + tileSize_, width_), y1 = std::min(y0 + tileSize_, height_);
        tileFrontier(tree_, gen_, tileFrustum(gen_, slopes_, x0, y0, x1, y1), from, signs_[g], cap_, keepLevel_, x0, y0, x1,
                     y1, width_, height_, list, next);
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
