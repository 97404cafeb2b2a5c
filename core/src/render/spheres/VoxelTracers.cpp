// samet and beam on the voxel octree (docs/dev/spheres.md, "On the voxel octree"). Both trace
// the quantized rays of PixelRays under the discrete traversal's semantics (DiscreteTraversal.h:
// each axis of negative direction mirrored, cells half-open [lo, hi), the ray visits the cells
// holding a point of its line at or beyond the eye), so their hit is the reference's.
#include "render/spheres/VoxelTracers.h"

#include "render/PerPixel.h"
#include "render/traversal/PixelRays.h"
#include "octrace/util/Error.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace octrace::detail {
namespace {

using i64 = std::int64_t;
__extension__ typedef __int128 i128;
constexpr int N = Octree::kIntBits;
constexpr int Q = QuantizedRay::kFracBits;
constexpr i64 L = i64(1) << N;
constexpr unsigned axisBit(int a) { return 4u >> a; }

/// Mirrored lattice coordinate of the low face of an original cell at `level` along axis a.
inline i64 mirroredLo(unsigned sign, int a, int cell, int level) {
    const i64 s = i64(1) << (N - level), lo = i64(cell) << (N - level);
    return (sign & axisBit(a)) ? L - lo - s : lo;
}

/// A point of the quantized line, given by its mirrored main coordinate num / den in lattice
/// units (den > 0). Numerators stay below 2^44 and denominators below 2^28, so products of the
/// cross-multiplication are exact in 128 bits.
struct LinePoint {
    i128 num = 0, den = 1;
};
inline bool before(const LinePoint& a, const LinePoint& b) { return a.num * b.den < b.num * a.den; }

/// The quantized line in mirrored lattice space: the main coordinate m is its parameter; the
/// u (v) coordinate is (U0 2^N + m dU) / 2^(N+Q), non-decreasing.
class MirroredLine {
public:
    explicit MirroredLine(const QuantizedRay& r) : r_(r) {
        role_[r.main] = 0;
        role_[r.u] = 1;
        role_[r.v] = 2;
    }
    unsigned sign() const { return r_.sign; }
    /// Whether the line moves along original axis a (the main axis always does).
    bool moves(int a) const { return role_[a] == 0 || slope(a) > 0; }
    /// The point where the mirrored coordinate along axis a reaches c (a must move).
    LinePoint reach(int a, i64 c) const {
        if (role_[a] == 0) return {c, 1};
        return {(i128(c) << (N + Q)) - (i128(base(a)) << N), slope(a)};
    }
    /// Whether the point's mirrored coordinate along axis a is >= c.
    bool atLeast(const LinePoint& p, int a, i64 c) const {
        if (!moves(a)) return base(a) >= (c << Q);
        return !before(p, reach(a, c));
    }
    /// The first point the ray visits: where the line enters the cube, or the eye if later.
    LinePoint start() const {
        LinePoint p{r_.eyeM, i128(1) << Q};  // eyeM >= 0: not before the lower main plane
        for (int a = 0; a < 3; ++a)
            if (role_[a] != 0 && moves(a)) {
                const LinePoint e = reach(a, 0);
                if (before(p, e)) p = e;
            }
        return p;
    }

private:
    i64 base(int a) const { return role_[a] == 1 ? r_.U0 : r_.V0; }
    i64 slope(int a) const { return role_[a] == 1 ? r_.dU : r_.dV; }
    const QuantizedRay& r_;
    int role_[3] = {0, 1, 2};
};

/// The leaf a step ends in.
enum class Leaf { Empty, Hit, OutOfCube };

/// Samet's neighbour finding with a root-to-leaf path instead of parent links: the current
/// leaf is (level_, cell_) with its ancestors path_[0 .. level_-1]; the current point p_ is
/// where the ray entered it.
class SametWalker {
public:
    SametWalker(const Octree& tree, const QuantizedRay& r, TraversalCounters& c) : tree_(tree), line_(r), c_(c) {}

