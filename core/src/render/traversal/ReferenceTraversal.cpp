#include "octrace/render/ReferenceTraversal.h"

#include "octrace/render/Lod.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace octrace {
namespace {

constexpr int N = Octree::kIntBits;
constexpr long double kL = 16384.0L;
static_assert((1 << N) == 16384);

/// A ray parameter as a fraction num/den with den > 0, compared by cross-multiplication.
struct Param {
    long double num = 0, den = 1;
};
inline bool less(const Param& a, const Param& b) { return a.num * b.den < b.num * a.den; }

/// Interval [start, end) of parameters where the line is inside the box along every axis
/// and in front of the eye. Returns false when empty.
bool boxInterval(const ReferenceRay& r, const long double lo[3], long double size, Param& start) {
    Param s{r.tEye, 1}, e{1, 1};
    if (r.tEye < 0) s = Param{0, 1};
    Param starts[4] = {s}, ends[4] = {e};
    int ns = 1, ne = 1;
    for (int a = 0; a < 3; ++a) {
        const long double l = lo[a], h = lo[a] + size, p = r.p0[a], d = r.dir[a];
        const bool closedTop = (r.sign >> (2 - a)) & 1;
        if (d == 0) {
            bool inside = closedTop ? (p > l && p <= h) : (p >= l && p < h);
            if (!inside) return false;
            continue;
        }
        if (d > 0) {
            starts[ns++] = Param{l - p, d};
            ends[ne++] = Param{h - p, d};
        } else {
            starts[ns++] = Param{p - h, -d};
            ends[ne++] = Param{p - l, -d};
        }
    }
    Param smax = starts[0], emin = ends[0];
    for (int i = 1; i < ns; ++i)
        if (less(smax, starts[i])) smax = starts[i];
    for (int i = 1; i < ne; ++i)
        if (less(ends[i], emin)) emin = ends[i];
    start = smax;
    return less(smax, emin);
}

struct Walker {
    const Octree& tree;
    const ReferenceRay& ray;
    TraversalCounters& counters;
    long double voxelSize;
    const LodCut* cut;
    const VoxelFilter* filter;

    /// The filter's verdict on a reached voxel; a refused one leaves no trace in `hit`.
    bool accepts(TraversalHit& hit) const {
        if (!filter || (*filter)(hit)) return true;
        hit = TraversalHit{};
        return false;
    }

    bool visit(std::uint32_t node, int level, const long double lo[3], TraversalHit& hit) {
        ++counters.nodes;
        const OctreeNode& nd = tree.nodes()[node];
        const long double half = std::ldexp(1.0L, N - level - 1);
        struct Cand {
            Param start;
            int child;
            std::uint32_t slot;
            long double lo[3];
        } cand[8];
        int n = 0;
        std::uint32_t slot = nd.firstChild;
        for (int c = 0; c < 8; ++c) {
            if (!(nd.childMask & (1u << c))) continue;
            Cand k;
            k.child = c;
            k.slot = slot++;
            k.lo[0] = lo[0] + ((c >> 2) & 1) * half;
            k.lo[1] = lo[1] + ((c >> 1) & 1) * half;
            k.lo[2] = lo[2] + (c & 1) * half;
            if (boxInterval(ray, k.lo, half, k.start)) cand[n++] = k;
        }
        for (int i = 1; i < n; ++i)  // insertion sort by entry parameter (at most 8)
            for (int j = i; j > 0 && less(cand[j].start, cand[j - 1].start); --j) std::swap(cand[j], cand[j - 1]);
        for (int i = 0; i < n; ++i) {
            const Cand& k = cand[i];
            if (level == tree.depth - 1) {
                hit.voxel = k.slot;
                for (int a = 0; a < 3; ++a) hit.cell[a] = int(std::lround(k.lo[a] / voxelSize));
                if (accepts(hit)) return true;
                continue;
            }
            if (nd.termMask & (1u << k.child)) {
                if (tree.form != OctreeForm::Shell) continue;  // interior term: not drawn
                // A coarse leaf: drawn as a solid cube of its level.
                hit.voxel = tree.nodes()[k.slot].firstChild;
                for (int a = 0; a < 3; ++a) hit.cell[a] = int(std::lround(k.lo[a] / voxelSize));
                hit.leafShift = tree.depth - level - 1;
                if (accepts(hit)) return true;
                continue;
            }
            if (cut) {
                ivec3 cell;
                for (int a = 0; a < 3; ++a) cell[a] = int(std::lround(k.lo[a] / half));
                if (cut->stops(level + 1, cell)) {
                    hit.voxel = tree.summaries()[k.slot].firstVoxel;
                    hit.cell = cell;
                    hit.node = k.slot;
                    hit.level = level + 1;
                    return true;
                }
            }
            if (visit(k.slot, level + 1, k.lo, hit)) return true;
        }
        return false;
    }
};

ReferenceRay fromPoints(const dvec3& p0, const dvec3& p1, long double tEye, unsigned sign) {
    ReferenceRay r;
    for (int a = 0; a < 3; ++a) {
        r.p0[a] = p0[a];
        r.dir[a] = (long double)p1[a] - (long double)p0[a];
    }
    r.tEye = tEye;
    r.sign = sign;
    r.valid = true;
    return r;
}

}  // namespace

ReferenceRay referenceRayFromQuantized(const QuantizedRay& q) {
    if (!q.meetsCube) return ReferenceRay{};
    long double tEye = std::ldexp((long double)q.eyeM, -(N + QuantizedRay::kFracBits));
    return fromPoints(q.lowerPoint(), q.upperPoint(), tEye, q.sign);
}

ReferenceRay referenceRayUnquantized(const dvec3& o, const dvec3& d) {
    int main = 0;
    for (int a = 1; a < 3; ++a)
        if (std::abs(d[a]) > std::abs(d[main])) main = a;
    if (!(std::abs(d[main]) > 0.0)) return ReferenceRay{};
    unsigned sign = 0;
    for (int a = 0; a < 3; ++a)
        if (d[a] < 0.0) sign |= 4u >> a;
    // Parameter 0 on the plane the ray enters along its main axis, 1 on the opposite one.
    double m0 = d[main] > 0 ? 0.0 : double(kL), m1 = d[main] > 0 ? double(kL) : 0.0;
    dvec3 p0 = o + d * ((m0 - o[main]) / d[main]);
    dvec3 p1 = o + d * ((m1 - o[main]) / d[main]);
    p0[main] = m0;
    p1[main] = m1;
    long double tEye = ((long double)o[main] - m0) / ((long double)m1 - m0);
    return fromPoints(p0, p1, tEye, sign);
}

TraversalHit traverseReference(const Octree& tree, const ReferenceRay& ray, TraversalCounters& counters,
                               const LodCut* cut, const VoxelFilter* filter) {
    TraversalHit hit;
    if (!ray.valid || tree.nodes().empty()) return hit;
    const long double lo[3] = {0, 0, 0};
    Param start;
    if (!boxInterval(ray, lo, kL, start)) return hit;
    Walker w{tree, ray, counters, std::ldexp(1.0L, N - tree.depth), cut && cut->active() ? cut : nullptr,
             filter && *filter ? filter : nullptr};
    w.visit(0, 0, lo, hit);
    return hit;
}

}  // namespace octrace
