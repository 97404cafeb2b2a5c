#include "octrace/render/SmoothSurface.h"
#include "render/Transpose8.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cstddef>
#include <cmath>
#include <limits>
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace octrace {
namespace {

inline int sideOf(double v) { return v >= 0.0 ? 1 : 0; }

/// A voxel's box as SmoothSurface::clip (and the lanes' version) takes it: its lower corner
/// and its slabs per axis, a hair wider than the box (the quantized ray that proposed it may
/// graze where the world ray passes a rounding error outside).
struct VoxelSlabs {
    dvec3 lo;
    double l[3], h[3];
    VoxelSlabs(const Octree& tree, const ivec3& cell) {
        const double side = tree.voxelSize();
        lo = tree.cubeOrigin + dvec3(cell) * side;
        const double pad = 1e-7 * side;
        for (int a = 0; a < 3; ++a) {
            l[a] = lo[a] - pad;
            h[a] = lo[a] + side + pad;
        }
    }
};

/// How close (in voxels) the fast test brackets a crossing: far below what a depth buffer of
/// float32 resolves at the distances drawn (its unit in the last place is 6e-8 of the distance).
constexpr double kCrossingTolerance = 1e-7;

/// testLanes takes the rays of a voxel together (eight at a time, AVX-512) from this many on;
/// a ray alone is cheaper through test() (the tile renderer's smooth frames at 1 thread: CT skin
/// about 3% slower with 1 than with 2). With each lane's fields gathered through the stack, the
/// lanes only paid from 4 rays; loaded and transposed in registers, from 2 (CT skin, whose voxels
/// meet two rays of a packet on average, and CT bone and T, 2-4% faster with 2 than with 4).
[[maybe_unused]] constexpr unsigned kLanesTogether = 2;

/// The interpolant along p(u) = entry + u dir as a cubic c[0] + c[1] u + c[2] u^2 + c[3] u^3.
struct Cubic {
    double c[4] = {0, 0, 0, 0};
    Cubic() = default;
    /// The coefficients as written out below (the lanes' version computes them so, lane by lane).
    Cubic(const double d[8], const dvec3& e, const dvec3& dir) {
        // The weight of the lower / upper corner along axis a, linear in u: (w0, w1) with
        // w(u) = w0 + w1 u. Contracted one axis at a time (z, then y, then x): linear, quadratic,
        // cubic polynomials, fewer products than expanding each corner's weight.
        auto lower = [&](int a) { return std::array<double, 2>{1.0 - e[a], -dir[a]}; };
        auto upper = [&](int a) { return std::array<double, 2>{e[a], dir[a]}; };
        const auto z0 = lower(2), z1 = upper(2), y0 = lower(1), y1 = upper(1), x0 = lower(0), x1 = upper(0);
        std::array<double, 3> h[2];
        for (int x = 0; x < 2; ++x) {
            std::array<double, 2> g[2];
            for (int y = 0; y < 2; ++y) {
                const double a = d[(x << 2) | (y << 1)], b = d[(x << 2) | (y << 1) | 1];
                g[y] = {a * z0[0] + b * z1[0], a * z0[1] + b * z1[1]};
            }
            h[x] = {g[0][0] * y0[0] + g[1][0] * y1[0], g[0][0] * y0[1] + g[0][1] * y0[0] + g[1][0] * y1[1] + g[1][1] * y1[0],
                    g[0][1] * y0[1] + g[1][1] * y1[1]};
        }
        c[0] = h[0][0] * x0[0] + h[1][0] * x1[0];
        c[1] = h[0][0] * x0[1] + h[0][1] * x0[0] + h[1][0] * x1[1] + h[1][1] * x1[0];
        c[2] = h[0][1] * x0[1] + h[0][2] * x0[0] + h[1][1] * x1[1] + h[1][2] * x1[0];
        c[3] = h[0][2] * x0[1] + h[1][2] * x1[1];
    }
    double operator()(double u) const { return ((c[3] * u + c[2]) * u + c[1]) * u + c[0]; }
    double slope(double u) const { return (3.0 * c[3] * u + 2.0 * c[2]) * u + c[1]; }
    /// The zeros of the derivative in (0, span), ascending; returns how many.
    int extrema(double span, double out[2]) const {
        const double A = 3.0 * c[3], B = 2.0 * c[2], C = c[1];
        // The derivative on [0, span] in Bernstein form (a quadratic: C, C + B span / 2, its
        // value at span): when the three lie strictly on one side, so does the derivative over
        // the span (their convex combination), and the cubic is monotone there.
        const double e0 = C, e1 = C + 0.5 * B * span, e2 = (A * span + B) * span + C;
        if ((e0 > 0.0 && e1 > 0.0 && e2 > 0.0) || (e0 < 0.0 && e1 < 0.0 && e2 < 0.0)) return 0;
        double r[2];
        int n = 0;
        const double scale = std::max({std::abs(A), std::abs(B), std::abs(C)});
        if (!(scale > 0.0)) return 0;
        if (std::abs(A) <= 1e-14 * scale) {
            if (B != 0.0) r[n++] = -C / B;
        } else {
            const double disc = B * B - 4.0 * A * C;
            if (disc > 0.0) {
                const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
                r[n++] = q / A;
                if (q != 0.0) r[n++] = C / q;
            }
        }
        int k = 0;
        for (int i = 0; i < n; ++i)
            if (r[i] > 0.0 && r[i] < span) out[k++] = r[i];
        if (k == 2 && out[0] > out[1]) std::swap(out[0], out[1]);
        return k;
    }
};

/// The trilinear interpolant at p (voxel coordinates), by repeated linear interpolation.
double trilinear(const double d[8], const dvec3& p) {
    auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
    const double x00 = lerp(d[0], d[4], p.x), x01 = lerp(d[1], d[5], p.x);
    const double x10 = lerp(d[2], d[6], p.x), x11 = lerp(d[3], d[7], p.x);
    return lerp(lerp(x00, x10, p.y), lerp(x01, x11, p.y), p.z);
}

}  // namespace

SmoothSurface::SmoothSurface(const Octree& tree, const RenderSettings& settings)
    : tree_(tree), active_(settings.surface == SurfaceMode::Smooth && !tree.corners().empty()), inverseVoxel_(1.0 / tree.voxelSize()) {}

bool SmoothSurface::clip(const RayState& state, const ivec3& cell, double& t0, double& span, dvec3& entry) const {
    const Ray& ray = state.world;
    const VoxelSlabs box(tree_, cell);
    double tin = 0.0, tout = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        const double l = box.l[a], h = box.h[a];
        if (ray.direction[a] == 0.0) {
            if (ray.origin[a] < l || ray.origin[a] > h) return false;
            continue;
        }
        double ta = (l - ray.origin[a]) * state.inverse[a], tb = (h - ray.origin[a]) * state.inverse[a];
        if (ta > tb) std::swap(ta, tb);
        tin = std::max(tin, ta);
        tout = std::min(tout, tb);
    }
    if (!(tout >= tin)) return false;
    t0 = tin;
    span = (tout - tin) * inverseVoxel_;
    entry = (ray.origin + tin * ray.direction - box.lo) * inverseVoxel_;
    return true;
}

