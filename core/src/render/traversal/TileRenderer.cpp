// The tile renderer: an exact conservative pre-pass per screen tile, then each ray traced from
// the tile's frontier nodes instead of the root. Exactness argument: docs/dev/tile-renderer.md
// (the numbered steps there are cited below).
#include "render/traversal/TileRenderer.h"
#include "render/traversal/TileFrontier.h"
#include "render/traversal/PacketTraversal.h"
#include "render/PerPixel.h"
#include "render/traversal/PixelRays.h"

#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/Lod.h"
#include "octrace/render/Shading.h"
#include "octrace/render/SmoothSurface.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace octrace::detail {
namespace {
/// The pixels of a tile whose rays go through the packet traversal (step 6), as bits k = row *
/// side + column of word arrays: what their hits need. Sized once for a tile's pixels and never
/// reallocated (a pixel's filter holds its sray).
struct PacketPixels {
    int side = 0;
    std::size_t words = 0;
    std::vector<dvec3> dir;
    std::vector<QuantizedRay> q;
    std::vector<TraversalHit> hit;             ///< valid where `done` has bit k
    std::vector<SmoothSurface::RayState> sray;  ///< smooth surfaces: each filter's state, carried from node to node
    std::vector<VoxelFilter> filter;            ///< smooth surfaces: the test of pixel k's sray[k] (set once: sray does not move)
    std::vector<PacketLane> lane;           ///< pixel k's lane (its pointers into the arrays above never change)
    std::vector<std::uint64_t> axis[3];     ///< bit k of axis[a]: pixel k's ray, of main axis a, goes through the packets
    std::vector<std::uint64_t> done;        ///< bit k: pixel k's hit is found
    std::vector<std::uint64_t> nodePixels;  ///< `words` words per frontier node i: the pixels of its rectangle
    /// `smooth` active: each lane carries its filter (smooth's test of its sray).
    PacketPixels(int tileSide, const SmoothSurface& smooth)
        : side(tileSide), words((std::size_t(tileSide) * std::size_t(tileSide) + 63) / 64), dir(64 * words),
          q(64 * words), hit(64 * words), sray(64 * words), filter(64 * words), lane(64 * words),
          axis{std::vector<std::uint64_t>(words), std::vector<std::uint64_t>(words), std::vector<std::uint64_t>(words)},
          done(words), nodePixels(64 * words) {
        const bool filtered = smooth.active();
        for (std::size_t k = 0; k < lane.size(); ++k) {
            if (filtered) filter[k] = smooth.filter(sray[k]);
            lane[k] = PacketLane{&q[k], filtered ? &filter[k] : nullptr, &hit[k], &sray[k]};
        }
    }
    // lane[k] and the filters point into this object's own arrays: a copy would point into this one.
    PacketPixels(const PacketPixels&) = delete;
    PacketPixels& operator=(const PacketPixels&) = delete;
    void clear() {
        for (std::vector<std::uint64_t>* v : {&axis[0], &axis[1], &axis[2], &done}) std::fill(v->begin(), v->end(), 0);
    }
    /// Pixel k's ray, of main axis a, goes through the packets.
    void trace(std::size_t k, int a) { axis[a][k / 64] |= std::uint64_t(1) << (k % 64); }
    /// Word w of the pixels whose rays go through the packets.
    std::uint64_t traced(std::size_t w) const { return axis[0][w] | axis[1][w] | axis[2][w]; }
    /// Node i's pixels: columns cx0 .. cx1 of rows cy0 .. cy1 (tile coordinates, inclusive).
    void setRect(std::size_t i, int cx0, int cx1, int cy0, int cy1) {
        std::uint64_t* w = nodePixels.data() + i * words;
        if (words == 1) {
            // Tiles of up to 8 x 8: the word built in a register (a word cleared by a fill and
            // then read back waits for the fill's stores).
            if (cx1 < cx0 || cy1 < cy0) {  // an empty rectangle (the lists keep none: rectMeets)
                *w = 0;
                return;
            }
            const std::uint64_t row = ((std::uint64_t(2) << (cx1 - cx0)) - 1) << cx0;  // columns cx0 .. cx1 (at most 8 of them)
            std::uint64_t m = 0;
            for (int r = cy0; r <= cy1; ++r) m |= row << (r * side);
            *w = m;
            return;
        }
        std::fill(w, w + words, 0);
        for (int row = cy0; row <= cy1; ++row)
            for (std::size_t a = std::size_t(row * side + cx0), b = std::size_t(row * side + cx1); a <= b;) {
                // bits a .. b, at most up to the end of a's word
                const std::size_t end = std::min(b, a | 63);
                const unsigned lo = unsigned(a % 64), n = unsigned(end - a + 1);
                w[a / 64] |= (n == 64 ? ~std::uint64_t(0) : ((std::uint64_t(1) << n) - 1)) << lo;
                a = end + 1;
            }
    }
};
}  // namespace