    TraversalHit run() {
        p_ = line_.start();
        path_[0] = 0;
        cell_ = ivec3(0);
        Leaf leaf = down(0);
        while (leaf == Leaf::Empty) leaf = step();
        return leaf == Leaf::Hit ? hit_ : TraversalHit{};
    }

private:
    /// What child `c` of inner node path_[l] is, with cell_ its cell at level l + 1; when it is
    /// an inner node, path_[l + 1] is set and Leaf::OutOfCube stands for "not a leaf".
    Leaf child(int l, unsigned c) {
        const OctreeNode& nd = tree_.nodes()[path_[l]];
        level_ = l + 1;
        if (!(nd.childMask & (1u << c))) return Leaf::Empty;
        const std::uint32_t slot = nd.firstChild + childRank(nd.childMask, c);
        if (level_ == tree_.depth) {
            hit_.voxel = slot;
            hit_.cell = cell_;
            hit_.leafShift = 0;
            return Leaf::Hit;
        }
        if (nd.termMask & (1u << c)) {
            if (tree_.form != OctreeForm::Shell) return Leaf::Empty;  // an interior term: not drawn
            hit_.voxel = tree_.nodes()[slot].firstChild;                 // a coarse leaf
            hit_.leafShift = tree_.depth - level_;
            hit_.cell = cell_ * (1 << hit_.leafShift);
            return Leaf::Hit;
        }
        path_[level_] = slot;
        return Leaf::OutOfCube;
    }

    /// From inner node path_[l] (cell_ its cell) down to the leaf holding p_.
    Leaf down(int l) {
        const unsigned sign = line_.sign();
        for (;; ++l) {
            ++c_.nodes;
            const i64 half = i64(1) << (N - l - 1);
            unsigned c = 0;
            for (int a = 0; a < 3; ++a) {
                const bool high = line_.atLeast(p_, a, mirroredLo(sign, a, cell_[a], l) + half) != ((sign & axisBit(a)) != 0);
                cell_[a] = cell_[a] * 2 + int(high);
                if (high) c |= axisBit(a);
            }
            const Leaf leaf = child(l, c);
            if (leaf != Leaf::OutOfCube) return leaf;
        }
    }

    /// From the current leaf to the next one along the ray: its exit point, the neighbour of
    /// equal size across the exit face (edge, corner) by climbing to the common ancestor and
    /// descending the mirrored path, then down to the leaf that holds the exit point.
    Leaf step() {
        const unsigned sign = line_.sign();
        const i64 s = i64(1) << (N - level_);
        LinePoint exit;
        unsigned exitAxes = 0;
        for (int a = 0; a < 3; ++a) {
            if (!line_.moves(a)) continue;
            const LinePoint e = line_.reach(a, mirroredLo(sign, a, cell_[a], level_) + s);
            if (exitAxes == 0 || before(e, exit)) {
                exit = e;
                exitAxes = axisBit(a);
            } else if (!before(exit, e)) {
                exitAxes |= axisBit(a);  // through an edge or corner: ties move on every such axis
            }
        }
        ivec3 next = cell_;
        for (int a = 0; a < 3; ++a) {
            if (!(exitAxes & axisBit(a))) continue;
            if (mirroredLo(sign, a, cell_[a], level_) + s == L) return Leaf::OutOfCube;
            next[a] += (sign & axisBit(a)) ? -1 : 1;
        }
        p_ = exit;
        // Climb: the common ancestor is where the two cells' coordinates agree.
        const unsigned diff = unsigned((cell_.x ^ next.x) | (cell_.y ^ next.y) | (cell_.z ^ next.z));
        const int target = level_;
        int l = target - std::bit_width(diff);
        // Descend the mirrored path: the neighbour's own bits, as deep as the tree goes.
        for (; l < target; ++l) {
            ++c_.nodes;
            const int shift = target - l - 1;
            cell_ = ivec3(next.x >> shift, next.y >> shift, next.z >> shift);
            const unsigned c = unsigned((cell_.x & 1) << 2 | (cell_.y & 1) << 1 | (cell_.z & 1));
            const Leaf leaf = child(l, c);
            if (leaf != Leaf::OutOfCube) return leaf;
        }
        return down(target);  // the neighbour is an inner node: down to the exit point's leaf
    }