bool SmoothSurface::accept(const RayState& ray, TraversalHit& hit, const double d[8], double t0, const dvec3& entry,
                           double u) const {
    const dvec3 p = entry + u * ray.world.direction;
    // The interpolant's gradient (voxel coordinates; the voxel is a cube, so it points as the
    // world gradient does).
    // Each component is the bilinear interpolant, over the other two axes, of the corners'
    // differences along its own axis (corner q = 4x + 2y + z).
    const double x0 = 1.0 - p.x, y0 = 1.0 - p.y, z0 = 1.0 - p.z;
    auto bilinear = [](double a00, double a01, double a10, double a11, double s0, double s1, double w0, double w1) {
        return (a00 * s0 + a10 * s1) * w0 + (a01 * s0 + a11 * s1) * w1;
    };
    const dvec3 g(bilinear(d[4] - d[0], d[5] - d[1], d[6] - d[2], d[7] - d[3], y0, p.y, z0, p.z),
                  bilinear(d[2] - d[0], d[3] - d[1], d[6] - d[4], d[7] - d[5], x0, p.x, z0, p.z),
                  bilinear(d[1] - d[0], d[3] - d[2], d[5] - d[4], d[7] - d[6], x0, p.x, y0, p.y));
    const double len = glm::length(g);
    hit.normal = len > 0.0 && std::isfinite(len) ? vec3(-g / len) : decodeNormal(tree_.voxels()[hit.voxel].normal);
    hit.distance = t0 + u * tree_.voxelSize();
    hit.zCells = float(double(hit.cell.z) + std::clamp(p.z, 0.0, 1.0));
    hit.smooth = true;
    return true;
}

