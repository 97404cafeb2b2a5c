// The discrete renderers: full traversal, paper A's trajectory coherence (linear, area) in
// approximate and exact variants, and colour coherence as an option on any of them.
//
// Pixels are computed in phases; within a phase every pixel depends only on pixels of earlier
// phases, so each phase runs in parallel over rows and the image does not depend on the
// number of threads. Supporting pixels are every 4th column (and the last), base rows every
// 4th row (and the last).
//   linear: 1. x % 4 == 0 full   2. x % 4 == 2 from (x-2, x+2)   3. odd x from (x-1, x+1)
//   area:   base rows as linear; 4. rows y % 4 == 2 from (y-2, y+2); 5. odd rows from (y-1, y+1)
//   full:   1. every pixel (with colour coherence: even x, then odd x filled or traced)
// Colour coherence fills a pixel of the last phase of its row or column pattern when its two
// partners were both traced and their 8-bit colours agree within the tolerance. Miss coherence
// (approximate linear and area) takes a common-path pixel whose partners both missed as a miss.
#include "render/traversal/CoherentRenderers.h"
#include "render/PerPixel.h"
#include "render/traversal/PixelRays.h"
#include "render/traversal/TileFrontier.h"

#include "octrace/render/DiscreteTraversal.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/render/Lod.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

