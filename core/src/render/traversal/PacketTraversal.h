#pragma once
// Private to core: the discrete traversal of several rays at once (docs/dev/tile-renderer.md,
// "Packets"). Each lane is exact: it finds the same hit as traverseFromNodes on the same node.
#include "octrace/render/DiscreteTraversal.h"

namespace octrace::detail {

/// Rays per packet.
constexpr unsigned kPacketLanes = 8;

/// The instruction set the packet traversal runs on: AVX2 (one 4-wide register of doubles per
/// lane quantity) or SSE2 (two 2-wide ones), the same arithmetic and so the same results.
enum class PacketIsa { Sse2, Avx2 };

/// The best the machine running this offers (AVX2 when the processor has it).
PacketIsa packetIsa();

/// One lane: its quantized ray, its filter (smooth surfaces, as traverseFromNodes's; may be
/// null) and where its hit goes.
struct PacketLane {
    const QuantizedRay* ray = nullptr;
    const VoxelFilter* filter = nullptr;
    TraversalHit* hit = nullptr;
};

/// traverseFromNodes(tree, *lane.ray, &start, 1, counters, lane.filter) for each of `count`
/// lanes (1 .. kPacketLanes) at once: the rays must share their main axis and sign pattern, meet
/// the cube, and no cut applies. Returns the lanes (bit i: lane i) that found their hit, which is
/// written to *lane.hit; the others wrote nothing. Lanes the packet's exact arithmetic cannot
/// take (the eye's main plane cuts the node, or the node is so coarse that a value could
/// exceed 2^52) are traced by the scalar traversal on the node instead.
unsigned traversePacket(PacketIsa isa, const Octree& tree, const StartNode& start, const PacketLane* lanes,
                        unsigned count, TraversalCounters& counters);

}  // namespace octrace::detail
