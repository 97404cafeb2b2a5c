#pragma once
// Private to core: the discrete traversal of several rays at once (docs/dev/tile-renderer.md,
// "Packets"). Each lane is exact: it finds the same hit as traverseFromNodes on the same node.
#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/SmoothSurface.h"

namespace octrace {
class LodCut;
}

namespace octrace::detail {

/// The instruction set the packet traversal runs on: AVX-512 (16 rays per packet, in two
/// 8-wide registers of doubles per lane quantity), AVX2 (8 rays, two 4-wide registers) or SSE2
/// (4 rays, two 2-wide registers; on a processor other than x86, the same in plain C++): the same
/// exact arithmetic, so the same results.
enum class PacketIsa { Sse2, Avx2, Avx512 };

/// The most rays a packet holds on any instruction set.
constexpr unsigned kMaxPacketLanes = 16;

/// The rays per packet on `isa` (more registers per quantity spill: 16 rays on AVX2 drew CT skin
/// 1.7 times slower than 8).
unsigned packetLanes(PacketIsa isa);

/// The best the processor running this offers (AVX-512 foundation, else AVX2, else SSE2; Sse2,
/// the plain C++ lanes, on other processors).
PacketIsa packetIsa();

/// One lane: its quantized ray, its filter (smooth surfaces, as traverseFromNodes's; may be
/// null), where its hit goes, and with smooth surfaces (traversePacket's `smooth`) the ray
/// state that the filter tests.
struct PacketLane {
    const QuantizedRay* ray = nullptr;
    const VoxelFilter* filter = nullptr;
    TraversalHit* hit = nullptr;
    SmoothSurface::RayState* state = nullptr;
};

/// traverseFromNodes(tree, *lane.ray, &start, 1, counters, lane.filter, cut) for each of `count`
/// lanes (1 .. packetLanes(isa)) at once: the rays must share their main axis and sign pattern and
/// meet the cube, a lane's filter must be null or non-empty, and with a cut the start node must
/// lie above LodCut::coarsestLevel() (as for traverseFromNodes). Returns the lanes
/// (bit i: lane i) that found their hit, which is written to *lane.hit; the others' *lane.hit is
/// left unspecified (a lane's filter is handed each voxel it passes there).
/// Lanes the packet's exact arithmetic cannot take (the eye's main plane cuts the node, or the
/// node is so coarse that a value could exceed 2^52) are traced by the scalar traversal on the node
/// instead; `scalarLanes`, when given, receives them (bit i: lane i).
/// `smooth`, when given: every lane's filter must be smooth's test() of the lane's `state` (the
/// packet then tests the lanes that meet a voxel together, SmoothSurface::testLanes, the same
/// results, and leaves the filters to the lanes traced by the scalar traversal).
unsigned traversePacket(PacketIsa isa, const Octree& tree, const StartNode& start, const PacketLane* lanes,
                        unsigned count, TraversalCounters& counters, const LodCut* cut = nullptr,
                        unsigned* scalarLanes = nullptr, const SmoothSurface* smooth = nullptr);

}  // namespace octrace::detail