/// Pixels x0 .. x1-1 of row y as background, as writePixelHit writes a miss, counting the rays
/// that meet the cube (certain inside the cube's inner outline, quantized between it and the
/// outline, none outside).
void fillBackground(Frame& frame, const PixelRays& rays, const RenderSettings& settings, int y, int x0, int x1,
                    RenderStats& st) {
    const std::size_t n = std::size_t(x1 - x0);
    writeMissRun(frame, frame.pixel(x0, y), n, settings);
    st.pixels += n;
    st.raysFull += n;
    st.rays += rays.raysMeetingCube(y, x0, x1);
}

RenderStats TileRenderer::render(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                                 Frame& frame) const {
    // A multi-resolution cut (--lod, --level) draws nodes whole: the frontier stays above the
    // coarsest level the cut can stop at, and the traversals from it honour the cut.
    const LodCut cut(tree, camera, settings.detail.lodPixels, settings.detail.level);
    const LodCut* cutp = cut.active() ? &cut : nullptr;
    camera.validate();
    Timer timer;
    frame.reshape(camera.width, camera.height);  // every pixel is written below
    const Shader shader(tree, camera, settings);
    const SmoothSurface& smooth = shader.smooth();
    const bool smoothOn = smooth.active();
    const PixelRays rays(tree, camera, cut.coarsestLevel());
    const RayGenerator gen(camera);
    const ScreenSlopes slopes(tree, gen, rays, camera.width, camera.height, widen_);
    const int T = std::max(settings.tileSize, 1);
    const int tilesX = (camera.width + T - 1) / T, tilesY = (camera.height + T - 1) / T;
    const std::size_t cap = frontierCap(T);
    // Nodes at this level stay whole: their children are voxels, or nodes a cut may draw whole.
    const int keepLevel = std::min(tree.depth, cut.coarsestLevel()) - 1;
    // Tiles in groups of G x G: the group's frontier (a larger cap) is where each tile's
    // refinement starts, so the coarse levels are walked once per group.
    constexpr int G = kTileGroup;
    const int groupsX = (tilesX + G - 1) / G, groupsY = (tilesY + G - 1) / G;
    // Counters per group of tiles (then summed: integers, so in any order); per tile, making and
    // summing 30,000 of them took a millisecond of every 1600 x 1200 frame.
    std::vector<RenderStats> groupStats(std::size_t(groupsX) * std::size_t(groupsY));
    const std::vector<FrontierNode> root{{StartNode{}}};
    const PacketIsa isa = packetIsa();
    const unsigned width = packetLanes(isa);
    // Step 5 for whole rows first: each row's pixels outside the surface's outline are background,
    // written and counted here in runs as long as the row allows (the tiles skip them). Written
    // tile row by tile row, eight pixels at a time in four buffers, a frame with nothing in view
    // took 4 times as long as `full`'s rows.
    constexpr int kBandRows = 16;
    const std::size_t bands = std::size_t((camera.height + kBandRows - 1) / kBandRows);
    std::vector<RenderStats> bandStats(bands);
    parallelFor(bands, settings.threads, [&](std::size_t b) {
        if (settings.cancel && settings.cancel->load(std::memory_order_relaxed)) return;  // the frame is thrown away
        for (int y = int(b) * kBandRows; y < std::min(int(b + 1) * kBandRows, camera.height); ++y)
            rays.forRunsOutsideSurface(y, camera.width, [&](int x0, int x1) {
                fillBackground(frame, rays, settings, y, x0, x1, bandStats[b]);
            });
    });
    parallelFor(std::size_t(groupsX) * std::size_t(groupsY), settings.threads, [&](std::size_t g) {
        if (settings.cancel && settings.cancel->load(std::memory_order_relaxed)) return;  // the frame is thrown away
        const int gx = int(g % std::size_t(groupsX)), gy = int(g / std::size_t(groupsX));
        const int gx0 = gx * G * T, gy0 = gy * G * T;
        const int gx1 = std::min(gx0 + G * T, camera.width), gy1 = std::min(gy0 + G * T, camera.height);
        // Step 5: a group outside the surface's outline has only background pixels, written with
        // their rows (above).
        if (!rays.mayHitSurfaceIn(gx0, gy0, gx1, gy1)) return;
        RenderStats& st = groupStats[g];
        std::vector<FrontierNode> group, list, next;
        std::vector<StartNode> starts;
        ShadeMemo memo;  // for the group's tiles
        std::vector<std::uint64_t> colMask, rowMask;
        PacketPixels packet(T, smooth);
        // Smooth surfaces: the ray state and test of the pixel traced alone (set once; the
        // state is assigned per pixel).
        SmoothSurface::RayState sray;
        const VoxelFilter filter = smooth.filter(sray);
        const VoxelFilter* fp = smoothOn ? &filter : nullptr;
        // The sign pattern of the group's middle ray orders the frontiers.
        const dvec3 mid = gen.direction((gx0 + gx1) / 2, (gy0 + gy1) / 2);
        const unsigned s = (mid.x < 0.0 ? 4u : 0u) | (mid.y < 0.0 ? 2u : 0u) | (mid.z < 0.0 ? 1u : 0u);
        if (!tree.nodes().empty()) {
            const TileFrustum gf = tileFrustum(gen, slopes, gx0, gy0, gx1, gy1);
            filterFrontier(gf, root, group, gx0, gy0, gx1, gy1);
            refineFrontier(tree, gf, s, G * G * cap, keepLevel, group, next);
            // The group's nodes' rectangles (every frustum has the same apex and pad), so that
            // each tile leaves out the nodes whose rectangle misses it before the frustum test.
            for (FrontierNode& fn : group) pixelRect(tree, gen, gf, fn, camera.width, camera.height);
        }
        for (int ty = gy * G; ty < std::min((gy + 1) * G, tilesY); ++ty)
            for (int tx = gx * G; tx < std::min((gx + 1) * G, tilesX); ++tx) {
            TraversalCounters counters;
            const int x0 = tx * T, y0 = ty * T;
            const int x1 = std::min(x0 + T, camera.width), y1 = std::min(y0 + T, camera.height);
            // Step 5: outside the surface's outline, no ray of the tile visits a boundary voxel
            // (its pixels are written with their rows, above).
            if (!rays.mayHitSurfaceIn(x0, y0, x1, y1)) continue;
            // The tile's rows of the frame, fetched for writing while the pre-pass runs (each
            // row of a tile is a separate short stream that the hardware prefetcher misses).
            const auto prefetchRun = [](const void* first, const void* last) {
                // Every cache line from the one holding `first` to the one holding `last`.
                for (std::uintptr_t a = reinterpret_cast<std::uintptr_t>(first) & ~std::uintptr_t(63),
                                    end = reinterpret_cast<std::uintptr_t>(last);
                     a <= end; a += 64)
                    __builtin_prefetch(reinterpret_cast<const void*>(a), 1);
            };
            for (int y = y0; y < y1; ++y) {
                const std::size_t p0 = frame.pixel(x0, y), p1 = frame.pixel(x1 - 1, y);
                prefetchRun(&frame.rgba[p0], reinterpret_cast<const char*>(&frame.rgba[p1]) + sizeof(vec4) - 1);
                prefetchRun(&frame.depth[p0], &frame.depth[p1]);
                prefetchRun(&frame.hitId[p0], &frame.hitId[p1]);
                prefetchRun(&frame.flags[p0], &frame.flags[p1]);
            }
            tileFrontier(tree, gen, tileFrustum(gen, slopes, x0, y0, x1, y1), group, s, cap, keepLevel, x0, y0, x1, y1,
                         camera.width, camera.height, list, next);
            const std::size_t kept = list.size();
            if (starts.size() < kept) starts.resize(kept);
            if (list.empty()) {
                // Step 5: no ray of the tile visits a boundary voxel (those outside the outline
                // are written with their rows).
                for (int y = y0; y < y1; ++y) {
                    const auto [lo, hi] = rays.surfaceSpanIn(y, x0, x1);
                    if (lo <= hi) fillBackground(frame, rays, settings, y, lo, hi + 1, st);
                }
                st.nodesVisited += counters.nodes;
                continue;
            }
            // Step 4 per pixel: bit i of colMask[x - x0] & rowMask[y - y0] says whether the
            // pixel lies in node i's rectangle (lists of up to 64 nodes; longer ones test each).
            const bool masked = kept <= 64;
            if (masked) {
                colMask.assign(std::size_t(x1 - x0), 0);
                rowMask.assign(std::size_t(y1 - y0), 0);
                for (std::size_t i = 0; i < kept; ++i) {
                    const FrontierNode& fn = list[i];
                    const std::uint64_t bit = std::uint64_t(1) << i;
                    for (int x = std::max(fn.x0, x0); x <= std::min(fn.x1, x1 - 1); ++x) colMask[std::size_t(x - x0)] |= bit;
                    for (int y = std::max(fn.y0, y0); y <= std::min(fn.y1, y1 - 1); ++y) rowMask[std::size_t(y - y0)] |= bit;
                }
            }
            // Step 6: rays of the tile's sign pattern go through the packet traversal, node by
            // node (only with the per-pixel node masks).
            const bool packets = masked;
            packet.clear();
            if (packets)
                for (std::size_t i = 0; i < kept; ++i) {
                    const FrontierNode& fn = list[i];
                    packet.setRect(i, std::max(fn.x0, x0) - x0, std::min(fn.x1, x1 - 1) - x0, std::max(fn.y0, y0) - y0,
                                   std::min(fn.y1, y1 - 1) - y0);
                }
            std::uint64_t raysMeeting = 0, raysFull = 0, raysCommon = 0;  // st's counters, in registers during the loop
            // The pixel's frontier nodes (bits of `list`), none when its ray cannot reach the surface.
            const auto pixelNodes = [&](int x, int y) -> std::uint64_t {
                if (!rays.mayHitSurface(x, y)) return 0;
                return masked ? colMask[std::size_t(x - x0)] & rowMask[std::size_t(y - y0)] : ~std::uint64_t(0);
            };
            for (int y = y0; y < y1; ++y) {
                // The row's rays, quantized together when some pixel of the row needs its ray.
                bool rowTraced = false;
                for (int x = x0; x < x1 && !rowTraced; ++x) rowTraced = pixelNodes(x, y) != 0;
                // Straight into the packets' slots of the row (k = row * T + column).
                dvec3* rowDirs = packet.dir.data() + std::size_t((y - y0) * T);
                QuantizedRay* rowRays = packet.q.data() + std::size_t((y - y0) * T);
                if (rowTraced) {
                    for (int x = x0; x < x1; ++x) rowDirs[x - x0] = gen.direction(x, y);
                    rays.quantizedRow(y, x0, x1 - x0, rowDirs, rowRays);
                }
                for (int x = x0; x < x1; ++x) {
                    if (!rays.mayHitSurface(x, y)) continue;  // step 5: written with its row, above
                    const std::uint64_t mask = masked ? colMask[std::size_t(x - x0)] & rowMask[std::size_t(y - y0)] : ~std::uint64_t(0);
                    if (mask == 0) {
                        // Step 5: nothing the ray can visit holds a boundary voxel (outside every
                        // frontier node's rectangle).
                        if (rays.mayMeetCube(x, y) && rays.meetsCube(x, y)) ++raysMeeting;
                        ++raysFull;
                        writeMissPixel(frame, x, y, settings, st);
                        continue;
                    }
                    const dvec3 dir = rowDirs[x - x0];
                    TraversalHit hit;
                    const QuantizedRay& q = rowRays[x - x0];
                    if (q.meetsCube) ++raysMeeting;
                    if (packets && q.sign == s && q.meetsCube) {
                        ++raysCommon;
                        const std::size_t k = std::size_t((y - y0) * T + (x - x0));
                        packet.trace(k, q.main);
                        if (smoothOn) packet.sray[k] = SmoothSurface::RayState(rays.world(x, y, dir));
                        continue;
                    }
                    // Smooth surfaces: the interpolant's test runs inside the traversal, on
                    // the boundary voxels in the ray's visiting order (the same as full's,
                    // by cover and order), instead of proposing the first and starting over
                    // from the root when it is passed (writePixelHit then keeps the hit).
                    if (smoothOn) sray = SmoothSurface::RayState(rays.world(x, y, dir));
                    if (q.sign != s) {
                        // Another sign pattern: the frontier's order may not be this ray's.
                        ++raysFull;
                        hit = traverseDiscrete(tree, q, counters, cutp, fp);
                    } else {
                        ++raysCommon;
                        std::size_t n = 0;
                        if (masked) {
                            for (std::uint64_t m = mask; m; m &= m - 1) starts[n++] = list[std::size_t(std::countr_zero(m))].start;
                        } else {
                            for (const FrontierNode& fn : list)
                                if (x >= fn.x0 && x <= fn.x1 && y >= fn.y0 && y <= fn.y1) starts[n++] = fn.start;
                        }
                        hit = traverseFromNodes(tree, q, starts.data(), n, counters, fp, cutp);
                    }
                    writePixelHit(frame, x, y, hit, shader, rays, dir, settings, st, counters, cutp, &memo);
                }
            }
            st.rays += raysMeeting;
            st.raysFull += raysFull;
            st.raysCommonPath += raysCommon;
            if (packets) {
                // Step 6: node by node in list order, the pixels still without a hit whose
                // rectangle holds the node, in packets of rays of one main axis (each axis's
                // pixels in their order, as many to a packet as it takes).
                PacketLane lanes[kMaxPacketLanes];
                std::uint32_t owner[kMaxPacketLanes];  // the lanes' pixels
                for (std::size_t i = 0; i < kept; ++i) {
                    unsigned count = 0;
                    const auto flush = [&] {
                        const unsigned found = traversePacket(isa, tree, list[i].start, lanes, count, counters, cutp, nullptr,
                                                             smoothOn ? &smooth : nullptr);
                        for (unsigned rest = found; rest; rest &= rest - 1) {
                            const unsigned k = owner[std::countr_zero(rest)];
                            packet.done[k / 64] |= std::uint64_t(1) << (k % 64);
                            // Shaded once the tile's nodes are done: fetched meanwhile (the
                            // normals and colours of CT skin's and the molecule's voxels are
                            // far from the cache).
                            const TraversalHit& hit = packet.hit[k];
                            if (!hit.nodeHit()) shader.prefetch(hit.voxel, !hit.smooth);
                        }
                        count = 0;
                    };
                    for (int a = 0; a < 3; ++a) {
                        for (std::size_t w = 0; w < packet.words; ++w)
                            for (std::uint64_t m = packet.nodePixels[i * packet.words + w] & packet.axis[a][w] & ~packet.done[w]; m;
                                 m &= m - 1) {
                                const std::size_t k = w * 64 + std::size_t(std::countr_zero(m));
                                lanes[count] = packet.lane[k];
                                owner[count] = std::uint32_t(k);
                                if (++count == width) flush();
                            }
                        if (count) flush();
                    }
                }
                const TraversalHit none;
                for (std::size_t w = 0; w < packet.words; ++w)
                    for (std::uint64_t m = packet.traced(w); m; m &= m - 1) {
                        const std::size_t k = w * 64 + std::size_t(std::countr_zero(m));
                        const bool found = packet.done[w] >> (k % 64) & 1u;
                        writePixelHit(frame, x0 + int(k % std::size_t(T)), y0 + int(k / std::size_t(T)), found ? packet.hit[k] : none,
                                      shader, rays, packet.dir[k], settings, st, counters, cutp, &memo);
                    }
            }
            st.nodesVisited += counters.nodes;
        }
    });
    groupStats.insert(groupStats.end(), bandStats.begin(), bandStats.end());
    return RenderStats::total(name(), groupStats, timer.ms());
}

}  // namespace octrace::detail