    const Octree& tree_;
    MirroredLine line_;
    TraversalCounters& c_;
    LinePoint p_;
    int level_ = 0;
    ivec3 cell_{0};
    std::uint32_t path_[Octree::kMaxDepth + 1] = {};
    TraversalHit hit_;
};

/// Primary rays of one screen tile as beams (paper B): a beam is the eye, a rectangle of the
/// tile's pixels and optionally a filter on the rays' direction signs. It descends the octree
/// front to back; each node's projected bounds cut the rectangle by binary search in the
/// sorted pixel coordinates; empty nodes cost nothing; in a boundary leaf the beam's rays not
/// yet hit are tested exactly (rayCrossesCell); the tile ends once every ray meeting the cube
/// is hit.
///
/// Front to back: a ray crosses a split plane only from its start side to the other, which for
/// a pinhole eye is the eye's side. A quantized ray lies within 2^-12 lattice units of its true
/// ray, so the eye's side holds for every ray of the beam unless the eye is that close to the
/// plane; there the beam is split by the rays' own direction sign on that axis, which orders
/// each half exactly. Orthographic rays share one direction: its signs give the order.
class VoxelBeamTile {
public:
    VoxelBeamTile(const Octree& tree, const RayGenerator& gen, int x0, int y0, int w, int h,
                  const PixelRays& pixels, const std::vector<std::uint8_t>& meets, std::vector<TraversalHit>& hits, TraversalCounters& c,
                  double cosWidest, std::uint64_t& beams, std::uint64_t& tests)
        : tree_(tree), gen_(gen), cosWidest_(cosWidest), x0_(x0), y0_(y0), w_(w), pixels_(pixels), hits_(hits), c_(c),
          beams_(beams), tests_(tests) {
        xs_.resize(std::size_t(w));
        ys_.resize(std::size_t(h));
        for (int i = 0; i < w; ++i) xs_[std::size_t(i)] = x0 + i + 0.5;
        for (int j = 0; j < h; ++j) ys_[std::size_t(j)] = y0 + j + 0.5;
        // A ray is quantized when a leaf first tests it; its direction signs (the quantized
        // ray's, for every ray that meets the cube) are known at once.
        const std::size_t n = meets.size();
        done_.resize(n);
        rays_.resize(n);
        quantized_.assign(n, 0);
        signs_.assign(n, 0);
        for (std::size_t k = 0; k < n; ++k) {
            done_[k] = !meets[k];
            remaining_ += meets[k];
            const dvec3 d = pixels.direction(x0 + int(k % std::size_t(w)), y0 + int(k / std::size_t(w)));
            for (int a = 0; a < 3; ++a)
                if (d[a] < 0.0) signs_[k] |= std::uint8_t(axisBit(a));
        }
        eye_ = tree.toOctreeSpace(gen.eye());
        worldPerUnit_ = tree.cubeSide / double(L);
        const dvec3 rel0 = tree.cubeOrigin - gen.eye();
        camOrigin_ = dvec3(glm::dot(rel0, gen.right()), glm::dot(rel0, gen.up()), glm::dot(rel0, gen.back()));
        for (int a = 0; a < 3; ++a)
            camAxis_[a] = dvec3(gen.right()[a], gen.up()[a], gen.back()[a]) * worldPerUnit_;
        const dvec3 d = -gen.back();
        for (int a = 0; a < 3; ++a)
            if (d[a] < 0.0) orthoSign_ |= axisBit(a);
        h_ = h;
    }

    void run() {
        if (remaining_ > 0 && !tree_.nodes().empty() && tree_.depth >= 1) visit(0, 0, ivec3(0), Rect{0, w_, 0, h_}, 0, 0);
    }

private:
    struct Rect {
        int i0, i1, j0, j1;
    };

