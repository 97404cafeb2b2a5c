#include "octrace/render/DiscreteTraversal.h"

#include "octrace/render/OrderTable.h"

#include <array>
#include <bit>
#include <cmath>

namespace octrace {
namespace {

constexpr int N = Octree::kIntBits;
constexpr int Q = QuantizedRay::kFracBits;
constexpr std::int64_t L = std::int64_t(1) << N;
using i64 = std::int64_t;

constexpr unsigned axisBit(int a) { return 4u >> a; }

// Canonical child numbering inside the traversal: (hm << 2) | (hu << 1) | hv, where hm, hu, hv
// say which half along the (mirrored) main, u and v axes.
struct Tables {
    std::array<std::uint8_t, 16> expandMU{}, expandMV{}, expandUV{};
    // canonical byte -> original byte, per main axis and sign pattern
    std::array<std::array<std::array<std::uint8_t, 256>, 8>, 3> toOriginal{};
    // original child index -> canonical index, per main axis and sign pattern
    std::array<std::array<std::array<std::uint8_t, 8>, 8>, 3> toCanonical{};

    Tables() {
        for (unsigned m = 0; m < 16; ++m) {
            for (unsigned i = 0; i < 8; ++i) {
                unsigned hm = i >> 2, hu = (i >> 1) & 1, hv = i & 1;
                if (m & (1u << ((hm << 1) | hu))) expandMU[m] |= std::uint8_t(1u << i);
                if (m & (1u << ((hm << 1) | hv))) expandMV[m] |= std::uint8_t(1u << i);
                if (m & (1u << ((hu << 1) | hv))) expandUV[m] |= std::uint8_t(1u << i);
            }
        }
        for (int main = 0; main < 3; ++main) {
            int u = main == 0 ? 1 : 0, v = main == 2 ? 1 : 2;
            for (unsigned s = 0; s < 8; ++s) {
                std::array<unsigned, 8> orig{};
                for (unsigned i = 0; i < 8; ++i) {
                    unsigned mirrored = ((i >> 2) ? axisBit(main) : 0u) | (((i >> 1) & 1) ? axisBit(u) : 0u) |
                                        ((i & 1) ? axisBit(v) : 0u);
                    orig[i] = mirrored ^ s;
                    toCanonical[std::size_t(main)][s][orig[i]] = std::uint8_t(i);
                }
                for (unsigned b = 0; b < 256; ++b) {
                    unsigned o = 0;
                    for (unsigned i = 0; i < 8; ++i)
                        if (b & (1u << i)) o |= 1u << orig[i];
                    toOriginal[std::size_t(main)][s][b] = std::uint8_t(o);
                }
            }
        }
    }
};

const Tables& tables() {
    static const Tables t;
    return t;
}

inline i64 floorShift(i64 x, int s) { return x >> s; }  // arithmetic shift = floor (C++20)

/// State of one node on the traversal stack, in mirrored integer space.
struct NodeState {
    std::uint32_t node;
    int level;
    i64 m0, u0, v0;        // box origin (lattice)
    i64 Wu0, Wu1, Wv0, Wv1;  // 2^(N+Q) * u, v of the line on the node's lower/upper main planes
    i64 Fc;                // F at the centre of the node's (u, v) square
    bool partial;          // the eye's plane cuts the node: apply the eye tests
    OrderTable::Entry order;
    int pos;
};

struct RayConsts {
    const QuantizedRay* r;
    i64 cU, cV;  // 1 when the line is parallel to the u (v) planes, else 0
    const std::uint8_t* toOriginal;
    const std::uint8_t* toCanonical;
};

/// The state byte (canonical numbering) of a node: the children that the ray crosses.
///
/// Child (hm, hu, hv) is crossed iff the intervals of the main coordinate where the line is
/// in its main half, its u range, its v range and in front of the eye have a common point;
/// for intervals on a line that holds iff they meet pairwise (Helly), which is what the three
/// projections test. Each interval is [start, end), so a pairwise test is start_i < end_j:
/// against the midpoint of the lower/upper points in the (main, u) and (main, v) planes, and
/// as the sign of the cross product F at the square's centre and edge midpoints in the (u, v)
/// plane. Six of the 24 pairwise tests follow from the node itself being crossed (which the
/// parent established exactly) and are left out: 18 comparisons remain.
inline unsigned stateByte(const RayConsts& k, const NodeState& n, i64& Wuc, i64& Wvc) {
    const Tables& T = tables();
    const QuantizedRay& r = *k.r;
    const int lg = N - n.level - 1;  // log2 of the half size
    const i64 h = i64(1) << lg;
    Wuc = (n.Wu0 + n.Wu1) >> 1;  // lower/upper points' midpoint: exact
    Wvc = (n.Wv0 + n.Wv1) >> 1;
    // Projection (main, u).
    const i64 Lu = n.u0 << (N + Q), Cu = (n.u0 + h) << (N + Q), Hu = (n.u0 + 2 * h) << (N + Q);
    unsigned mu = unsigned(n.Wu0 < Cu && Wuc > Lu - k.cU) | unsigned(Wuc > Cu - k.cU) << 1 |
                  unsigned(Wuc < Cu) << 2 | unsigned(Wuc < Hu && n.Wu1 > Cu - k.cU) << 3;
    // Projection (main, v).
    const i64 Lv = n.v0 << (N + Q), Cv = (n.v0 + h) << (N + Q), Hv = (n.v0 + 2 * h) << (N + Q);
    unsigned mv = unsigned(n.Wv0 < Cv && Wvc > Lv - k.cV) | unsigned(Wvc > Cv - k.cV) << 1 |
                  unsigned(Wvc < Cv) << 2 | unsigned(Wvc < Hv && n.Wv1 > Cv - k.cV) << 3;
    // Projection (u, v): the middle point Fc is where the line crosses the square's midlines.
    const i64 Ah = r.dV << (Q + lg), Bh = r.dU << (Q + lg);
    const i64 F = n.Fc;
    unsigned uv = unsigned(F - Ah < k.cU && F + Bh > -k.cV) | unsigned(F > -k.cV) << 1 | unsigned(F < k.cU) << 2 |
                  unsigned(F - Bh < k.cU && F + Ah > -k.cV) << 3;
    unsigned byte = T.expandMU[mu] & T.expandMV[mv] & T.expandUV[uv];
    if (n.partial) {
        // Only the part of the line in front of the eye counts.
        unsigned em = unsigned(((n.m0 + h) << Q) > r.eyeM) | unsigned(((n.m0 + 2 * h) << Q) > r.eyeM) << 1;
        unsigned eu = unsigned(r.uEyeFloor < n.u0 + h) | unsigned(r.uEyeFloor < n.u0 + 2 * h) << 1;
        unsigned ev = unsigned(r.vEyeFloor < n.v0 + h) | unsigned(r.vEyeFloor < n.v0 + 2 * h) << 1;
        // (m,u) expansion with m from em and u from eu: bit (hm<<1|hu) set iff em[hm] && eu[hu].
        unsigned emu = 0, emv = 0;
        for (unsigned a = 0; a < 2; ++a)
            for (unsigned b = 0; b < 2; ++b) {
                if ((em >> a & 1) && (eu >> b & 1)) emu |= 1u << (a << 1 | b);
                if ((em >> a & 1) && (ev >> b & 1)) emv |= 1u << (a << 1 | b);
            }
        byte &= T.expandMU[emu] & T.expandMV[emv];
    }
    return byte;
}

/// Exact test of the root box [0, 2^N)^3.
bool rootCrossed(const QuantizedRay& r, i64 cU, i64 cV, i64 Wu0, i64 Wu1, i64 Wv0, i64 Wv1) {
    const i64 top = L << (N + Q);
    auto F = [&](i64 a, i64 b) { return ((a << Q) - r.U0) * r.dV - ((b << Q) - r.V0) * r.dU; };
    return Wu0 < top && Wu1 > -cU && Wv0 < top && Wv1 > -cV && F(0, L) < cU && F(L, 0) > -cV && r.eyeM < (L << Q) &&
           r.uEyeFloor < L && r.vEyeFloor < L;
}

template <bool kObserve>
TraversalHit traverse(const Octree& tree, const QuantizedRay& r, TraversalCounters& counters,
                      const std::function<void(unsigned, unsigned)>* observe) {
    TraversalHit result;
    if (!r.meetsCube || tree.nodes.empty()) return result;
    const Tables& T = tables();
    const OrderTable& order = OrderTable::instance();
    RayConsts k{&r, r.dU == 0 ? 1 : 0, r.dV == 0 ? 1 : 0, T.toOriginal[std::size_t(r.main)][r.sign].data(),
                T.toCanonical[std::size_t(r.main)][r.sign].data()};
    const int depth = tree.depth;

    NodeState stack[Octree::kMaxDepth + 1];
    int sp = 0;
    NodeState& root = stack[0];
    root.node = 0;
    root.level = 0;
    root.m0 = root.u0 = root.v0 = 0;
    root.Wu0 = r.U0 << N;
    root.Wu1 = (r.U0 + r.dU) << N;
    root.Wv0 = r.V0 << N;
    root.Wv1 = (r.V0 + r.dV) << N;
    root.Fc = (((L / 2) << Q) - r.U0) * r.dV - (((L / 2) << Q) - r.V0) * r.dU;
    root.partial = r.eyeM > 0;
    {
        i64 Wuc, Wvc;
        unsigned byte = stateByte(k, root, Wuc, Wvc);
        ++counters.nodes;
        unsigned orig = k.toOriginal[byte];
        if constexpr (kObserve) (*observe)(r.sign, orig);
        root.order = order.entry(r.sign, orig & tree.nodes[0].childMask);
        root.pos = 0;
    }
    while (sp >= 0) {
        NodeState& n = stack[sp];
        if (n.pos >= OrderTable::count(n.order)) {
            --sp;
            continue;
        }
        const unsigned c = unsigned(OrderTable::child(n.order, n.pos++));
        const OctreeNode& nd = tree.nodes[n.node];
        const std::uint32_t slot = nd.firstChild + childRank(nd.childMask, c);
        const unsigned ci = k.toCanonical[c];
        const unsigned hm = ci >> 2, hu = (ci >> 1) & 1, hv = ci & 1;
        const int lg = N - n.level - 1;
        const i64 h = i64(1) << lg;
        if (n.level == depth - 1) {
            // Child is a voxel and the first crossed one in order: the hit.
            i64 mm = n.m0 + hm * h, uu = n.u0 + hu * h, vv = n.v0 + hv * h;
            i64 mirrored[3];
            mirrored[r.main] = mm;
            mirrored[r.u] = uu;
            mirrored[r.v] = vv;
            for (int a = 0; a < 3; ++a) {
                i64 o = (r.sign & axisBit(a)) ? L - (mirrored[a] + h) : mirrored[a];
                result.cell[a] = int(o >> (N - depth));
            }
            result.voxel = slot;
            return result;
        }
        if (nd.termMask & (1u << c)) continue;  // interior terms: volume form, not drawn by this shell renderer
        i64 Wuc = (n.Wu0 + n.Wu1) >> 1, Wvc = (n.Wv0 + n.Wv1) >> 1;
        NodeState& ch = stack[sp + 1];
        ch.node = slot;
        ch.level = n.level + 1;
        ch.m0 = n.m0 + hm * h;
        ch.u0 = n.u0 + hu * h;
        ch.v0 = n.v0 + hv * h;
        ch.Wu0 = hm ? Wuc : n.Wu0;
        ch.Wu1 = hm ? n.Wu1 : Wuc;
        ch.Wv0 = hm ? Wvc : n.Wv0;
        ch.Wv1 = hm ? n.Wv1 : Wvc;
        const i64 qa = r.dV << (Q + lg - 1), qb = r.dU << (Q + lg - 1);
        ch.Fc = n.Fc + (hu ? qa : -qa) - (hv ? qb : -qb);
        ch.partial = n.partial && (ch.m0 << Q) < r.eyeM;
        i64 a, b;
        unsigned byte = stateByte(k, ch, a, b);
        ++counters.nodes;
        unsigned orig = k.toOriginal[byte];
        if constexpr (kObserve) (*observe)(r.sign, orig);
        ch.order = order.entry(r.sign, orig & tree.nodes[slot].childMask);
        ch.pos = 0;
        if (OrderTable::count(ch.order) > 0) ++sp;
    }
    return result;
}

}  // namespace

dvec3 QuantizedRay::lowerPoint() const {
    dvec3 p;
    const double s = 1.0 / double(1 << kFracBits);
    double mm = 0.0, uu = double(U0) * s, vv = double(V0) * s;
    p[main] = (sign & axisBit(main)) ? double(L) - mm : mm;
    p[u] = (sign & axisBit(u)) ? double(L) - uu : uu;
    p[v] = (sign & axisBit(v)) ? double(L) - vv : vv;
    return p;
}

dvec3 QuantizedRay::upperPoint() const {
    dvec3 p;
    const double s = 1.0 / double(1 << kFracBits);
    double mm = double(L), uu = double(U0 + dU) * s, vv = double(V0 + dV) * s;
    p[main] = (sign & axisBit(main)) ? double(L) - mm : mm;
    p[u] = (sign & axisBit(u)) ? double(L) - uu : uu;
    p[v] = (sign & axisBit(v)) ? double(L) - vv : vv;
    return p;
}

double QuantizedRay::eyeParameter() const { return std::ldexp(double(eyeM), -(N + Q)); }

QuantizedRay quantizeRay(const dvec3& o, const dvec3& d) {
    QuantizedRay r;
    int main = 0;
    for (int a = 1; a < 3; ++a)
        if (std::abs(d[a]) > std::abs(d[main])) main = a;
    if (!(std::abs(d[main]) > 0.0) || !std::isfinite(d[main])) return r;
    r.main = main;
    r.u = main == 0 ? 1 : 0;
    r.v = main == 2 ? 1 : 2;
    dvec3 om, dm;
    for (int a = 0; a < 3; ++a) {
        if (d[a] < 0.0) r.sign |= axisBit(a);
        om[a] = d[a] < 0.0 ? double(L) - o[a] : o[a];
        dm[a] = std::abs(d[a]);
    }
    const double t0 = (0.0 - om[main]) / dm[main], t1 = (double(L) - om[main]) / dm[main];
    const double u0 = om[r.u] + t0 * dm[r.u], u1 = om[r.u] + t1 * dm[r.u];
    const double v0 = om[r.v] + t0 * dm[r.v], v1 = om[r.v] + t1 * dm[r.v];
    // A ray crossing the cube has |u|, |v| within (-L, 2L) on both planes; anything far
    // outside misses (and would overflow the fixed point).
    auto far = [](double x) { return !(x > -2.0 * L && x < 3.0 * L); };
    if (far(u0) || far(u1) || far(v0) || far(v1) || !(om[main] < double(L))) return r;
    const double scale = double(1 << QuantizedRay::kFracBits);
    // Round half up (floor(x + 1/2)): cheaper than llround, and the same for both signs' ties
    // up to the documented rule; |x| < 2^42 so the double is exact before flooring.
    auto fix = [](double x) { return i64(std::floor(x + 0.5)); };
    r.U0 = fix(u0 * scale);
    r.dU = fix(u1 * scale) - r.U0;
    r.V0 = fix(v0 * scale);
    r.dV = fix(v1 * scale) - r.V0;
    r.eyeM = om[main] > 0.0 ? fix(om[main] * scale) : 0;
    // floor of u at the eye's plane: (U0 * 2^(N+Q) + eyeM * dU) / 2^(N+2Q), exactly.
    r.uEyeFloor = floorShift((r.U0 << (N + Q)) + r.eyeM * r.dU, N + 2 * Q);
    r.vEyeFloor = floorShift((r.V0 << (N + Q)) + r.eyeM * r.dV, N + 2 * Q);
    i64 cU = r.dU == 0 ? 1 : 0, cV = r.dV == 0 ? 1 : 0;
    r.meetsCube = rootCrossed(r, cU, cV, r.U0 << N, (r.U0 + r.dU) << N, r.V0 << N, (r.V0 + r.dV) << N);
    return r;
}

TraversalHit traverseDiscrete(const Octree& tree, const QuantizedRay& ray, TraversalCounters& counters) {
    return traverse<false>(tree, ray, counters, nullptr);
}

TraversalHit traverseDiscreteObserved(const Octree& tree, const QuantizedRay& ray, TraversalCounters& counters,
                                      const std::function<void(unsigned, unsigned)>& observe) {
    return traverse<true>(tree, ray, counters, &observe);
}

}  // namespace octrace
