#include "octrace/render/SmoothSurface.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace octrace {
namespace {

inline int sideOf(double v) { return v >= 0.0 ? 1 : 0; }

/// The interpolant along p(u) = entry + u dir as a cubic c[0] + c[1] u + c[2] u^2 + c[3] u^3.
struct Cubic {
    double c[4] = {0, 0, 0, 0};
    Cubic(const double d[8], const dvec3& e, const dvec3& dir) {
        // The weight of the lower / upper corner along each axis, linear in u: w[a][h] = w0 + w1 u.
        double w[3][2][2];
        for (int a = 0; a < 3; ++a) {
            w[a][0][0] = 1.0 - e[a];
            w[a][0][1] = -dir[a];
            w[a][1][0] = e[a];
            w[a][1][1] = dir[a];
        }
        for (int q = 0; q < 8; ++q) {
            const double* X = w[0][(q >> 2) & 1];
            const double* Y = w[1][(q >> 1) & 1];
            const double* Z = w[2][q & 1];
            const double p0 = X[0] * Y[0], p1 = X[0] * Y[1] + X[1] * Y[0], p2 = X[1] * Y[1];
            c[0] += d[q] * (p0 * Z[0]);
            c[1] += d[q] * (p1 * Z[0] + p0 * Z[1]);
            c[2] += d[q] * (p2 * Z[0] + p1 * Z[1]);
            c[3] += d[q] * (p2 * Z[1]);
        }
    }
    double operator()(double u) const { return ((c[3] * u + c[2]) * u + c[1]) * u + c[0]; }
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
    : tree_(tree), active_(settings.surface == SurfaceMode::Smooth && !tree.corners().empty()) {}

bool SmoothSurface::clip(const Ray& ray, const ivec3& cell, double& t0, double& span, dvec3& entry) const {
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
        double ta = (l - ray.origin[a]) / ray.direction[a], tb = (h - ray.origin[a]) / ray.direction[a];
        if (ta > tb) std::swap(ta, tb);
        tin = std::max(tin, ta);
        tout = std::min(tout, tb);
    }
    if (!(tout >= tin)) return false;
    t0 = tin;
    span = (tout - tin) / side;
    entry = (ray.origin + tin * ray.direction - lo) / side;
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
/// whose end lies on the other side holds the crossing, found by Illinois regula falsi.
/// `side`: the carried side (-1 none: the entry's), on return the exit side when there is no
/// crossing. Returns whether there is one, at `u` voxels from the entry.
bool cubicCrossing(const VoxelSpan& s, int& side, double& u) {
    const Cubic f(s.d, s.entry, s.dir);
    if (side < 0) side = sideOf(f(0.0));
    if (sideOf(f(0.0)) != side) {
        u = 0.0;
        return true;
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
        // Illinois: regula falsi that halves the value of an end kept twice in a row.
        int kept = 0;
        for (int it = 0; it < 100 && hi - lo > 1e-9; ++it) {
            double m = fhi != flo ? lo - flo * (hi - lo) / (fhi - flo) : 0.5 * (lo + hi);
            if (!(m > lo && m < hi)) m = 0.5 * (lo + hi);
            const double fm = f(m);
            if (sideOf(fm) == side) {
                lo = m;
                flo = fm;
                if (kept == -1) fhi *= 0.5;
                kept = -1;
            } else {
                hi = m;
                fhi = fm;
                if (kept == 1) flo *= 0.5;
                kept = 1;
            }
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
    if (!clip(ray.world, hit.cell, s.t0, s.span, s.entry)) return false;
    decodeCorners(code, s.d);
    s.dir = ray.world.direction;
    double u = 0.0;
    if (!search(s, ray.side, u)) return false;
    return accept(ray, hit, s.d, s.t0, s.entry, u);
}

bool SmoothSurface::test(RayState& ray, TraversalHit& hit) const { return testWith(ray, hit, cubicCrossing); }

bool SmoothSurface::testReference(RayState& ray, TraversalHit& hit) const { return testWith(ray, hit, marchedCrossing); }

VoxelFilter SmoothSurface::filter(RayState& ray, bool reference) const {
    if (!active_) return {};
    if (reference) return [this, &ray](TraversalHit& hit) { return testReference(ray, hit); };
    return [this, &ray](TraversalHit& hit) { return test(ray, hit); };
}

}  // namespace octrace