    void visit(std::uint32_t node, int level, const ivec3& cell, Rect r, unsigned fMask, unsigned fSign) {
        ++beams_;
        ++c_.nodes;
        if (!cut(level, cell, r)) return;
        children(node, level, cell, r, fMask, fSign);
    }

    void children(std::uint32_t node, int level, const ivec3& cell, const Rect& r, unsigned fMask, unsigned fSign) {
        // flip: the axes whose high half comes first.
        unsigned flip = 0;
        for (int a = 0; a < 3; ++a) {
            const unsigned b = axisBit(a);
            if (fMask & b) {
                flip |= fSign & b;
            } else if (gen_.orthographic()) {
                flip |= orthoSign_ & b;
            } else {
                const double mid = std::ldexp(double(2 * cell[a] + 1), N - level - 1);
                if (std::abs(eye_[a] - mid) < kEyeTolerance) {  // the eye on the plane: split by the rays' signs
                    children(node, level, cell, r, fMask | b, fSign);
                    if (remaining_ > 0) children(node, level, cell, r, fMask | b, fSign | b);
                    return;
                }
                if (eye_[a] > mid) flip |= b;
            }
        }
        const OctreeNode& nd = tree_.nodes()[node];
        for (unsigned k = 0; k < 8 && remaining_ > 0; ++k) {
            const unsigned c = k ^ flip;
            if (!(nd.childMask & (1u << c))) continue;  // empty: the beam only moves on
            const std::uint32_t slot = nd.firstChild + childRank(nd.childMask, c);
            const ivec3 cc = cell * 2 + ivec3((c >> 2) & 1, (c >> 1) & 1, c & 1);
            if (level + 1 == tree_.depth) {
                intersect(level + 1, cc, slot, r, fMask, fSign);
            } else if (nd.termMask & (1u << c)) {
                if (tree_.form == OctreeForm::Shell) intersect(level + 1, cc, tree_.nodes()[slot].firstChild, r, fMask, fSign);
            } else {
                visit(slot, level + 1, cc, r, fMask, fSign);
            }
        }
    }

    /// A boundary leaf (voxel or coarse leaf `voxel` at `level`): each ray of the beam not yet
    /// hit that crosses it has it as its hit, being visited in the ray's own order.
    void intersect(int level, const ivec3& cell, std::uint32_t voxel, Rect r, unsigned fMask, unsigned fSign) {
        ++beams_;
        // A few rays are tested faster than the leaf is projected.
        if ((r.i1 - r.i0) * (r.j1 - r.j0) > kFewRays && !cut(level, cell, r)) return;
        const int shift = tree_.depth - level;
        for (int j = r.j0; j < r.j1; ++j)
            for (int i = r.i0; i < r.i1; ++i) {
                const std::size_t k = std::size_t(j) * std::size_t(w_) + std::size_t(i);
                if (done_[k] || (signs_[k] & fMask) != fSign) continue;
                ++tests_;
                if (!quantized_[k]) {
                    rays_[k] = pixels_.quantized(x0_ + i, y0_ + j, pixels_.direction(x0_ + i, y0_ + j));
                    quantized_[k] = 1;
                }
                if (!rayCrossesCell(rays_[k], cell, level)) continue;
                TraversalHit& h = hits_[k];
                h.voxel = voxel;
                h.leafShift = shift;
                h.cell = cell * (1 << shift);
                done_[k] = 1;
                --remaining_;
            }
    }

