#include "octrace/render/SmoothSurface.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace octrace {
namespace {

inline int sideOf(double v) { return v >= 0.0 ? 1 : 0; }

/// How close (in voxels) the fast test brackets a crossing: far below what a depth buffer of
/// float32 resolves at the distances drawn (its unit in the last place is 6e-8 of the distance).
constexpr double kCrossingTolerance = 1e-7;

/// The interpolant along p(u) = entry + u dir as a cubic c[0] + c[1] u + c[2] u^2 + c[3] u^3.
struct Cubic {
    double c[4] = {0, 0, 0, 0};
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
    const double side = tree_.voxelSize();
    const dvec3 lo = tree_.cubeOrigin + dvec3(cell) * side;
    // A hair wider than the box: the quantized ray that proposed it may graze where the world
    // ray passes a rounding error outside.
    const double pad = 1e-7 * side;
    double tin = 0.0, tout = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        const double l = lo[a] - pad, h = lo[a] + side + pad;
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
    entry = (ray.origin + tin * ray.direction - lo) * inverseVoxel_;
    return true;
}

bool SmoothSurface::accept(const RayState& ray, TraversalHit& hit, const double d[8], double t0, const dvec3& entry,
                           double u) const {
    const dvec3 p = entry + u * ray.world.direction;
    // The interpolant's gradient (voxel coordinates; the voxel is a cube, so it points as the
    // world gradient does).
    dvec3 g(0.0);
    for (int q = 0; q < 8; ++q) {
        const int x = (q >> 2) & 1, y = (q >> 1) & 1, z = q & 1;
        const double wx = x ? p.x : 1.0 - p.x, wy = y ? p.y : 1.0 - p.y, wz = z ? p.z : 1.0 - p.z;
        g.x += d[q] * (x ? 1.0 : -1.0) * wy * wz;
        g.y += d[q] * (y ? 1.0 : -1.0) * wx * wz;
        g.z += d[q] * (z ? 1.0 : -1.0) * wx * wy;
    }
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

/// The fast search: the cubic's extrema split the span into monotone pieces; the first piece
/// whose end lies on the other side holds the crossing, found by Newton's method from the
/// regula falsi point inside the bracket, closed to kCrossingTolerance.
/// `side`: the carried side (-1 none: the entry's), on return the exit side when there is no
/// crossing. Returns whether there is one, at `u` voxels from the entry.
bool cubicCrossing(const VoxelSpan& s, int& side, double& u) {
    const Cubic f(s.d, s.entry, s.dir);
    if (side < 0) side = sideOf(f(0.0));
    if (sideOf(f(0.0)) != side) {
        u = 0.0;
        return true;
    }
    // The cubic on [0, span] in Bernstein form: f is a convex combination of the four
    // coefficients (with positive weights inside the span, the end coefficients at its ends),
    // so when all four lie on the carried side, so does f over the whole span: no crossing,
    // and the exit side is the carried one. Most voxels the ray passes are decided here.
    {
        const double h = s.span * (1.0 / 3.0);
        const double b0 = f.c[0], b1 = b0 + f.c[1] * h, b2 = b1 + (f.c[1] + f.c[2] * s.span) * h;
        const double b3 = f(s.span);
        if (side ? std::min({b0, b1, b2, b3}) >= 0.0 : std::max({b0, b1, b2, b3}) < 0.0) return false;
    }
    double cuts[3];
    const int n = f.extrema(s.span, cuts);
    cuts[n] = s.span;
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
    side = sideOf(f(s.span));
    return false;
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

bool SmoothSurface::testReference(RayState& ray, TraversalHit& hit) const { return testWith(ray, hit, marchedCrossing); }

VoxelFilter SmoothSurface::filter(RayState& ray, bool reference) const {
    if (!active_) return {};
    if (reference) return [this, &ray](TraversalHit& hit) { return testReference(ray, hit); };
    return [this, &ray](TraversalHit& hit) { return test(ray, hit); };
}

}  // namespace octrace
