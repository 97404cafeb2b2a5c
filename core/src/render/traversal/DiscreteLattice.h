#pragma once
// Private to core: the discrete traversal's lattice arithmetic (DiscreteTraversal.h,
// docs/dev/discrete-traversal.md) that more than one traversal engine needs: the scalar engine
// (DiscreteTraversal.cpp) and the packet engine (PacketTraversal.cpp).
#include "octrace/octree/Octree.h"
#include "octrace/render/DiscreteTraversal.h"

#include <cstdint>

namespace octrace::lattice {

constexpr int N = Octree::kIntBits;
constexpr int Q = QuantizedRay::kFracBits;
using i64 = std::int64_t;
constexpr i64 L = i64(1) << N;

/// The child-index bit of axis a (x: 4, y: 2, z: 1).
constexpr unsigned axisBit(int a) { return 4u >> a; }

/// Exact test of a node box [m0, m0+s) x [u0, u0+s) x [v0, v0+s) (mirrored lattice): the
/// same pairwise interval tests as the state byte, for the box itself, given the line's
/// lower/upper points on the box's main planes (2^(N+Q) times u and v there: Wu0 .. Wv1) and the
/// cross product F at the box's (u0, v0 + s) and (u0 + s, v0) corners. cU (cV) is 1 when the line
/// is parallel to the u (v) planes, else 0.
inline bool boxCrossedFrom(const QuantizedRay& r, i64 cU, i64 cV, i64 m0, i64 u0, i64 v0, i64 s, i64 Wu0, i64 Wu1,
                           i64 Wv0, i64 Wv1, i64 Fuv1, i64 Fu1v) {
    return Wu0 < ((u0 + s) << (N + Q)) && Wu1 > (u0 << (N + Q)) - cU && Wv0 < ((v0 + s) << (N + Q)) &&
           Wv1 > (v0 << (N + Q)) - cV && Fuv1 < cU && Fu1v > -cV && r.eyeM < ((m0 + s) << Q) &&
           r.uEyeFloor < u0 + s && r.vEyeFloor < v0 + s;
}

/// Mirrored lattice origin (main, u, v) of a node given by its cell coordinates at `level`.
inline void mirroredOrigin(const QuantizedRay& r, const ivec3& cell, int level, i64& m0, i64& u0, i64& v0) {
    const i64 s = i64(1) << (N - level);
    i64 o[3];
    for (int a = 0; a < 3; ++a) {
        const i64 lo = i64(cell[a]) << (N - level);
        o[a] = (r.sign & axisBit(a)) ? L - (lo + s) : lo;
    }
    m0 = o[r.main];
    u0 = o[r.u];
    v0 = o[r.v];
}

/// The cell coordinates at `level` of the lowest corner of a box of side `side` whose mirrored
/// origin, indexed by original axis, is `mirrored`.
inline ivec3 unmirroredCell(const QuantizedRay& r, const i64 mirrored[3], i64 side, int level) {
    ivec3 cell;
    for (int a = 0; a < 3; ++a) {
        const i64 o = (r.sign & axisBit(a)) ? L - (mirrored[a] + side) : mirrored[a];
        cell[a] = int(o >> (N - level));
    }
    return cell;
}

}  // namespace octrace::lattice
