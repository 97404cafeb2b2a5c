#include "octrace/render/DiscreteTraversal.h"
#include "render/traversal/DiscreteLattice.h"

#include "octrace/render/Lod.h"
#include "octrace/render/OrderTable.h"

#include <array>
#include <bit>
#include <cmath>
#include <limits>
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace octrace {
namespace {

using namespace lattice;

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

/// OrderTable::instance(), kept here: an engine is made per ray, and the call is in another file.
const OrderTable& orderTable() {
    static const OrderTable& t = OrderTable::instance();
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
    bool lazy;            // guided mode: state not computed yet, path child comes first
    unsigned pathChild;   // guided mode: the child on the path
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

bool boxCrossed(const QuantizedRay& r, i64 cU, i64 cV, i64 m0, i64 u0, i64 v0, i64 s) {
    const i64 Wu0 = (r.U0 << N) + m0 * r.dU, Wu1 = (r.U0 << N) + (m0 + s) * r.dU;
    const i64 Wv0 = (r.V0 << N) + m0 * r.dV, Wv1 = (r.V0 << N) + (m0 + s) * r.dV;
    auto F = [&](i64 a, i64 b) { return ((a << Q) - r.U0) * r.dV - ((b << Q) - r.V0) * r.dU; };
    return boxCrossedFrom(r, cU, cV, m0, u0, v0, s, Wu0, Wu1, Wv0, Wv1, F(u0, v0 + s), F(u0 + s, v0));
}

/// predecessors[s][z]: children that some ray with sign pattern s can visit before child z
/// (their mirrored bits are a proper subset of z's).
struct Predecessors {
    std::array<std::array<std::uint8_t, 8>, 8> mask{};
    Predecessors() {
        for (unsigned s = 0; s < 8; ++s)
            for (unsigned z = 0; z < 8; ++z)
                for (unsigned y = 0; y < 8; ++y) {
                    unsigned ym = y ^ s, zm = z ^ s;
                    if (ym != zm && (ym & zm) == ym) mask[s][z] |= std::uint8_t(1u << y);
                }
    }
};
const Predecessors& predecessors() {
    static const Predecessors p;
    return p;
}

/// The traversal: a stack of nodes, each with the ordered list of its crossed non-empty
/// children. Frames may be *lazy* (guided mode): their state byte is computed only if the
/// search comes back to them, because no non-empty child can precede the path child.
template <bool kObserve>
class Engine {
public:
    Engine(const Octree& tree, const QuantizedRay& r, TraversalCounters& counters,
           const std::function<void(unsigned, unsigned)>* observe)
        : tree_(tree), r_(r), counters_(counters), observe_(observe), order_(orderTable()) {
        const Tables& T = tables();
        k_ = RayConsts{&r, r.dU == 0 ? 1 : 0, r.dV == 0 ? 1 : 0, T.toOriginal[std::size_t(r.main)][r.sign].data(),
                       T.toCanonical[std::size_t(r.main)][r.sign].data()};
    }

    /// Puts the node (mirrored box origin, level) at the bottom of the stack with its state
    /// computed directly from the ray (a few multiplications).
    void start(std::uint32_t node, int level, i64 m0, i64 u0, i64 v0) {
        setFrame(node, level, m0, u0, v0);
        if (!computeOrder(stack_[0])) sp_ = -1;
    }

    /// As start(), only if the ray crosses the node's box (boxCrossed, sharing its products
    /// with the frame); false, and nothing to run, otherwise.
    bool startIfCrossed(std::uint32_t node, int level, i64 m0, i64 u0, i64 v0) {
        setFrame(node, level, m0, u0, v0);
        const NodeState& f = stack_[0];
        const i64 s = i64(1) << (N - level);
        // boxCrossed's tests, with the frame's lower/upper points; F at the two corners from
        // F at the centre (F is linear, dF/du = dV << Q, dF/dv = -dU << Q, and s/2 away).
        const i64 qa = r_.dV << (Q + N - level - 1), qb = r_.dU << (Q + N - level - 1);
        if (!boxCrossedFrom(r_, k_.cU, k_.cV, m0, u0, v0, s, f.Wu0, f.Wu1, f.Wv0, f.Wv1, f.Fc - qa - qb, f.Fc + qa + qb)) {
            sp_ = -1;
            return false;
        }
        if (!computeOrder(stack_[0])) sp_ = -1;
        return true;
    }

    /// Bottom frame without its state byte.
    void setFrame(std::uint32_t node, int level, i64 m0, i64 u0, i64 v0) {
        sp_ = 0;
        NodeState& f = stack_[0];
        const i64 s = i64(1) << (N - level), h = s >> 1;
        f.node = node;
        f.level = level;
        f.m0 = m0;
        f.u0 = u0;
        f.v0 = v0;
        const i64 U = r_.U0 << N, V = r_.V0 << N;
        f.Wu0 = U + m0 * r_.dU;
        f.Wu1 = f.Wu0 + s * r_.dU;
        f.Wv0 = V + m0 * r_.dV;
        f.Wv1 = f.Wv0 + s * r_.dV;
        f.Fc = (((u0 + h) << Q) - r_.U0) * r_.dV - (((v0 + h) << Q) - r_.V0) * r_.dU;
        f.partial = (m0 << Q) < r_.eyeM;
        f.lazy = false;
        f.pathChild = 0;
        f.pos = 0;
        f.order = 0;
    }

    void setCut(const LodCut* cut) { cut_ = cut && cut->active() ? cut : nullptr; }
    void setFilter(const VoxelFilter* filter) { filter_ = filter && *filter ? filter : nullptr; }

    /// Guided mode: frames on this path above `guideLevel` become lazy where they can.
    void guide(const BranchNode* b) { guide_ = b; }
    bool resumedOrComputedOnPath() const { return onPathWork_; }

    TraversalHit run() {
        TraversalHit result;
        while (sp_ >= 0) {
            NodeState& n = stack_[sp_];
            unsigned c;
            if (n.lazy) {
                if (n.pos == 0) {
                    c = n.pathChild;
                    n.pos = 1;
                } else {
                    // The path child held no hit: come back and finish this node properly.
                    n.lazy = false;
                    onPathWork_ = true;
                    computeOrder(n);
                    // No non-empty child precedes the path child, so it is first in the list.
                    n.pos = 1;
                    continue;
                }
            } else {
                if (n.pos >= OrderTable::count(n.order)) {
                    --sp_;
                    continue;
                }
                c = unsigned(OrderTable::child(n.order, n.pos++));
            }
            const OctreeNode& nd = tree_.nodes()[n.node];
            const std::uint32_t slot = nd.firstChild + childRank(nd.childMask, c);
            const unsigned ci = k_.toCanonical[c];
            const unsigned hm = ci >> 2, hu = (ci >> 1) & 1, hv = ci & 1;
            const int lg = N - n.level - 1;
            const i64 h = i64(1) << lg;
            const bool coarseLeaf = (nd.termMask & (1u << c)) && tree_.form == OctreeForm::Shell;
            if (n.level == tree_.depth - 1 || coarseLeaf) {
                // Child is a voxel (or a coarse leaf) and the first crossed one in order: the hit.
                i64 mirrored[3];
                mirrored[r_.main] = n.m0 + hm * h;
                mirrored[r_.u] = n.u0 + hu * h;
                mirrored[r_.v] = n.v0 + hv * h;
                result.cell = unmirroredCell(r_, mirrored, h, tree_.depth);
                result.voxel = coarseLeaf ? tree_.nodes()[slot].firstChild : slot;
                result.leafShift = tree_.depth - n.level - 1;
                if (filter_ && !(*filter_)(result)) {
                    result = TraversalHit{};  // passed: go on behind it
                    continue;
                }
                return result;
            }
            if (nd.termMask & (1u << c)) continue;  // interior terms: volume form, not drawn by this shell renderer
            if (cut_) {
                // Multi-resolution: the crossed non-empty child may be drawn as a whole.
                const int level = n.level + 1;
                i64 mirrored[3];
                mirrored[r_.main] = n.m0 + hm * h;
                mirrored[r_.u] = n.u0 + hu * h;
                mirrored[r_.v] = n.v0 + hv * h;
                const ivec3 cell = unmirroredCell(r_, mirrored, h, level);
                if (cut_->stops(level, cell)) {
                    result.voxel = tree_.summaries()[slot].firstVoxel;
                    result.cell = cell;
                    result.node = slot;
                    result.level = level;
                    return result;
                }
            }
            const i64 Wuc = (n.Wu0 + n.Wu1) >> 1, Wvc = (n.Wv0 + n.Wv1) >> 1;
            NodeState& ch = stack_[sp_ + 1];
            ch.node = slot;
            ch.level = n.level + 1;
            ch.m0 = n.m0 + hm * h;
            ch.u0 = n.u0 + hu * h;
            ch.v0 = n.v0 + hv * h;
            ch.Wu0 = hm ? Wuc : n.Wu0;
            ch.Wu1 = hm ? n.Wu1 : Wuc;
            ch.Wv0 = hm ? Wvc : n.Wv0;
            ch.Wv1 = hm ? n.Wv1 : Wvc;
            const i64 qa = r_.dV << (Q + lg - 1), qb = r_.dU << (Q + lg - 1);
            ch.Fc = n.Fc + (hu ? qa : -qa) - (hv ? qb : -qb);
            ch.partial = n.partial && (ch.m0 << Q) < r_.eyeM;
            ch.lazy = false;
            ch.pathChild = 0;
            if (guide_ && ch.level < guide_->level && slot == guide_->path[ch.level]) {
                const unsigned z = guide_->childIndex[ch.level];
                const unsigned childMask = tree_.nodes()[slot].childMask;
                if ((childMask & predecessors().mask[r_.sign][z]) == 0) {
                    ch.lazy = true;
                    ch.pathChild = z;
                    ch.pos = 0;
                    ++counters_.statesDeferred;
                    ++sp_;
                    continue;
                }
                onPathWork_ = true;
            }
            if (computeOrder(ch)) ++sp_;
        }
        return result;
    }

    /// The root, lazily when guided and possible; returns false when the ray misses the cube.
    bool startAtRoot() {
        if (!r_.meetsCube || tree_.nodes().empty()) return false;
        if (guide_ && guide_->level > 0) {
            const unsigned z = guide_->childIndex[0];
            if ((tree_.nodes()[0].childMask & predecessors().mask[r_.sign][z]) == 0) {
                setFrame(0, 0, 0, 0, 0);
                NodeState& f = stack_[0];
                f.lazy = true;
                f.pathChild = z;
                ++counters_.statesDeferred;
                return true;
            }
            onPathWork_ = true;
        }
        start(0, 0, 0, 0, 0);
        return true;
    }

private:
    bool computeOrder(NodeState& f) {
        i64 a, b;
        const unsigned byte = stateByte(k_, f, a, b);
        ++counters_.nodes;
        const unsigned orig = k_.toOriginal[byte];
        if constexpr (kObserve) (*observe_)(r_.sign, orig);
        f.order = order_.entry(r_.sign, orig & tree_.nodes()[f.node].childMask);
        f.pos = 0;
        return OrderTable::count(f.order) > 0;
    }

    const Octree& tree_;
    const QuantizedRay& r_;
    TraversalCounters& counters_;
    const std::function<void(unsigned, unsigned)>* observe_;
    const OrderTable& order_;
    RayConsts k_{};
    const BranchNode* guide_ = nullptr;
    const LodCut* cut_ = nullptr;
    const VoxelFilter* filter_ = nullptr;
    bool onPathWork_ = false;
    NodeState stack_[Octree::kMaxDepth + 1];
    int sp_ = -1;
};

template <bool kObserve>
TraversalHit traverse(const Octree& tree, const QuantizedRay& r, TraversalCounters& counters,
                      const std::function<void(unsigned, unsigned)>* observe, const LodCut* cut = nullptr,
                      const VoxelFilter* filter = nullptr) {
    if (!r.meetsCube || tree.nodes().empty()) return TraversalHit{};  // before setting up the engine
    Engine<kObserve> e(tree, r, counters, observe);
    e.setCut(cut);
    e.setFilter(filter);
    if (!e.startAtRoot()) return TraversalHit{};
    return e.run();
}

/// Exact test whether the ray crosses the branch node; gives the node's mirrored origin.
bool branchCrossed(const QuantizedRay& r, const BranchNode& b, i64& m0, i64& u0, i64& v0) {
    mirroredOrigin(r, b.cell, b.level, m0, u0, v0);
    return boxCrossed(r, r.dU == 0, r.dV == 0, m0, u0, v0, i64(1) << (N - b.level));
}

}  // namespace

namespace {
/// A point given in mirrored (main, u, v) coordinates, back in original octree space.
dvec3 unmirror(const QuantizedRay& r, double mm, double uu, double vv) {
    dvec3 p;
    p[r.main] = (r.sign & axisBit(r.main)) ? double(L) - mm : mm;
    p[r.u] = (r.sign & axisBit(r.u)) ? double(L) - uu : uu;
    p[r.v] = (r.sign & axisBit(r.v)) ? double(L) - vv : vv;
    return p;
}
}  // namespace

dvec3 QuantizedRay::lowerPoint() const {
    const double s = 1.0 / double(1 << kFracBits);
    return unmirror(*this, 0.0, double(U0) * s, double(V0) * s);
}

dvec3 QuantizedRay::upperPoint() const {
    const double s = 1.0 / double(1 << kFracBits);
    return unmirror(*this, double(L), double(U0 + dU) * s, double(V0 + dV) * s);
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
    if (!(om[main] < double(L))) return r;  // the eye is past the cube's far plane
    const double inv = 1.0 / dm[main];
    const double t0 = (0.0 - om[main]) * inv, t1 = (double(L) - om[main]) * inv;
    const double u0 = om[r.u] + t0 * dm[r.u], u1 = om[r.u] + t1 * dm[r.u];
    const double v0 = om[r.v] + t0 * dm[r.v], v1 = om[r.v] + t1 * dm[r.v];
    // u and v grow along the (mirrored) ray: a line whose u or v range between the two main
    // planes lies more than a lattice unit outside [0, L] misses the cube whatever the
    // rounding (and far-off values would overflow the fixed point).
    if (!(u1 > -1.0 && u0 < double(L) + 1.0 && v1 > -1.0 && v0 < double(L) + 1.0)) return r;
    auto far = [](double x) { return !(x > -2.0 * L && x < 3.0 * L); };
    if (far(u0) || far(u1) || far(v0) || far(v1)) return r;
    const double scale = double(1 << QuantizedRay::kFracBits);
    // Round half up (floor(x + 1/2)): cheaper than llround, and the same for both signs' ties
    // up to the documented rule; |x| < 2^42 so the double is exact before flooring.
    auto fix = [](double x) {
        const double y = x + 0.5;
        i64 t = i64(y);  // truncates towards zero
        return t - (double(t) > y ? 1 : 0);
    };
    r.U0 = fix(u0 * scale);
    r.dU = fix(u1 * scale) - r.U0;
    r.V0 = fix(v0 * scale);
    r.dV = fix(v1 * scale) - r.V0;
    r.eyeM = om[main] > 0.0 ? fix(om[main] * scale) : 0;
    // floor of u at the eye's plane: (U0 * 2^(N+Q) + eyeM * dU) / 2^(N+2Q), exactly.
    r.uEyeFloor = floorShift((r.U0 << (N + Q)) + r.eyeM * r.dU, N + 2 * Q);
    r.vEyeFloor = floorShift((r.V0 << (N + Q)) + r.eyeM * r.dV, N + 2 * Q);
    i64 cU = r.dU == 0 ? 1 : 0, cV = r.dV == 0 ? 1 : 0;
    r.meetsCube = boxCrossed(r, cU, cV, 0, 0, 0, L);
    return r;
}

#if defined(__x86_64__) && defined(__GNUC__)
namespace {
/// quantizeRay's fix(x * 2^Q): floor(x * 2^Q + 1/2) by truncation and a correction, lane by lane.
[[gnu::target("avx512f,avx512dq")]] inline __m512i fixEight(__m512d x) {
    const __m512d y = _mm512_add_pd(_mm512_mul_pd(x, _mm512_set1_pd(double(1 << QuantizedRay::kFracBits))), _mm512_set1_pd(0.5));
    const __m512i t = _mm512_cvttpd_epi64(y);
    const __mmask8 above = _mm512_cmp_pd_mask(_mm512_cvtepi64_pd(t), y, _CMP_GT_OQ);
    return _mm512_mask_sub_epi64(t, above, t, _mm512_set1_epi64(1));
}

/// quantizeRay for eight rays from one origin in AVX-512 registers (F and DQ): every double the
/// scalar code computes is computed here by the same operation on the same operands (no fused
/// multiply-add: the build passes -ffp-contract=off, without which GCC fuses them here, where the
/// target has FMA), and the fixed-point conversions are exact in both, so every field has the
/// same bits. A lane that takes one of the scalar code's early returns (a zero or non-finite
/// direction, an eye past the far plane, a line far off the cube) is left to the scalar code:
/// `scalar` gets its bit.
[[gnu::target("avx512f,avx512dq")]] void quantizeEight(const dvec3& o, const dvec3* d, QuantizedRay* out, unsigned& scalar) {
    alignas(64) double dx[8], dy[8], dz[8];
    for (int l = 0; l < 8; ++l) {
        dx[l] = d[l].x;
        dy[l] = d[l].y;
        dz[l] = d[l].z;
    }
    const __m512d zero = _mm512_setzero_pd(), Ld = _mm512_set1_pd(double(L)), one = _mm512_set1_pd(1.0);
    const __m512d signBit = _mm512_set1_pd(-0.0);
    const __m512d D[3] = {_mm512_load_pd(dx), _mm512_load_pd(dy), _mm512_load_pd(dz)};
    __m512d om[3], dm[3];
    __mmask8 neg[3];
    for (int a = 0; a < 3; ++a) {
        neg[a] = _mm512_cmp_pd_mask(D[a], zero, _CMP_LT_OQ);
        const __m512d O = _mm512_set1_pd(o[a]);
        om[a] = _mm512_mask_blend_pd(neg[a], O, _mm512_sub_pd(Ld, O));
        dm[a] = _mm512_andnot_pd(signBit, D[a]);
    }
    // main: the first axis of largest |d| (strictly larger replaces).
    const __mmask8 m1 = _mm512_cmp_pd_mask(dm[1], dm[0], _CMP_GT_OQ);
    const __m512d d01 = _mm512_mask_blend_pd(m1, dm[0], dm[1]);
    const __mmask8 m2 = _mm512_cmp_pd_mask(dm[2], d01, _CMP_GT_OQ);
    const __mmask8 main0 = __mmask8(~(m1 | m2)), main1 = __mmask8(m1 & ~m2);
    // (main, u, v) = (0, 1, 2), (1, 0, 2) or (2, 0, 1).
    const __m512d omM = _mm512_mask_blend_pd(m2, _mm512_mask_blend_pd(m1, om[0], om[1]), om[2]);
    const __m512d dmM = _mm512_mask_blend_pd(m2, d01, dm[2]);
    const __m512d omU = _mm512_mask_blend_pd(main0, om[0], om[1]), dmU = _mm512_mask_blend_pd(main0, dm[0], dm[1]);
    const __m512d omV = _mm512_mask_blend_pd(m2, om[2], om[1]), dmV = _mm512_mask_blend_pd(m2, dm[2], dm[1]);
    // The scalar code's early returns, lane by lane.
    const __mmask8 finite = _mm512_cmp_pd_mask(dmM, _mm512_set1_pd(std::numeric_limits<double>::infinity()), _CMP_LT_OQ);
    __mmask8 ok = __mmask8(_mm512_cmp_pd_mask(dmM, zero, _CMP_GT_OQ) & finite & _mm512_cmp_pd_mask(omM, Ld, _CMP_LT_OQ));
    const __m512d inv = _mm512_div_pd(one, dmM);
    const __m512d t0 = _mm512_mul_pd(_mm512_sub_pd(zero, omM), inv), t1 = _mm512_mul_pd(_mm512_sub_pd(Ld, omM), inv);
    const __m512d u0 = _mm512_add_pd(omU, _mm512_mul_pd(t0, dmU)), u1 = _mm512_add_pd(omU, _mm512_mul_pd(t1, dmU));
    const __m512d v0 = _mm512_add_pd(omV, _mm512_mul_pd(t0, dmV)), v1 = _mm512_add_pd(omV, _mm512_mul_pd(t1, dmV));
    const __m512d minus1 = _mm512_set1_pd(-1.0), L1 = _mm512_add_pd(Ld, one);
    ok &= _mm512_cmp_pd_mask(u1, minus1, _CMP_GT_OQ) & _mm512_cmp_pd_mask(u0, L1, _CMP_LT_OQ) & _mm512_cmp_pd_mask(v1, minus1, _CMP_GT_OQ) &
          _mm512_cmp_pd_mask(v0, L1, _CMP_LT_OQ);
    const __m512d farLo = _mm512_set1_pd(-2.0 * double(L)), farHi = _mm512_set1_pd(3.0 * double(L));
    for (const __m512d& x : {u0, u1, v0, v1})
        ok &= __mmask8(_mm512_cmp_pd_mask(x, farLo, _CMP_GT_OQ) & _mm512_cmp_pd_mask(x, farHi, _CMP_LT_OQ));
    scalar = unsigned(__mmask8(~ok));
    if (!ok) return;
    // fix(x * scale): floor(x * scale + 1/2) by truncation and a correction, as the scalar code.
    const __m512i U0 = fixEight(u0), V0 = fixEight(v0);
    const __m512i dU = _mm512_sub_epi64(fixEight(u1), U0), dV = _mm512_sub_epi64(fixEight(v1), V0);
    const __m512i eyeM = _mm512_maskz_mov_epi64(_mm512_cmp_pd_mask(omM, zero, _CMP_GT_OQ), fixEight(omM));
    const __m512i uEye = _mm512_maskz_srai_epi64(0xFF, _mm512_add_epi64(_mm512_maskz_slli_epi64(0xFF, U0, N + Q), _mm512_mullo_epi64(eyeM, dU)), N + 2 * Q);
    const __m512i vEye = _mm512_maskz_srai_epi64(0xFF, _mm512_add_epi64(_mm512_maskz_slli_epi64(0xFF, V0, N + Q), _mm512_mullo_epi64(eyeM, dV)), N + 2 * Q);
    // boxCrossed(r, cU, cV, 0, 0, 0, L), term by term (cU, cV: 1 where dU, dV are 0).
    const __m512i zeroI = _mm512_setzero_si512(), oneI = _mm512_set1_epi64(1), LI = _mm512_set1_epi64(L);
    const __m512i cU = _mm512_maskz_mov_epi64(_mm512_cmpeq_epi64_mask(dU, zeroI), oneI);
    const __m512i cV = _mm512_maskz_mov_epi64(_mm512_cmpeq_epi64_mask(dV, zeroI), oneI);
    const __m512i U0N = _mm512_maskz_slli_epi64(0xFF, U0, N), V0N = _mm512_maskz_slli_epi64(0xFF, V0, N);
    const __m512i far = _mm512_set1_epi64(L << (N + Q)), LQ = _mm512_set1_epi64(L << Q);
    const __m512i Wu1 = _mm512_add_epi64(U0N, _mm512_mullo_epi64(LI, dU)), Wv1 = _mm512_add_epi64(V0N, _mm512_mullo_epi64(LI, dV));
    // F(a, b) = ((a << Q) - U0) dV - ((b << Q) - V0) dU at (0, L) and (L, 0).
    const __m512i Fuv1 = _mm512_sub_epi64(_mm512_mullo_epi64(_mm512_sub_epi64(zeroI, U0), dV), _mm512_mullo_epi64(_mm512_sub_epi64(LQ, V0), dU));
    const __m512i Fu1v = _mm512_sub_epi64(_mm512_mullo_epi64(_mm512_sub_epi64(LQ, U0), dV), _mm512_mullo_epi64(_mm512_sub_epi64(zeroI, V0), dU));
    const __mmask8 meets = _mm512_cmplt_epi64_mask(U0N, far) & _mm512_cmpgt_epi64_mask(Wu1, _mm512_sub_epi64(zeroI, cU)) &
                           _mm512_cmplt_epi64_mask(V0N, far) & _mm512_cmpgt_epi64_mask(Wv1, _mm512_sub_epi64(zeroI, cV)) &
                           _mm512_cmplt_epi64_mask(Fuv1, cU) & _mm512_cmpgt_epi64_mask(Fu1v, _mm512_sub_epi64(zeroI, cV)) &
                           _mm512_cmplt_epi64_mask(eyeM, LQ) & _mm512_cmplt_epi64_mask(uEye, LI) & _mm512_cmplt_epi64_mask(vEye, LI);
    alignas(64) i64 f[7][8];
    _mm512_store_si512(f[0], U0);
    _mm512_store_si512(f[1], dU);
    _mm512_store_si512(f[2], V0);
    _mm512_store_si512(f[3], dV);
    _mm512_store_si512(f[4], eyeM);
    _mm512_store_si512(f[5], uEye);
    _mm512_store_si512(f[6], vEye);
    for (unsigned l = 0; l < 8; ++l) {
        if (!(ok >> l & 1u)) continue;
        QuantizedRay& r = out[l];
        r = QuantizedRay{};
        r.main = (main0 >> l & 1u) ? 0 : (main1 >> l & 1u) ? 1 : 2;
        r.u = r.main == 0 ? 1 : 0;
        r.v = r.main == 2 ? 1 : 2;
        for (int a = 0; a < 3; ++a)
            if (neg[a] >> l & 1u) r.sign |= axisBit(a);
        r.U0 = f[0][l];
        r.dU = f[1][l];
        r.V0 = f[2][l];
        r.dV = f[3][l];
        r.eyeM = f[4][l];
        r.uEyeFloor = f[5][l];
        r.vEyeFloor = f[6][l];
        r.meetsCube = meets >> l & 1u;
    }
}
}  // namespace
#endif

void quantizeRays(const dvec3& origin, const dvec3* directions, int n, QuantizedRay* out) {
    int i = 0;
#if defined(__x86_64__) && defined(__GNUC__)
    static const bool avx512 = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq");
    if (avx512)
        for (; i + 8 <= n; i += 8) {
            unsigned scalar = 0;
            quantizeEight(origin, directions + i, out + i, scalar);
            for (; scalar; scalar &= scalar - 1) {
                const int l = std::countr_zero(scalar);
                out[i + l] = quantizeRay(origin, directions[i + l]);
            }
        }
#endif
    for (; i < n; ++i) out[i] = quantizeRay(origin, directions[i]);
}

TraversalHit traverseDiscrete(const Octree& tree, const QuantizedRay& ray, TraversalCounters& counters,
                              const LodCut* cut, const VoxelFilter* filter) {
    return traverse<false>(tree, ray, counters, nullptr, cut, filter);
}

TraversalHit traverseDiscreteObserved(const Octree& tree, const QuantizedRay& ray, TraversalCounters& counters,
                                      const std::function<void(unsigned, unsigned)>& observe) {
    return traverse<true>(tree, ray, counters, &observe);
}

bool rayCrossesCell(const QuantizedRay& ray, const ivec3& cell, int level) {
    if (!ray.meetsCube) return false;
    i64 m0, u0, v0;
    mirroredOrigin(ray, cell, level, m0, u0, v0);
    return boxCrossed(ray, ray.dU == 0, ray.dV == 0, m0, u0, v0, i64(1) << (N - level));
}

BranchNode branchNode(const Octree& tree, const ivec3& a, const ivec3& b, int up) {
    BranchNode bn;
    const int depth = tree.depth;
    const unsigned diff = unsigned((a.x ^ b.x) | (a.y ^ b.y) | (a.z ^ b.z));
    const int width = diff ? 32 - std::countl_zero(diff) : 0;
    int level = std::min(depth - width, depth - 1);
    if (up > 0 && level >= 0) level = std::max(level - up, 0);
    if (level < 0 || tree.nodes().empty()) return bn;
    std::uint32_t node = 0;
    bn.path[0] = 0;
    for (int l = 0; l < level; ++l) {
        const int shift = depth - 1 - l;
        const unsigned c = unsigned(((a.x >> shift) & 1) << 2 | ((a.y >> shift) & 1) << 1 | ((a.z >> shift) & 1));
        const OctreeNode& nd = tree.nodes()[node];
        if (!(nd.childMask & (1u << c))) return BranchNode{};  // not a voxel's path
        if (nd.termMask & (1u << c)) {
            if (tree.form != OctreeForm::Shell) return BranchNode{};  // an interior term: not a voxel's path
            // A coarse leaf holds both cells: its parent is the branch node.
            bn.level = l;
            bn.cell = a >> (depth - l);
            return bn;
        }
        bn.childIndex[l] = std::uint8_t(c);
        node = nd.firstChild + childRank(nd.childMask, c);
        bn.path[l + 1] = node;
    }
    bn.level = level;
    bn.cell = a >> (depth - level);
    return bn;
}

TraversalHit traverseFromNodes(const Octree& tree, const QuantizedRay& ray, const StartNode* nodes, std::size_t count,
                               TraversalCounters& counters, const VoxelFilter* filter, const LodCut* cut) {
    if (!ray.meetsCube || count == 0) return TraversalHit{};
    Engine<false> e(tree, ray, counters, nullptr);
    e.setFilter(filter);
    e.setCut(cut);
    for (std::size_t i = 0; i < count; ++i) {
        const StartNode& n = nodes[i];
        i64 m0, u0, v0;
        mirroredOrigin(ray, n.cell, n.level, m0, u0, v0);
        // The state byte leaves out the tests that follow from the node being crossed: check it.
        if (!e.startIfCrossed(n.node, n.level, m0, u0, v0)) continue;
        const TraversalHit hit = e.run();
        if (hit.hit()) return hit;
    }
    return TraversalHit{};
}

TraversalHit traverseFromNode(const Octree& tree, const QuantizedRay& ray, std::uint32_t node, int level,
                              const ivec3& cell, TraversalCounters& counters) {
    const StartNode n{node, level, cell};
    return traverseFromNodes(tree, ray, &n, 1, counters);
}

TraversalHit traverseFromBranch(const Octree& tree, const QuantizedRay& ray, const BranchNode& branch,
                                TraversalCounters& counters, bool& fellBack) {
    fellBack = true;
    if (!ray.meetsCube || !branch.valid()) return traverseDiscrete(tree, ray, counters);
    i64 m0, u0, v0;
    if (branchCrossed(ray, branch, m0, u0, v0)) {
        Engine<false> e(tree, ray, counters, nullptr);
        e.start(branch.path[branch.level], branch.level, m0, u0, v0);
        TraversalHit hit = e.run();
        if (hit.hit()) {
            fellBack = false;
            return hit;
        }
    }
    return traverseDiscrete(tree, ray, counters);
}

std::uint8_t predecessorChildren(unsigned sign, unsigned child) { return predecessors().mask[sign & 7u][child & 7u]; }

TraversalHit traverseGuided(const Octree& tree, const QuantizedRay& ray, const BranchNode& branch,
                            TraversalCounters& counters, bool& certified) {
    certified = false;
    if (!ray.meetsCube || !branch.valid()) return traverseDiscrete(tree, ray, counters);
    // Deferring is possible only where no non-empty child can precede the path child; when no
    // path node allows it, the guided traversal is the full one (skip the set-up).
    bool anyDeferrable = false;
    for (int l = 0; l < branch.level && !anyDeferrable; ++l)
        anyDeferrable = (tree.nodes()[branch.path[l]].childMask & predecessors().mask[ray.sign][branch.childIndex[l]]) == 0;
    if (!anyDeferrable) return traverseDiscrete(tree, ray, counters);
    // The path frames may be taken on trust only if the ray crosses the branch node (and so
    // every node above it on the path).
    i64 m0, u0, v0;
    if (!branchCrossed(ray, branch, m0, u0, v0)) return traverseDiscrete(tree, ray, counters);
    Engine<false> e(tree, ray, counters, nullptr);
    e.guide(&branch);
    if (!e.startAtRoot()) return TraversalHit{};
    TraversalHit hit = e.run();
    certified = hit.hit() && !e.resumedOrComputedOnPath();
    return hit;
}

}  // namespace octrace