namespace {

/// The ray's span in one voxel: its corners, where it enters (distance t0, voxel coordinates
/// `entry`), its direction and its length in voxels.
struct VoxelSpan {
    double d[8];
    double t0 = 0.0, span = 0.0;
    dvec3 entry{0.0}, dir{0.0};
};

/// How cubicCrossing's first steps decide a voxel.
enum class Start { None, Entry, Search };

/// cubicCrossing's first steps (the lanes' version, SmoothSurface::testLanes, takes the same
/// steps lane by lane): the carried side, a crossing at the entry, or none by the Bernstein bound.
Start crossingStart(const Cubic& f, double span, int& side) {
    if (side < 0) side = sideOf(f(0.0));
    if (sideOf(f(0.0)) != side) return Start::Entry;
    // The cubic on [0, span] in Bernstein form: f is a convex combination of the four
    // coefficients (with positive weights inside the span, the end coefficients at its ends),
    // so when all four lie on the carried side, so does f over the whole span: no crossing,
    // and the exit side is the carried one. Most voxels the ray passes are decided here.
    const double h = span * (1.0 / 3.0);
    const double b0 = f.c[0], b1 = b0 + f.c[1] * h, b2 = b1 + (f.c[1] + f.c[2] * span) * h;
    const double b3 = f(span);
    if (side ? std::min({b0, b1, b2, b3}) >= 0.0 : std::max({b0, b1, b2, b3}) < 0.0) return Start::None;
    return Start::Search;
}

/// The rest of cubicCrossing, once crossingStart has said Search.
bool cubicSearch(const Cubic& f, double span, int& side, double& u) {
    double cuts[3];
    const int n = f.extrema(span, cuts);
    cuts[n] = span;
    double lo = 0.0, flo = f(0.0);
    for (int i = 0; i <= n; ++i) {
        double hi = cuts[i], fhi = f(hi);
        if (sideOf(fhi) == side) {
            lo = hi;
            flo = fhi;
            continue;
        }
        // Newton's method from the regula falsi point, kept inside the bracket (a step that
        // leaves it bisects instead); once a step is below half the tolerance, the next point
        // is placed half the tolerance past Newton's on the side still open, so that the
        // bracket closes to the tolerance around the crossing.
        double m = fhi != flo ? lo - flo * (hi - lo) / (fhi - flo) : 0.5 * (lo + hi);
        for (int it = 0; it < 100; ++it) {
            if (!(m > lo && m < hi)) m = 0.5 * (lo + hi);
            const double fm = f(m);
            const bool same = sideOf(fm) == side;
            (same ? lo : hi) = m;
            if (hi - lo <= kCrossingTolerance) break;
            const double next = m - fm / f.slope(m);
            m = std::abs(next - m) < 0.5 * kCrossingTolerance ? next + (same ? 0.5 : -0.5) * kCrossingTolerance : next;
        }
        u = hi;
        return true;
    }
    side = sideOf(f(span));
    return false;
}

/// The fast search: the cubic's extrema split the span into monotone pieces; the first piece
/// whose end lies on the other side holds the crossing, found by Newton's method from the
/// regula falsi point inside the bracket, closed to kCrossingTolerance.
/// `side`: the carried side (-1 none: the entry's), on return the exit side when there is no
/// crossing. Returns whether there is one, at `u` voxels from the entry.
bool cubicCrossing(const VoxelSpan& s, int& side, double& u) {
    const Cubic f(s.d, s.entry, s.dir);
    switch (crossingStart(f, s.span, side)) {
        case Start::None: return false;
        case Start::Entry: u = 0.0; return true;
        case Start::Search: break;
    }
    return cubicSearch(f, s.span, side, u);
}

/// The reference search, as cubicCrossing but by a march of equal steps over the span with the
/// interpolant evaluated directly, the first step that changes side bisected.
bool marchedCrossing(const VoxelSpan& s, int& side, double& u) {
    auto at = [&](double v) { return trilinear(s.d, s.entry + v * s.dir); };
    if (side < 0) side = sideOf(at(0.0));
    if (sideOf(at(0.0)) != side) {
        u = 0.0;
        return true;
    }
    double prev = 0.0;
    for (int k = 1; k <= SmoothSurface::kReferenceSteps; ++k) {
        const double v = s.span * double(k) / double(SmoothSurface::kReferenceSteps);
        if (sideOf(at(v)) == side) {
            prev = v;
            continue;
        }
        double lo = prev, hi = v;
        while (hi - lo > 1e-12) {
            const double m = 0.5 * (lo + hi);
            if (!(m > lo && m < hi)) break;
            (sideOf(at(m)) == side ? lo : hi) = m;
        }
        u = hi;
        return true;
    }
    side = sideOf(at(s.span));
    return false;
}


/// What the first steps of test() give for up to eight rays in one voxel (testLanes).
struct LaneStarts {
    alignas(64) double t0[8], span[8], entry[3][8], c[4][8];
    int side[8];          ///< the carried side after crossingStart
    unsigned clipped = 0;  ///< lanes whose ray meets the voxel's box (clip)
    unsigned entry0 = 0;   ///< of those, the crossing at the entry (Start::Entry)
    unsigned search = 0;   ///< of those, Start::Search
};

#if defined(__x86_64__) && defined(__GNUC__)
#define OCTRACE_SMOOTH_AVX512 1
// The lanes' arithmetic (a lambda would not take startEight's target).
[[gnu::target("avx512f")]] inline __m512d mulL(__m512d x, __m512d y) { return _mm512_mul_pd(x, y); }
[[gnu::target("avx512f")]] inline __m512d addL(__m512d x, __m512d y) { return _mm512_add_pd(x, y); }
[[gnu::target("avx512f")]] inline __m512d negL(__m512d x) {  // -x: the sign flipped, as C++'s unary minus
    return _mm512_castsi512_pd(_mm512_xor_si512(_mm512_castpd_si512(x), _mm512_set1_epi64(std::int64_t(0x8000000000000000ull))));
}
/// Cubic::operator() lane by lane.
[[gnu::target("avx512f")]] inline __m512d cubicL(const __m512d c[4], __m512d u) {
    return addL(mulL(addL(mulL(addL(mulL(c[3], u), c[2]), u), c[1]), u), c[0]);
}

/// SmoothSurface::clip, the Cubic and crossingStart for `n` (1 .. 8) rays in one voxel, in
/// AVX-512 registers: every double the scalar code computes is computed here by the same
/// operation on the same operands in the same order (no fused multiply-add: the build passes
/// -ffp-contract=off), every comparison with the same predicate (false on NaN, as C++'s), and
/// std::max, std::min and their lists resolved as libstdc++ does (the first of equals), so each
/// lane gets the scalar code's bits.
[[gnu::target("avx512f")]] void startEight(const SmoothSurface::RayState* const* rays, unsigned n, const VoxelSlabs& box,
                                            double inverseVoxel, const double d[8], LaneStarts& out) {
    // Each lane's first eight doubles (origin, direction, inverse x and y: consecutive) in one
    // register, then transposed: one register per field, lane k in element k. Written to the
    // stack lane by lane and read back as registers, they waited on the stores (store
    // forwarding). Idle lanes repeat lane 0.
    static_assert(offsetof(SmoothSurface::RayState, world) == 0 && offsetof(Ray, direction) == 24 &&
                      offsetof(SmoothSurface::RayState, inverse) == 48,
                  "startEight loads a RayState's origin, direction and inverse as nine consecutive doubles");
    __m512d row[8], invZ = _mm512_setzero_pd();
    __m512i sides = _mm512_setzero_si512();
    for (unsigned k = 0; k < 8; ++k) {
        const SmoothSurface::RayState& r = *rays[k < n ? k : 0];
        row[k] = _mm512_loadu_pd(&r.world.origin.x);
        invZ = _mm512_mask_broadcastsd_pd(invZ, __mmask8(1u << k), _mm_load_sd(&r.inverse.z));
        sides = _mm512_mask_set1_epi64(sides, __mmask8(1u << k), r.side);
    }
    __m512d field[8];
    detail::transpose8(row, field);
    const __m512d O[3] = {field[0], field[1], field[2]}, D[3] = {field[3], field[4], field[5]}, I[3] = {field[6], field[7], invZ};
    const __mmask8 lanes = __mmask8((1u << n) - 1u);
    const __m512d zero = _mm512_setzero_pd(), one = _mm512_set1_pd(1.0);
    // clip: the slabs axis by axis.
    __m512d tin = zero, tout = _mm512_set1_pd(std::numeric_limits<double>::infinity());
    __mmask8 outside = 0;
    for (int a = 0; a < 3; ++a) {
        const __m512d L = _mm512_set1_pd(box.l[a]), H = _mm512_set1_pd(box.h[a]);
        const __mmask8 parallel = _mm512_cmp_pd_mask(D[a], zero, _CMP_EQ_OQ);
        outside |= parallel & (_mm512_cmp_pd_mask(O[a], L, _CMP_LT_OQ) | _mm512_cmp_pd_mask(O[a], H, _CMP_GT_OQ));
        const __m512d ta = _mm512_mul_pd(_mm512_sub_pd(L, O[a]), I[a]), tb = _mm512_mul_pd(_mm512_sub_pd(H, O[a]), I[a]);
        const __mmask8 swap = _mm512_cmp_pd_mask(ta, tb, _CMP_GT_OQ);
        const __m512d near = _mm512_mask_blend_pd(swap, ta, tb), far = _mm512_mask_blend_pd(swap, tb, ta);
        tin = _mm512_mask_mov_pd(tin, _mm512_cmp_pd_mask(tin, near, _CMP_LT_OQ) & ~parallel, near);   // std::max(tin, near)
        tout = _mm512_mask_mov_pd(tout, _mm512_cmp_pd_mask(far, tout, _CMP_LT_OQ) & ~parallel, far);  // std::min(tout, far)
    }
    const __mmask8 clipped = _mm512_cmp_pd_mask(tout, tin, _CMP_GE_OQ) & ~outside & lanes;
    const __m512d iv = _mm512_set1_pd(inverseVoxel);
    const __m512d span = _mm512_mul_pd(_mm512_sub_pd(tout, tin), iv);
    __m512d E[3];
    for (int a = 0; a < 3; ++a)
        E[a] = _mm512_mul_pd(_mm512_sub_pd(_mm512_add_pd(O[a], _mm512_mul_pd(tin, D[a])), _mm512_set1_pd(box.lo[a])), iv);
    // The Cubic, as its constructor writes it out: (w0, w1) per axis and end.
    const __m512d z0[2] = {_mm512_sub_pd(one, E[2]), negL(D[2])}, z1[2] = {E[2], D[2]};
    const __m512d y0[2] = {_mm512_sub_pd(one, E[1]), negL(D[1])}, y1[2] = {E[1], D[1]};
    const __m512d x0[2] = {_mm512_sub_pd(one, E[0]), negL(D[0])}, x1[2] = {E[0], D[0]};
    __m512d hx[2][3];
    for (int x = 0; x < 2; ++x) {
        __m512d g[2][2];
        for (int y = 0; y < 2; ++y) {
            const __m512d A = _mm512_set1_pd(d[(x << 2) | (y << 1)]), B = _mm512_set1_pd(d[(x << 2) | (y << 1) | 1]);
            g[y][0] = addL(mulL(A, z0[0]), mulL(B, z1[0]));
            g[y][1] = addL(mulL(A, z0[1]), mulL(B, z1[1]));
        }
        hx[x][0] = addL(mulL(g[0][0], y0[0]), mulL(g[1][0], y1[0]));
        hx[x][1] = addL(addL(addL(mulL(g[0][0], y0[1]), mulL(g[0][1], y0[0])), mulL(g[1][0], y1[1])), mulL(g[1][1], y1[0]));
        hx[x][2] = addL(mulL(g[0][1], y0[1]), mulL(g[1][1], y1[1]));
    }
    const __m512d c0 = addL(mulL(hx[0][0], x0[0]), mulL(hx[1][0], x1[0]));
    const __m512d c1 = addL(addL(addL(mulL(hx[0][0], x0[1]), mulL(hx[0][1], x0[0])), mulL(hx[1][0], x1[1])), mulL(hx[1][1], x1[0]));
    const __m512d c2 = addL(addL(addL(mulL(hx[0][1], x0[1]), mulL(hx[0][2], x0[0])), mulL(hx[1][1], x1[1])), mulL(hx[1][2], x1[0]));
    const __m512d c3 = addL(mulL(hx[0][2], x0[1]), mulL(hx[1][2], x1[1]));
    const __m512d c[4] = {c0, c1, c2, c3};
    // crossingStart: the carried side, the entry, the Bernstein bound.
    const __mmask8 none = _mm512_cmplt_epi64_mask(sides, _mm512_setzero_si512());
    const __mmask8 above0 = _mm512_cmp_pd_mask(cubicL(c, zero), zero, _CMP_GE_OQ);  // sideOf(f(0))
    const __mmask8 above = (none & above0) | (~none & _mm512_cmpeq_epi64_mask(sides, _mm512_set1_epi64(1)));
    const __mmask8 entry0 = above0 ^ above;
    const __m512d third = mulL(span, _mm512_set1_pd(1.0 / 3.0));
    const __m512d b0 = c0, b1 = addL(b0, mulL(c1, third)), b2 = addL(b1, mulL(addL(c1, mulL(c2, span)), third));
    const __m512d b3 = cubicL(c, span);
    // std::min({b0, b1, b2, b3}) and std::max(...): the first of the least / greatest.
    __m512d lowest = b0, highest = b0;
    const __m512d later[3] = {b1, b2, b3};
    for (const __m512d b : later) {
        lowest = _mm512_mask_mov_pd(lowest, _mm512_cmp_pd_mask(b, lowest, _CMP_LT_OQ), b);
        highest = _mm512_mask_mov_pd(highest, _mm512_cmp_pd_mask(highest, b, _CMP_LT_OQ), b);
    }
    const __mmask8 kept = (above & _mm512_cmp_pd_mask(lowest, zero, _CMP_GE_OQ)) | (~above & _mm512_cmp_pd_mask(highest, zero, _CMP_LT_OQ));
    out.clipped = clipped;
    out.entry0 = clipped & entry0;
    out.search = clipped & ~entry0 & ~kept;
    _mm512_store_pd(out.t0, tin);
    _mm512_store_pd(out.span, span);
    for (int a = 0; a < 3; ++a) _mm512_store_pd(out.entry[a], E[a]);
    _mm512_store_pd(out.c[0], c0);
    _mm512_store_pd(out.c[1], c1);
    _mm512_store_pd(out.c[2], c2);
    _mm512_store_pd(out.c[3], c3);
    for (unsigned k = 0; k < 8; ++k) out.side[k] = int(above >> k & 1u);
}
#endif

}  // namespace