    /// Narrows the rectangle to the rays whose pixel centre lies in the projection of the cell's
    /// box widened by kEyeTolerance lattice units (a quantized ray that crosses the box passes
    /// that close to its true ray). False when no ray is left.
    ///
    /// Perspective: a ray of the view frustum at distance r from the eye is at least c0 r in
    /// front of it (c0: the cosine of the widest pixel's angle to the view axis). So for a box
    /// at distance D from the eye the rays meet only its part at depth >= eps = c0 D / 2: the
    /// box clipped by that plane, whose outline is the hull of its corners in front and of its
    /// edges' crossings of the plane. Nothing in front: no ray meets it. The eye in the box:
    /// no cut.
    bool cut(int level, const ivec3& cell, Rect& r) const {
        const double side = std::ldexp(1.0, N - level);
        const dvec3 lo = dvec3(cell) * side - kEyeTolerance, hi = dvec3(cell + 1) * side + kEyeTolerance;
        // Corners in camera coordinates (along right, up, back from the eye): affine in octree space.
        dvec3 cam[8];
        cam[0] = camOrigin_ + camAxis_[0] * lo.x + camAxis_[1] * lo.y + camAxis_[2] * lo.z;
        const double edge = hi.x - lo.x;
        for (int k = 1; k < 8; ++k) {
            const int a = k & 4 ? 0 : k & 2 ? 1 : 2;  // the highest axis bit of k: k = (k ^ bit) + bit
            cam[k] = cam[k ^ int(axisBit(a))] + camAxis_[a] * edge;
        }
        double pxLo = kInf, pxHi = -kInf, pyLo = kInf, pyHi = -kInf;
        auto add = [&](const dvec3& c) {
            double px, py;
            gen_.toPixel(c.x, c.y, c.z, px, py);
            pxLo = std::min(pxLo, px);
            pxHi = std::max(pxHi, px);
            pyLo = std::min(pyLo, py);
            pyHi = std::max(pyHi, py);
        };
        if (gen_.orthographic()) {
            bool front = false;
            for (const dvec3& c : cam) {
                add(c);
                front = front || c.z < 0.0;
            }
            if (!front) return false;  // behind the view plane
        } else {
            const double dist = glm::length(glm::clamp(eye_, lo, hi) - eye_) * worldPerUnit_;
            if (!(dist > 0.0)) return true;  // the eye in the box
            const double eps = 0.5 * cosWidest_ * dist;
            bool front = false;
            for (int k = 0; k < 8; ++k) {
                if (cam[k].z > -eps) continue;
                add(cam[k]);
                front = true;
                for (int a = 0; a < 3; ++a) {  // edges to corners behind the plane: their crossing
                    const dvec3& o = cam[k ^ (4 >> a)];
                    if (o.z <= -eps) continue;
                    const double f = (-eps - cam[k].z) / (o.z - cam[k].z);
                    add(cam[k] + (o - cam[k]) * f);
                }
            }
            if (!front) return false;
        }
        r.i0 = std::max(r.i0, int(std::lower_bound(xs_.begin(), xs_.end(), pxLo - kMargin) - xs_.begin()));
        r.i1 = std::min(r.i1, int(std::upper_bound(xs_.begin(), xs_.end(), pxHi + kMargin) - xs_.begin()));
        r.j0 = std::max(r.j0, int(std::lower_bound(ys_.begin(), ys_.end(), pyLo - kMargin) - ys_.begin()));
        r.j1 = std::min(r.j1, int(std::upper_bound(ys_.begin(), ys_.end(), pyHi + kMargin) - ys_.begin()));
        return r.i0 < r.i1 && r.j0 < r.j1;
    }

