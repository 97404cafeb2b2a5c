// The discrete traversal of several rays at once: docs/dev/tile-renderer.md, "Packets".
#include "render/traversal/PacketTraversal.h"
#include "render/traversal/DiscreteLattice.h"
#include "render/Transpose8.h"

#include "octrace/render/Lod.h"

#include <algorithm>
#include <cassert>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#if defined(__x86_64__) || defined(__i386__)
#define OCTRACE_PACKET_X86 1
#include <immintrin.h>
#endif

namespace octrace::detail {
namespace {

using namespace lattice;

/// What the lanes share (the start node, in their common mirrored frame) and each lane's start
/// values, as doubles (exact: setupPacket checks the magnitudes).
struct PacketSetup {
    alignas(64) double Wu0[kMaxPacketLanes], Wu1[kMaxPacketLanes], Wv0[kMaxPacketLanes], Wv1[kMaxPacketLanes], Fc[kMaxPacketLanes];
    alignas(64) double cU[kMaxPacketLanes], cV[kMaxPacketLanes], dUq[kMaxPacketLanes], dVq[kMaxPacketLanes];
    unsigned active = 0;  ///< lanes that cross the node and that the packet takes
    i64 m0 = 0, u0 = 0, v0 = 0;
    std::uint32_t node = 0;
    int level = 0;
    int main = 0, u = 1, v = 2;
    std::uint8_t toOriginal[8] = {};  ///< canonical child index (hm, hu, hv) -> original child index
    const SmoothSurface* smooth = nullptr;  ///< traversePacket's `smooth`
};

// Every value of the traversal below the node is a start value plus or minus terms of at most
// (|dU| + |dV|) 2^(Q + lg) in all (the halvings of F's steps sum to less than that, and the
// comparisons add Ah + Bh): within 2^52 when both parts are within 2^50.
constexpr i64 kBound = i64(1) << 50;

#if defined(OCTRACE_PACKET_X86)
static_assert(offsetof(QuantizedRay, dU) == offsetof(QuantizedRay, U0) + 8 && offsetof(QuantizedRay, V0) == offsetof(QuantizedRay, U0) + 16 &&
                  offsetof(QuantizedRay, dV) == offsetof(QuantizedRay, U0) + 24 && offsetof(QuantizedRay, eyeM) == offsetof(QuantizedRay, U0) + 32 &&
                  offsetof(QuantizedRay, uEyeFloor) == offsetof(QuantizedRay, U0) + 40 &&
                  offsetof(QuantizedRay, vEyeFloor) == offsetof(QuantizedRay, U0) + 48,
              "setupLanesAvx512 loads QuantizedRay's seven 64-bit fields from U0 on");

/// The lanes' part of setupPacket eight lanes at a time in AVX-512 registers (F and DQ): the
/// same 64-bit integer operations (wrapping alike), compared and converted to double exactly as
/// the scalar code, so the same start values, the same active lanes and the same lanes for the
/// scalar engine.
[[gnu::target("avx512f,avx512dq")]] void setupLanesAvx512(const PacketLane* lanes, unsigned count, PacketSetup& p, unsigned& scalar, i64 s,
                                                          i64 h, int lg) {
    const __m512i zero = _mm512_setzero_si512(), one = _mm512_set1_epi64(1), bound = _mm512_set1_epi64(kBound);
    const __m512i m0 = _mm512_set1_epi64(p.m0), S = _mm512_set1_epi64(s), shiftQlg = _mm512_set1_epi64(Q + lg);
    const __m512i uMid = _mm512_set1_epi64((p.u0 + h) << Q), vMid = _mm512_set1_epi64((p.v0 + h) << Q);
    const __m512i uHi = _mm512_set1_epi64((p.u0 + s) << (N + Q)), uLo = _mm512_set1_epi64(p.u0 << (N + Q));
    const __m512i vHi = _mm512_set1_epi64((p.v0 + s) << (N + Q)), vLo = _mm512_set1_epi64(p.v0 << (N + Q));
    const __m512i mHi = _mm512_set1_epi64((p.m0 + s) << Q), mLo = _mm512_set1_epi64(p.m0 << Q);
    const __m512i uEnd = _mm512_set1_epi64(p.u0 + s), vEnd = _mm512_set1_epi64(p.v0 + s);
    for (unsigned g = 0; g < kMaxPacketLanes / 8; ++g) {
        // Each lane's seven 64-bit fields (U0 .. vEyeFloor, consecutive) in one register, then
        // transposed: one register per field, lane k in element k.
        __m512i row[8];
        __mmask8 valid = 0;
        for (unsigned k = 0; k < 8; ++k) {
            const unsigned l = 8 * g + k;
            row[k] = l < count ? _mm512_maskz_loadu_epi64(0x7F, &lanes[l].ray->U0) : zero;
            if (l < count) valid |= __mmask8(1u << k);
        }
        __m512i field[8];
        transpose8(row, field);
        const __m512i U0 = field[0], dU = field[1], V0 = field[2], dV = field[3], eyeM = field[4], uEye = field[5], vEye = field[6];
        const __m512i wu0 = _mm512_add_epi64(_mm512_maskz_sllv_epi64(0xFF, U0, _mm512_set1_epi64(N)), _mm512_mullo_epi64(m0, dU));
        const __m512i wu1 = _mm512_add_epi64(wu0, _mm512_mullo_epi64(S, dU));
        const __m512i wv0 = _mm512_add_epi64(_mm512_maskz_sllv_epi64(0xFF, V0, _mm512_set1_epi64(N)), _mm512_mullo_epi64(m0, dV));
        const __m512i wv1 = _mm512_add_epi64(wv0, _mm512_mullo_epi64(S, dV));
        const __m512i fc = _mm512_sub_epi64(_mm512_mullo_epi64(_mm512_sub_epi64(uMid, U0), dV), _mm512_mullo_epi64(_mm512_sub_epi64(vMid, V0), dU));
        const __mmask8 zu = _mm512_cmpeq_epi64_mask(dU, zero), zv = _mm512_cmpeq_epi64_mask(dV, zero);
        const __m512i cu = _mm512_maskz_mov_epi64(zu, one), cv = _mm512_maskz_mov_epi64(zv, one);
        const __m512i qa = _mm512_maskz_sllv_epi64(0xFF, dV, shiftQlg), qb = _mm512_maskz_sllv_epi64(0xFF, dU, shiftQlg);
        const __m512i fuv1 = _mm512_sub_epi64(_mm512_sub_epi64(fc, qa), qb), fu1v = _mm512_add_epi64(_mm512_add_epi64(fc, qa), qb);
        // boxCrossedFrom, term by term.
        __mmask8 crossed = valid & _mm512_cmplt_epi64_mask(wu0, uHi) & _mm512_cmpgt_epi64_mask(wu1, _mm512_sub_epi64(uLo, cu)) &
                           _mm512_cmplt_epi64_mask(wv0, vHi) & _mm512_cmpgt_epi64_mask(wv1, _mm512_sub_epi64(vLo, cv));
        crossed &= _mm512_cmplt_epi64_mask(fuv1, cu) & _mm512_cmpgt_epi64_mask(fu1v, _mm512_sub_epi64(zero, cv)) &
                   _mm512_cmplt_epi64_mask(eyeM, mHi) & _mm512_cmplt_epi64_mask(uEye, uEnd) & _mm512_cmplt_epi64_mask(vEye, vEnd);
        const __m512i steps = _mm512_maskz_sllv_epi64(0xFF, _mm512_add_epi64(_mm512_maskz_abs_epi64(0xFF, dU), _mm512_maskz_abs_epi64(0xFF, dV)), shiftQlg);
        const __mmask8 exact = __mmask8(~_mm512_cmplt_epi64_mask(mLo, eyeM) & _mm512_cmplt_epi64_mask(_mm512_maskz_abs_epi64(0xFF, fc), bound) &
                                        _mm512_cmplt_epi64_mask(steps, bound));
        const __mmask8 active = crossed & exact;
        double* const out[9] = {p.Wu0, p.Wu1, p.Wv0, p.Wv1, p.Fc, p.cU, p.cV, p.dUq, p.dVq};
        const __m512i value[9] = {wu0, wu1, wv0, wv1, fc, cu, cv, _mm512_maskz_sllv_epi64(0xFF, dU, _mm512_set1_epi64(Q)),
                                  _mm512_maskz_sllv_epi64(0xFF, dV, _mm512_set1_epi64(Q))};
        for (int i = 0; i < 9; ++i) _mm512_store_pd(out[i] + 8 * g, _mm512_maskz_cvtepi64_pd(active, value[i]));
        p.active |= unsigned(active) << (8 * g);
        scalar |= unsigned(crossed & __mmask8(~exact)) << (8 * g);
    }
}
#endif

/// The lanes' start on the node, as the scalar engine's startIfCrossed: a lane whose ray does not
/// cross the node has no hit in it; a lane the packet cannot take exactly goes to `scalar`.
void setupPacket(const StartNode& start, const PacketLane* lanes, unsigned count, unsigned width, bool avx512, PacketSetup& p,
                 unsigned& scalar) {
    const QuantizedRay& r0 = *lanes[0].ray;
    mirroredOrigin(r0, start.cell, start.level, p.m0, p.u0, p.v0);
    p.node = start.node;
    p.level = start.level;
    p.main = r0.main;
    p.u = r0.u;
    p.v = r0.v;
    for (unsigned ci = 0; ci < 8; ++ci) {
        const unsigned mirrored = ((ci >> 2) ? axisBit(r0.main) : 0u) | (((ci >> 1) & 1) ? axisBit(r0.u) : 0u) |
                                  ((ci & 1) ? axisBit(r0.v) : 0u);
        p.toOriginal[ci] = std::uint8_t(mirrored ^ r0.sign);
    }
    const int lg = N - start.level - 1;
    const i64 s = i64(1) << (N - start.level), h = s >> 1;
    p.active = 0;
    scalar = 0;
#if defined(OCTRACE_PACKET_X86)
    if (avx512) {
        setupLanesAvx512(lanes, count, p, scalar, s, h, lg);
        return;
    }
#else
    (void)avx512;
#endif
    for (double* a : {p.Wu0, p.Wu1, p.Wv0, p.Wv1, p.Fc, p.cU, p.cV, p.dUq, p.dVq}) std::fill_n(a, width, 0.0);
    for (unsigned l = 0; l < count; ++l) {
        const QuantizedRay& r = *lanes[l].ray;
        const i64 wu0 = (r.U0 << N) + p.m0 * r.dU, wu1 = wu0 + s * r.dU;
        const i64 wv0 = (r.V0 << N) + p.m0 * r.dV, wv1 = wv0 + s * r.dV;
        const i64 fc = (((p.u0 + h) << Q) - r.U0) * r.dV - (((p.v0 + h) << Q) - r.V0) * r.dU;
        const i64 cu = r.dU == 0 ? 1 : 0, cv = r.dV == 0 ? 1 : 0;
        const i64 qa = r.dV << (Q + lg), qb = r.dU << (Q + lg);
        if (!boxCrossedFrom(r, cu, cv, p.m0, p.u0, p.v0, s, wu0, wu1, wv0, wv1, fc - qa - qb, fc + qa + qb)) continue;
        const i64 steps = (std::abs(r.dU) + std::abs(r.dV)) << (Q + lg);
        if ((p.m0 << Q) < r.eyeM || !(std::abs(fc) < kBound && steps < kBound)) {
            scalar |= 1u << l;  // the eye's plane cuts the node (its eye tests), or too coarse a node
            continue;
        }
        p.Wu0[l] = double(wu0);
        p.Wu1[l] = double(wu1);
        p.Wv0[l] = double(wv0);
        p.Wv1[l] = double(wv1);
        p.Fc[l] = double(fc);
        p.cU[l] = double(cu);
        p.cV[l] = double(cv);
        p.dUq[l] = double(r.dU << Q);
        p.dVq[l] = double(r.dV << Q);
        p.active |= 1u << l;
    }
}

/// `hit` := the voxel `voxel` at `cell`, a leaf of side 2^leafShift voxels, field by field: a
/// copy of a whole hit reads it back in wider pieces than its fields were written in, and waits
/// for them (store forwarding); a filter reads it back field by field.
inline void setVoxelHit(TraversalHit& hit, std::uint32_t voxel, const ivec3& cell, int leafShift) {
    hit.voxel = voxel;
    hit.cell = cell;
    hit.leafShift = leafShift;
    hit.node = kNoHit;
    hit.level = 0;
    hit.smooth = false;
    hit.distance = 0.0;
    hit.normal = vec3(0.0f);
    hit.zCells = 0.0f;
}

/// The lanes of `m` that take the voxel (index `voxel`, at `cell`, a leaf of side 2^leafShift
/// voxels) as their hit: each lane's hit is set to it, then given to the lane's filter (none:
/// taken), or with `smooth` the lanes' states to smooth's test of them all at once; a lane whose
/// filter passes the voxel goes on behind it, and its hit is written again at its next voxel
/// (only the hits of lanes done are read). Out of line, once per voxel rather than per lane: the
/// kernels are compiled for their instruction set, and what they call of std::function stays
/// compiled for the baseline; around a call, a kernel saves and restores its vector registers.
[[gnu::noinline]] unsigned acceptingLanes(const PacketLane* lanes, unsigned m, std::uint32_t voxel, const ivec3& cell,
                                          int leafShift, const SmoothSurface* smooth) {
    unsigned accepted = 0;
    SmoothSurface::RayState* states[kMaxPacketLanes];
    TraversalHit* hits[kMaxPacketLanes];
    unsigned n = 0;
    for (unsigned rest = m; rest; rest &= rest - 1) {
        const unsigned l = unsigned(__builtin_ctz(rest));
        TraversalHit& hit = *lanes[l].hit;
        setVoxelHit(hit, voxel, cell, leafShift);
        if (smooth) {
            states[n] = lanes[l].state;
            hits[n++] = &hit;
        } else if (!lanes[l].filter || (*lanes[l].filter)(hit)) {
            accepted |= 1u << l;
        }
    }
    if (smooth) {
        // Bit i of the tested is the i-th lane of m.
        unsigned tested = smooth->testLanes(states, hits, n);
        for (unsigned rest = m; rest; rest &= rest - 1, tested >>= 1)
            if (tested & 1u) accepted |= 1u << __builtin_ctz(rest);
    }
    return accepted;
}

#define OCTRACE_PACKET_TARGET
namespace sse2 {
#if defined(OCTRACE_PACKET_X86)
/// One SSE2 register of doubles.
struct Reg {
    using type = __m128d;
    static constexpr unsigned kWidth = 2;
    static type set(double x) { return _mm_set1_pd(x); }
    static type load(const double* p) { return _mm_load_pd(p); }
    static type add(type x, type y) { return _mm_add_pd(x, y); }
    static type sub(type x, type y) { return _mm_sub_pd(x, y); }
    static type mul(type x, type y) { return _mm_mul_pd(x, y); }
    static unsigned lt(type x, type y) { return unsigned(_mm_movemask_pd(_mm_cmplt_pd(x, y))); }
    static unsigned gt(type x, type y) { return unsigned(_mm_movemask_pd(_mm_cmpgt_pd(x, y))); }
};
#else
/// Two doubles in plain C++ (a processor other than x86): the same arithmetic, lane by lane.
struct Reg {
    struct type {
        double v[2];
    };
    static constexpr unsigned kWidth = 2;
    static type set(double x) { return {{x, x}}; }
    static type load(const double* p) { return {{p[0], p[1]}}; }
    static type add(type x, type y) { return {{x.v[0] + y.v[0], x.v[1] + y.v[1]}}; }
    static type sub(type x, type y) { return {{x.v[0] - y.v[0], x.v[1] - y.v[1]}}; }
    static type mul(type x, type y) { return {{x.v[0] * y.v[0], x.v[1] * y.v[1]}}; }
    static unsigned lt(type x, type y) { return unsigned(x.v[0] < y.v[0]) | unsigned(x.v[1] < y.v[1]) << 1; }
    static unsigned gt(type x, type y) { return unsigned(x.v[0] > y.v[0]) | unsigned(x.v[1] > y.v[1]) << 1; }
};
#endif
#include "render/traversal/PacketKernel.inc"
}  // namespace sse2
#undef OCTRACE_PACKET_TARGET

#if defined(OCTRACE_PACKET_X86)
// Every function of these namespaces carries the target attribute (GCC's target pragma would leave
// friend functions defined in a class without it, and clang does not know the pragma).
#define OCTRACE_PACKET_TARGET [[gnu::target("avx2")]]
namespace avx2 {
/// One AVX register of doubles.
struct Reg {
    using type = __m256d;
    static constexpr unsigned kWidth = 4;
    OCTRACE_PACKET_TARGET static type set(double x) { return _mm256_set1_pd(x); }
    OCTRACE_PACKET_TARGET static type load(const double* p) { return _mm256_load_pd(p); }
    OCTRACE_PACKET_TARGET static type add(type x, type y) { return _mm256_add_pd(x, y); }
    OCTRACE_PACKET_TARGET static type sub(type x, type y) { return _mm256_sub_pd(x, y); }
    OCTRACE_PACKET_TARGET static type mul(type x, type y) { return _mm256_mul_pd(x, y); }
    OCTRACE_PACKET_TARGET static unsigned lt(type x, type y) { return unsigned(_mm256_movemask_pd(_mm256_cmp_pd(x, y, _CMP_LT_OQ))); }
    OCTRACE_PACKET_TARGET static unsigned gt(type x, type y) { return unsigned(_mm256_movemask_pd(_mm256_cmp_pd(x, y, _CMP_GT_OQ))); }
};
#include "render/traversal/PacketKernel.inc"
}  // namespace avx2
#undef OCTRACE_PACKET_TARGET

#define OCTRACE_PACKET_TARGET [[gnu::target("avx512f")]]
namespace avx512 {
/// One AVX-512 register of doubles.
struct Reg {
    using type = __m512d;
    static constexpr unsigned kWidth = 8;
    OCTRACE_PACKET_TARGET static type set(double x) { return _mm512_set1_pd(x); }
    OCTRACE_PACKET_TARGET static type load(const double* p) { return _mm512_load_pd(p); }
    OCTRACE_PACKET_TARGET static type add(type x, type y) { return _mm512_add_pd(x, y); }
    OCTRACE_PACKET_TARGET static type sub(type x, type y) { return _mm512_sub_pd(x, y); }
    OCTRACE_PACKET_TARGET static type mul(type x, type y) { return _mm512_mul_pd(x, y); }
    OCTRACE_PACKET_TARGET static unsigned lt(type x, type y) { return unsigned(_mm512_cmp_pd_mask(x, y, _CMP_LT_OQ)); }
    OCTRACE_PACKET_TARGET static unsigned gt(type x, type y) { return unsigned(_mm512_cmp_pd_mask(x, y, _CMP_GT_OQ)); }
};
#include "render/traversal/PacketKernel.inc"
}  // namespace avx512
#undef OCTRACE_PACKET_TARGET
#endif  // OCTRACE_PACKET_X86

}  // namespace

#if defined(OCTRACE_PACKET_X86)
static_assert(sse2::Lanes::kCount <= kMaxPacketLanes && avx2::Lanes::kCount <= kMaxPacketLanes &&
              avx512::Lanes::kCount <= kMaxPacketLanes);

unsigned packetLanes(PacketIsa isa) {
    switch (isa) {
        case PacketIsa::Avx512: return avx512::Lanes::kCount;
        case PacketIsa::Avx2: return avx2::Lanes::kCount;
        case PacketIsa::Sse2: break;
    }
    return sse2::Lanes::kCount;
}

PacketIsa packetIsa() {
    static const PacketIsa isa = __builtin_cpu_supports("avx512f") ? PacketIsa::Avx512
                                 : __builtin_cpu_supports("avx2")  ? PacketIsa::Avx2
                                                                   : PacketIsa::Sse2;
    return isa;
}
#else
static_assert(sse2::Lanes::kCount <= kMaxPacketLanes);
unsigned packetLanes(PacketIsa) { return sse2::Lanes::kCount; }
PacketIsa packetIsa() { return PacketIsa::Sse2; }
#endif

unsigned traversePacket(PacketIsa isa, const Octree& tree, const StartNode& start, const PacketLane* lanes,
                        unsigned count, TraversalCounters& counters, const LodCut* cut, unsigned* scalarLanes,
                        const SmoothSurface* smooth) {
    if (cut && !cut->active()) cut = nullptr;
    for (unsigned l = 0; l < count; ++l)
        assert(lanes[l].ray->meetsCube && (!lanes[l].filter || *lanes[l].filter) && (!smooth || lanes[l].state));
    PacketSetup p;
    unsigned scalar = 0;
#if defined(OCTRACE_PACKET_X86)
    static const bool dq = __builtin_cpu_supports("avx512dq");
    const bool avx512 = isa == PacketIsa::Avx512 && dq;
#else
    const bool avx512 = false;
#endif
    setupPacket(start, lanes, count, packetLanes(isa), avx512, p, scalar);
    p.smooth = smooth;
    unsigned done = 0;
    if (scalarLanes) *scalarLanes = scalar;
    if (p.active) {
#if defined(OCTRACE_PACKET_X86)
        switch (isa) {
            case PacketIsa::Avx512: done = cut ? avx512::runPacket<true>(tree, p, lanes, counters, cut) : avx512::runPacket<false>(tree, p, lanes, counters, nullptr); break;
            case PacketIsa::Avx2: done = cut ? avx2::runPacket<true>(tree, p, lanes, counters, cut) : avx2::runPacket<false>(tree, p, lanes, counters, nullptr); break;
            case PacketIsa::Sse2: done = cut ? sse2::runPacket<true>(tree, p, lanes, counters, cut) : sse2::runPacket<false>(tree, p, lanes, counters, nullptr); break;
        }
#else
        (void)isa;
        done = cut ? sse2::runPacket<true>(tree, p, lanes, counters, cut) : sse2::runPacket<false>(tree, p, lanes, counters, nullptr);
#endif
    }
    for (; scalar; scalar &= scalar - 1) {
        const unsigned l = unsigned(__builtin_ctz(scalar));
        const TraversalHit hit = traverseFromNodes(tree, *lanes[l].ray, &start, 1, counters, lanes[l].filter, cut);
        if (hit.hit()) {
            *lanes[l].hit = hit;
            done |= 1u << l;
        }
    }
    return done;
}

}  // namespace octrace::detail