template <class Search>
bool SmoothSurface::testWith(RayState& ray, TraversalHit& hit, const Search& search) const {
    if (!active_ || hit.nodeHit() || hit.leafShift != 0) return true;
    const std::uint64_t code = tree_.corners()[hit.voxel];
    if (code == 0) return true;
    VoxelSpan s;
    if (!clip(ray, hit.cell, s.t0, s.span, s.entry)) return false;
    decodeCorners(code, s.d);
    s.dir = ray.world.direction;
    double u = 0.0;
    if (!search(s, ray.side, u)) return false;
    return accept(ray, hit, s.d, s.t0, s.entry, u);
}

// Flattened: the clip, the corners' decoding, the search and the acceptance inline (a million
// calls a frame and more; each call spills the search's registers).
[[gnu::flatten]] bool SmoothSurface::test(RayState& ray, TraversalHit& hit) const { return testWith(ray, hit, cubicCrossing); }

unsigned SmoothSurface::testLanes(RayState* const* rays, TraversalHit* const* hits, unsigned count) const {
    unsigned accepted = 0;
#if defined(OCTRACE_SMOOTH_AVX512)
    static const bool avx512 = __builtin_cpu_supports("avx512f");
    const TraversalHit& first = *hits[0];
    for (unsigned k = 1; k < count; ++k) assert(hits[k]->voxel == first.voxel && hits[k]->cell == first.cell);
    const std::uint64_t code = active_ && count >= kLanesTogether && !first.nodeHit() && first.leafShift == 0 ? tree_.corners()[first.voxel] : 0;
    if (avx512 && code != 0) {
        // The voxel's part of testWith and clip, once.
        double d[8];
        decodeCorners(code, d);
        const VoxelSlabs box(tree_, first.cell);
        for (unsigned i = 0; i < count; i += 8) {
            const unsigned n = std::min(count - i, 8u);
            LaneStarts st;
            startEight(rays + i, n, box, inverseVoxel_, d, st);
            for (unsigned rest = st.clipped; rest; rest &= rest - 1) {
                const unsigned k = unsigned(std::countr_zero(rest));
                RayState& ray = *rays[i + k];
                ray.side = st.side[k];
                double u = 0.0;
                if (!(st.entry0 >> k & 1u)) {
                    if (!(st.search >> k & 1u)) continue;  // no crossing (Start::None)
                    Cubic f;
                    for (int j = 0; j < 4; ++j) f.c[j] = st.c[j][k];
                    if (!cubicSearch(f, st.span[k], ray.side, u)) continue;
                }
                accept(ray, *hits[i + k], d, st.t0[k], dvec3(st.entry[0][k], st.entry[1][k], st.entry[2][k]), u);
                accepted |= 1u << (i + k);
            }
        }
        return accepted;
    }
#endif
    for (unsigned k = 0; k < count; ++k)
        if (test(*rays[k], *hits[k])) accepted |= 1u << k;
    return accepted;
}

bool SmoothSurface::testReference(RayState& ray, TraversalHit& hit) const { return testWith(ray, hit, marchedCrossing); }

VoxelFilter SmoothSurface::filter(RayState& ray, bool reference) const {
    if (!active_) return {};
    if (reference) return [this, &ray](TraversalHit& hit) { return testReference(ray, hit); };
    return [this, &ray](TraversalHit& hit) { return test(ray, hit); };
}

}  // namespace octrace