    static constexpr double kEyeTolerance = 1.0 / 64.0;  // lattice units, far above the quantization's 2^-12
    static constexpr int kFewRays = 4;
    static constexpr double kMargin = 1e-6;              // pixels: the projection's rounding is far below
    static constexpr double kInf = std::numeric_limits<double>::infinity();
    const Octree& tree_;
    const RayGenerator& gen_;
    double cosWidest_;
    int x0_, y0_, w_, h_ = 0;
    const PixelRays& pixels_;
    std::vector<QuantizedRay> rays_;
    std::vector<std::uint8_t> quantized_, signs_;
    std::vector<TraversalHit>& hits_;
    TraversalCounters& c_;
    std::uint64_t& beams_;
    std::uint64_t& tests_;
    std::vector<double> xs_, ys_;
    std::vector<std::uint8_t> done_;
    std::size_t remaining_ = 0;
    dvec3 eye_;                 // octree space
    double worldPerUnit_ = 1.0;  // world length of one lattice unit
    dvec3 camOrigin_, camAxis_[3];  // camera coordinates of the lattice origin and per unit along each axis
    unsigned orthoSign_ = 0;
};

constexpr int kBeamTile = 32;  // the initial beams: screen tiles of 32 x 32 pixels

RenderStats renderBeams(const std::string& name, const Octree& tree, const Camera& camera, const RenderSettings& settings,
                        Frame& frame) {
    camera.validate();
    Timer timer;
    frame.reshape(camera.width, camera.height);  // every pixel is written below
    const Shader shader(tree, camera, settings);
    const PixelRays rays(tree, camera);
    const RayGenerator gen(camera);
    // The cosine of the widest angle between a pixel's ray and the view axis (perspective).
    const double halfH = std::tan(glm::radians(camera.fovYDegrees) * 0.5), halfW = halfH * camera.width / camera.height;
    const double cosWidest = 1.0 / std::sqrt(1.0 + halfH * halfH + halfW * halfW);
    const int tilesX = (camera.width + kBeamTile - 1) / kBeamTile, tilesY = (camera.height + kBeamTile - 1) / kBeamTile;
    std::vector<RenderStats> tileStats(std::size_t(tilesX) * std::size_t(tilesY));
    parallelFor(tileStats.size(), settings.threads, [&](std::size_t t) {
        RenderStats& st = tileStats[t];
        const int x0 = int(t % std::size_t(tilesX)) * kBeamTile, y0 = int(t / std::size_t(tilesX)) * kBeamTile;
        const int x1 = std::min(x0 + kBeamTile, camera.width), y1 = std::min(y0 + kBeamTile, camera.height);
        const int w = x1 - x0, h = y1 - y0;
        std::vector<std::uint8_t> meets(std::size_t(w) * std::size_t(h));
        std::vector<TraversalHit> hits(meets.size());
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i) {
                const bool m = rays.mayMeetCube(x0 + i, y0 + j) && rays.meetsCube(x0 + i, y0 + j);
                meets[std::size_t(j) * std::size_t(w) + std::size_t(i)] = m;
                st.rays += m;
            }
        TraversalCounters counters;
        VoxelBeamTile(tree, gen, x0, y0, w, h, rays, meets, hits, counters, cosWidest, st.beams, st.intersections).run();
        for (int j = 0; j < h; ++j)
            for (int i = 0; i < w; ++i)
                writePixelHit(frame, x0 + i, y0 + j, hits[std::size_t(j) * std::size_t(w) + std::size_t(i)], shader, rays,
                              rays.direction(x0 + i, y0 + j), settings, st, counters);
        st.nodesVisited = counters.nodes;
    });
    return RenderStats::total(name, tileStats, timer.ms());
}

}  // namespace

RenderStats renderVoxelTracer(VoxelTracer tracer, const std::string& name, const Octree& tree, const Camera& camera,
                              const RenderSettings& settings, Frame& frame) {
    if (settings.detail.active(tree.depth))
        throw UsageError("renderer " + name + " has no multi-resolution mode (`lod`, `level`): use " + voxelRenderersThat(&Renderer::multiResolution));
    if (tracer == VoxelTracer::Beam) return renderBeams(name, tree, camera, settings, frame);
    return renderPerPixel(name, tree, camera, settings, frame,
                          [&](const PixelRays& rays, int x, int y, const dvec3& d, TraversalCounters& c, bool& meets) {
                              if (!rays.mayMeetCube(x, y)) return TraversalHit{};  // meets stays false
                              const QuantizedRay q = rays.quantized(x, y, d);
                              meets = q.meetsCube;
                              return traverseSamet(tree, q, c);
                          });
}

}  // namespace octrace::detail

namespace octrace {

TraversalHit traverseSamet(const Octree& tree, const QuantizedRay& ray, TraversalCounters& counters) {
    if (!ray.meetsCube || tree.nodes().empty() || tree.depth < 1) return TraversalHit{};
    return detail::SametWalker(tree, ray, counters).run();
}

}  // namespace octrace