namespace octrace::detail {
namespace {

enum class Start { Root, Branch, Guided };

/// Tile side of the exact variants' frontier certificate: the tile renderer's default.
constexpr int kCertificateTile = 8;

struct Context {
    const Octree& tree;
    const RenderSettings& settings;
    Frame& frame;
    const Shader& shader;
    const PixelRays& rays;
    ivec3* cells;  // hit cells, read only at pixels that hit (nullptr: no pattern reads them)
    std::uint32_t* srgb;  // packed 8-bit colour of traced and filled pixels (colour coherence; nullptr: off)
    const LodCut& cut;
    std::uint32_t backgroundSrgb;  // packSrgb8(settings.background), for colour coherence
    const ImageFrontier* frontier;  // the exact variants' certificate (nullptr: none)
};

/// Frontier nodes to be proven empty for one ray, traced in batches (one traversal set-up per
/// batch: traverseFromNodes).
class EmptyProof {
public:
    EmptyProof(const Octree& tree, const QuantizedRay& q, TraversalCounters& counters) : tree_(tree), q_(q), counters_(counters) {}
    /// Adds a node; false when a full batch held a hit.
    bool add(const StartNode& n) {
        slots_.n[count_++] = n;
        return count_ < kBatch || flush();
    }
    /// True when no node added since the last flush gives the ray a hit.
    bool flush() {
        const std::size_t n = count_;
        count_ = 0;
        return n == 0 || !traverseFromNodes(tree_, q_, slots_.n, n, counters_).hit();
    }

private:
    static constexpr std::size_t kBatch = 16;
    const Octree& tree_;
    const QuantizedRay& q_;
    TraversalCounters& counters_;
    union Slots {  // left uninitialised: written before read
        Slots() {}
        StartNode n[kBatch];
    } slots_;
    std::size_t count_ = 0;
};

/// Whether the ray of pixel (x, y) finds no hit in any of the frontier nodes that its tile keeps
/// for it: then it visits no boundary voxel (cover, docs/dev/tile-renderer.md step 3: every
/// boundary voxel a ray of the tile visits lies in a frontier node whose rectangle holds its
/// pixel), whatever its sign pattern.
bool provenMiss(const Context& c, int x, int y, const QuantizedRay& q, TraversalCounters& counters) {
    EmptyProof empty(c.tree, q, counters);
    return c.frontier->forEachNode(x, y, [&](const FrontierNode& fn) { return empty.add(fn.start); }) && empty.flush();
}

/// Step 3 of certifiedStart: B lies inside the frontier node at `fromLevel` on its path. Every
/// non-empty child that a ray of q's sign pattern can cross before the path child, at the path
/// nodes from that level down to B's parent, must give the ray no hit: inner nodes are traced
/// (in `empty`'s batches), a leaf (a coarse leaf; conservatively an interior term) must not be
/// crossed.
bool nothingBeforePath(const Context& c, const QuantizedRay& q, const BranchNode& b, int fromLevel, EmptyProof& empty) {
    for (int l = fromLevel; l < b.level; ++l) {
        const OctreeNode& nd = c.tree.nodes()[b.path[l]];
        const unsigned before = nd.childMask & predecessorChildren(q.sign, b.childIndex[l]);
        if (!before) continue;
        const ivec3 cell = b.cell >> (b.level - l);
        for (unsigned ch = 0; ch < 8; ++ch) {
            if (!(before & (1u << ch))) continue;
            const ivec3 cc = cell * 2 + ivec3(int(ch >> 2), int((ch >> 1) & 1), int(ch & 1));
            if (l + 1 >= c.tree.depth || (nd.termMask & (1u << ch))) {
                if (rayCrossesCell(q, cc, l + 1)) return false;
            } else if (!empty.add({nd.firstChild + childRank(nd.childMask, ch), l + 1, cc})) {
                return false;
            }
        }
    }
    return empty.flush();
}

/// The exact variants' start at branch node `b`, certified by the tile frontier
/// (docs/dev/coherence.md, "The frontier certificate"). The pixel's frontier nodes are walked
/// front to back up to the node that holds the hit found in B: every node before it must lie in
/// B or give the ray no hit (traced, in batches), and if it holds B (B inside it), nothing of
/// it in front of B's cells may give the ray a hit (nothingBeforePath). True with `hit` set when certified; false
/// when the caller must trace from the root.
bool certifiedStart(const Context& c, int x, int y, const QuantizedRay& q, const BranchNode& b,
                    TraversalCounters& counters, TraversalHit& hit) {
    const int depth = c.tree.depth;
    EmptyProof empty(c.tree, q, counters);
    bool traced = false, certified = false;
    c.frontier->forEachNode(x, y, [&](const FrontierNode& fn) {
        const StartNode& n = fn.start;
        const bool inB = n.level >= b.level && (n.cell >> (n.level - b.level)) == b.cell;
        const bool holdsB = n.level < b.level && (b.cell >> (b.level - n.level)) == n.cell;
        if (!inB && !holdsB) return empty.add(n);  // outside B: it must give the ray no hit
        if (!traced) {
            // What lies in front of B's first node must be empty before B is worth tracing.
            if (!empty.flush()) return false;
            hit = traverseFromNode(c.tree, q, b.path[b.level], b.level, b.cell, counters);
            if (!hit.hit()) return false;
            traced = true;
        }
        // B inside this node: nothing in front of B's cells but what the path passes in it.
        if (holdsB) {
            certified = empty.flush() && nothingBeforePath(c, q, b, n.level, empty);
            return false;
        }
        if ((hit.cell >> (depth - n.level)) == n.cell) {
            certified = empty.flush();
            return false;
        }
        return true;  // another node inside B
    });
    return certified;  // the end of the list without reaching h's node: not for a hit in B (cover)
}

/// The directions and quantized rays of pixels x0 .. x0 + n - 1 of one row, made together
/// (PixelRays::quantizedRow: eight at a time where the processor can, the same bits).
struct RowRays {
    int y = -1, x0 = 0, n = 0;
    std::vector<dvec3> dir;
    std::vector<QuantizedRay> q;
    /// Pixels lo .. hi of row y (none when lo > hi).
    void make(const PixelRays& rays, int row, int lo, int hi) {
        y = row;
        x0 = lo;
        n = std::max(hi - lo + 1, 0);
        if (dir.size() < std::size_t(n)) {
            dir.resize(std::size_t(n));
            q.resize(std::size_t(n));
        }
        for (int i = 0; i < n; ++i) dir[std::size_t(i)] = rays.direction(lo + i, row);
        if (n) rays.quantizedRow(row, lo, n, dir.data(), q.data());
    }
    bool holds(int x, int row) const { return row == y && x >= x0 && x < x0 + n; }
};

/// Traces pixel (x, y) and writes it; `partners` are the two neighbours whose hits give the
/// branch node (nullptr: from the root). `row`: the row's rays made beforehand, or none.
void tracePixel(const Context& c, int x, int y, const std::size_t* partners, Start mode, RenderStats& st,
                TraversalCounters& counters, const RowRays* row = nullptr) {
    Frame& f = c.frame;
    const std::size_t p = f.pixel(x, y);
    auto background = [&](std::uint8_t flags) {
        f.flags[p] = flags;
        f.rgba[p] = c.settings.background;
        f.depth[p] = std::numeric_limits<float>::infinity();
        f.hitId[p] = kNoHit;
        if (c.srgb) c.srgb[p] = c.backgroundSrgb;
    };
    // Outside the cube's outline: no ray to quantize.
    if (!c.rays.mayMeetCube(x, y)) {
        ++st.raysFull;
        return background(Frame::kTraced);
    }
    // Meets the cube perhaps, but not the surface's bounding box (rounded out to the nodes a
    // multi-resolution cut may draw whole): nothing to find. The ray is quantized only to be
    // counted in `rays`, and not even that well inside the cube's outline. Miss coherence: the
    // same for a pixel whose partners both missed, taken as a miss (not certain: not traced).
    const bool cannotHit = !c.rays.mayHitSurface(x, y);
    const bool missFill = !cannotHit && partners && mode == Start::Branch && c.settings.coherence.miss &&
                          f.hitId[partners[0]] == kNoHit && f.hitId[partners[1]] == kNoHit;
    if (cannotHit || missFill) {
        if (c.rays.meetsCube(x, y)) ++st.rays;
        ++(missFill ? st.missFilled : st.raysFull);
        return background(missFill ? Frame::kMissFilled : Frame::kTraced);
    }
    const bool made = row && row->holds(x, y);
    QuantizedRay own;
    const dvec3 dir = made ? row->dir[std::size_t(x - row->x0)] : c.rays.direction(x, y);
    if (!made) own = c.rays.quantized(x, y, dir);
    const QuantizedRay& q = made ? row->q[std::size_t(x - row->x0)] : own;
    if (q.meetsCube) ++st.rays;
    // The exact variants' miss coherence, always on: a pixel whose partners both missed is taken
    // as a miss only when that is proven (so it is no setting).
    if (partners && c.frontier && f.hitId[partners[0]] == kNoHit &&
        f.hitId[partners[1]] == kNoHit && provenMiss(c, x, y, q, counters)) {
        ++st.missFilled;
        return background(Frame::kMissFilled);
    }
    TraversalHit hit;
    std::uint8_t flags = Frame::kTraced;
    const bool usePartners = partners && mode != Start::Root && f.hitId[partners[0]] != kNoHit &&
                             f.hitId[partners[1]] != kNoHit && q.meetsCube;
    if (usePartners) {
        const BranchNode bn = branchNode(c.tree, c.cells[partners[0]], c.cells[partners[1]], c.settings.coherence.branchUp);
        ++st.raysCommonPath;
        flags |= Frame::kCommonPath;
        if (mode == Start::Branch) {
            bool fellBack = false;
            hit = traverseFromBranch(c.tree, q, bn, counters, fellBack);
            if (fellBack) {
                ++st.fallbacks;
                flags |= Frame::kFallback;
            }
        } else if (c.frontier && q.sign == c.frontier->sign(x, y)) {
            if (certifiedStart(c, x, y, q, bn, counters, hit)) {
                ++st.raysCertified;
                flags |= Frame::kCertified;
            } else {
                ++st.fallbacks;
                flags |= Frame::kFallback;
                hit = traverseDiscrete(c.tree, q, counters);
            }
        } else {
            // Another sign pattern than the one ordering the tile's frontier: only the
            // structural certificate applies.
            bool certified = false;
            hit = traverseGuided(c.tree, q, bn, counters, certified);
            if (certified) {
                ++st.raysCertified;
                flags |= Frame::kCertified;
            }
        }
    } else {
        ++st.raysFull;
        hit = traverseDiscrete(c.tree, q, counters, &c.cut);
    }
    // In place, and only when the smooth test applies (as writePixelHit: a copy of the hit just
    // written field by field stalls on store forwarding).
    if (surfaceTestApplies(c.shader.smooth(), hit)) hit = surfaceHit(c.shader.smooth(), hit, c.rays, x, y, dir, counters, &c.cut);
    f.flags[p] = flags;
    if (!hit.hit()) {
        f.rgba[p] = c.settings.background;
        f.depth[p] = std::numeric_limits<float>::infinity();
        f.hitId[p] = kNoHit;
    } else {
        ++st.hits;
        f.hitId[p] = hit.voxel;
        if (c.cells) c.cells[p] = hit.cell;
        f.rgba[p] = c.shader.shade(hit, &st.secondaryRays);
        f.depth[p] = c.shader.distance(c.rays.world(x, y, dir), hit);
    }
    if (c.srgb) c.srgb[p] = hit.hit() ? packSrgb8(f.rgba[p]) : c.backgroundSrgb;
}

/// Writes the background to the pixels of row y whose rays cannot hit the surface, counted as
/// tracePixel counts them, in one pass; returns the pixels left to the patterns (lo > hi: none).
/// Each field is filled as a run (writeMissRun, as the tile renderer's background rows), and the
/// rays are counted per run (PixelRays::raysMeetingCube).
std::pair<int, int> fillOutsideSurface(const Context& c, int y, RenderStats& st) {
    Frame& f = c.frame;
    return c.rays.forRunsOutsideSurface(y, f.width, [&](int x0, int x1) {
        const std::size_t p = f.pixel(x0, y), n = std::size_t(x1 - x0);
        writeMissRun(f, p, n, c.settings);
        if (c.srgb) std::fill_n(c.srgb + p, n, c.backgroundSrgb);
        st.raysFull += n;
        st.rays += c.rays.raysMeetingCube(y, x0, x1);
    });
}

/// Colour coherence: fills pixel p from its partners when both are known (traced, or filled by
/// colour or miss coherence) and their colours agree. Both showing the surface: the average
/// colour and depth, the first partner's hit id. Both background (paper A fills any pair of
/// close colours): the background, no hit. Either way only the ray's quantization is computed,
/// to count it in `rays` when it meets the cube.
bool tryFill(const Context& c, int x, int y, const std::size_t* partners, RenderStats& st) {
    Frame& f = c.frame;
    const std::size_t a = partners[0], b = partners[1];
    constexpr std::uint8_t known = Frame::kTraced | Frame::kColourFilled | Frame::kMissFilled;
    if (!(f.flags[a] & known) || !(f.flags[b] & known)) return false;
    const bool hitA = f.hitId[a] != kNoHit, hitB = f.hitId[b] != kNoHit;
    if (hitA != hitB) return false;
    if (!hitA && !c.settings.coherence.colourFillsBackground) return false;
    for (int ch = 0; ch < 4; ++ch) {
        const int da = int((c.srgb[a] >> (8 * ch)) & 0xFF), db = int((c.srgb[b] >> (8 * ch)) & 0xFF);
        if (float(std::abs(da - db)) > c.settings.coherence.colourTolerance) return false;
    }
    const std::size_t p = f.pixel(x, y);
    f.flags[p] = Frame::kColourFilled;
    ++st.colourFilled;
    if (!hitA) {
        f.rgba[p] = c.settings.background;
        f.depth[p] = std::numeric_limits<float>::infinity();
        f.hitId[p] = kNoHit;
        c.srgb[p] = c.backgroundSrgb;
        if (c.rays.meetsCube(x, y)) ++st.rays;
        return true;
    }
    // The ray lies between two rays that hit voxels inside the convex scene cube: it meets it.
    f.rgba[p] = 0.5f * (f.rgba[a] + f.rgba[b]);
    f.depth[p] = 0.5f * (f.depth[a] + f.depth[b]);
    f.hitId[p] = f.hitId[a];
    if (c.cells) c.cells[p] = c.cells[a];
    c.srgb[p] = packSrgb8(f.rgba[p]);
    ++st.rays;
    ++st.hits;
    return true;
}

}  // namespace

std::string DiscreteRenderer::name() const {
    std::string n = pattern_ == Pattern::Full ? "full" : pattern_ == Pattern::Linear ? "linear" : "area";
    if (exact_) n += "-exact";
    return n;
}

RenderStats DiscreteRenderer::render(const Octree& tree, const Camera& camera, const RenderSettings& settings,
                                     Frame& frame) const {
    camera.validate();
    Timer timer;
    frame.reshape(camera.width, camera.height);  // every pixel is written below
    const Shader shader(tree, camera, settings);
    const LodCut cut(tree, camera, settings.detail.lodPixels, settings.detail.level);
    const PixelRays rays(tree, camera, cut.coarsestLevel());
    // Written at every hit before any pattern reads it there: left uninitialised.
    std::unique_ptr<ivec3[]> cells(pattern_ == Pattern::Full ? nullptr : new ivec3[frame.hitId.size()]);
    // Written at every traced or filled pixel before a partner reads it: left uninitialised.
    std::unique_ptr<std::uint32_t[]> srgb(settings.coherence.colour ? new std::uint32_t[frame.hitId.size()] : nullptr);
    if (cut.active() && pattern_ != Pattern::Full)
        throw UsageError("renderer " + name() + " has no multi-resolution mode (`lod`, `level`): use " + voxelRenderersThat(&Renderer::multiResolution));
    // The exact variants' certificate: every tile's frontier, built once per frame.
    std::unique_ptr<const ImageFrontier> frontier(
        exact_ && pattern_ != Pattern::Full ? new ImageFrontier(tree, camera, rays, kCertificateTile) : nullptr);
    const Context ctx{tree,   settings, frame, shader, rays, cells.get(), srgb.get(), cut, packSrgb8(settings.background),
                      frontier.get()};
    const int W = camera.width, H = camera.height;
    const Start mode = pattern_ == Pattern::Full ? Start::Root : exact_ ? Start::Guided : Start::Branch;
    const bool colour = settings.coherence.colour;

    std::vector<RenderStats> rowStats(static_cast<std::size_t>(H));
    std::vector<std::uint64_t> rowNodes(static_cast<std::size_t>(H), 0), rowDeferred(static_cast<std::size_t>(H), 0);
    auto isSupportCol = [&](int x) { return x % 4 == 0 || x == W - 1; };
    auto isBaseRow = [&](int y) { return y % 4 == 0 || y == H - 1; };

    // Pixels whose rays cannot hit the surface are background whatever the pattern, except
    // that paper A's colour fill of background pairs marks some of them filled: written in
    // one pass per row first, unless that fill is on.
    const bool fillFirst = !(colour && settings.coherence.colourFillsBackground);
    auto patternSpan = [&](int y, RenderStats& st) {
        return fillFirst ? fillOutsideSurface(ctx, y, st) : std::pair<int, int>{0, W - 1};
    };
    // The exact variants quantize a row's rays together before its pixels (the approximate
    // ones and `full` stay as paper A's: one ray at a time). One buffer per thread.
    const bool rowsTogether = exact_ && pattern_ != Pattern::Full;
    const auto rowRays = [&](int y, int lo, int hi) -> const RowRays* {
        if (!rowsTogether) return nullptr;
        thread_local RowRays rr;
        rr.make(rays, y, std::max(lo, 0), std::min(hi, W - 1));
        return &rr;
    };
    // One row along its own pattern, all phases while the row is in cache.
    auto doRow = [&](int y, TraversalCounters& k) {
        RenderStats& st = rowStats[std::size_t(y)];
        const auto [lo, hi] = patternSpan(y, st);
        auto outside = [lo = lo, hi = hi](int x) { return x < lo || x > hi; };
        if (pattern_ == Pattern::Full) {
            if (!colour) {
                for (int x = lo; x <= hi; ++x) tracePixel(ctx, x, y, nullptr, mode, st, k);
                return;
            }
            for (int x = 0; x < W; x += 2)
                if (!outside(x)) tracePixel(ctx, x, y, nullptr, mode, st, k);
            if (W % 2 == 0 && !outside(W - 1)) tracePixel(ctx, W - 1, y, nullptr, mode, st, k);
            for (int x = 1; x < W - 1; x += 2) {
                if (outside(x)) continue;
                const std::size_t pr[2] = {frame.pixel(x - 1, y), frame.pixel(x + 1, y)};
                if (!tryFill(ctx, x, y, pr, st)) tracePixel(ctx, x, y, nullptr, mode, st, k);
            }
            return;
        }
        const RowRays* rr = rowRays(y, lo, hi);
        // 1. supporting columns
        for (int x = 0; x < W; ++x)
            if (isSupportCol(x) && !outside(x)) tracePixel(ctx, x, y, nullptr, mode, st, k, rr);
        // 2. middle of each 4-pixel group, from the supporting pixels 2 away
        for (int x = 2; x < W; x += 4) {
            if (isSupportCol(x) || outside(x)) continue;
            const std::size_t pr[2] = {frame.pixel(x - 2, y), frame.pixel(std::min(x + 2, W - 1), y)};
            tracePixel(ctx, x, y, pr, mode, st, k, rr);
        }
        // 3. the two remaining pixels, from their neighbours at distance 1
        for (int x = 1; x < W; ++x) {
            if (isSupportCol(x) || x % 4 == 2 || outside(x)) continue;
            const std::size_t pr[2] = {frame.pixel(x - 1, y), frame.pixel(x + 1, y)};
            if (!(colour && tryFill(ctx, x, y, pr, st))) tracePixel(ctx, x, y, pr, mode, st, k, rr);
        }
    };
    // The rows strictly between base row b and the next base row, from the pixels above and below.
    auto doBand = [&](int b, TraversalCounters& k) {
        const int next = std::min(b + 4, H - 1);
        std::pair<int, int> span[4];
        for (int y = b + 1; y < next; ++y) span[y - b - 1] = patternSpan(y, rowStats[std::size_t(y)]);
        for (int pass = 0; pass < 2; ++pass)
            for (int y = b + 1; y < next; ++y) {
                if ((y % 4 == 2) != (pass == 0)) continue;  // first the middle row, then the others
                RenderStats& st = rowStats[std::size_t(y)];
                const auto [lo, hi] = span[y - b - 1];
                const RowRays* rr = rowRays(y, lo, hi);
                for (int x = std::max(lo, 0); x <= std::min(hi, W - 1); ++x) {
                    if (y % 4 == 2) {
                        const std::size_t pr[2] = {frame.pixel(x, y - 2), frame.pixel(x, std::min(y + 2, H - 1))};
                        tracePixel(ctx, x, y, pr, mode, st, k, rr);
                    } else {
                        const std::size_t pr[2] = {frame.pixel(x, y - 1), frame.pixel(x, y + 1)};
                        if (!(colour && tryFill(ctx, x, y, pr, st))) tracePixel(ctx, x, y, pr, mode, st, k, rr);
                    }
                }
            }
    };
    auto run = [&](std::size_t count, auto body) {
        parallelFor(count, settings.threads, [&](std::size_t i) {
            TraversalCounters k;
            const int y = body(int(i), k);
            if (y >= 0) {
                rowNodes[std::size_t(y)] += k.nodes;
                rowDeferred[std::size_t(y)] += k.statesDeferred;
            }
        });
    };
    if (pattern_ != Pattern::Area) {
        run(std::size_t(H), [&](int y, TraversalCounters& k) {
            doRow(y, k);
            return y;
        });
    } else {
        // Base rows first (each on its own), then the bands between them.
        std::vector<int> base;
        for (int y = 0; y < H; ++y)
            if (isBaseRow(y)) base.push_back(y);
        run(base.size(), [&](int i, TraversalCounters& k) {
            doRow(base[std::size_t(i)], k);
            return base[std::size_t(i)];
        });
        run(base.size(), [&](int i, TraversalCounters& k) {
            doBand(base[std::size_t(i)], k);
            return base[std::size_t(i)] + 1 < H ? base[std::size_t(i)] + 1 : -1;  // counters kept on a band row
        });
    }
    RenderStats total;
    total.renderer = name() + (colour ? "+colour" : "");  // the alias that names these settings
    for (std::size_t y = 0; y < rowStats.size(); ++y) {
        rowStats[y].nodesVisited = rowNodes[y];
        rowStats[y].statesDeferred = rowDeferred[y];
        rowStats[y].pixels = std::uint64_t(W);
        total.add(rowStats[y]);
    }
    total.renderMs = timer.ms();
    return total;
}

}  // namespace octrace::detail
