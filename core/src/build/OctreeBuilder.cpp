#include "octrace/build/OctreeBuilder.h"

#include "build/MinMaxPyramid.h"
#include "build/TreeAssembly.h"
#include "octrace/build/Volume.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Memory.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <charconv>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <sstream>

namespace octrace {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// Shortest text that reads back as the same value: "0.7" for 0.7f rather than "0.699999988",
/// and enough digits to tell an iso value from a range end it differs from (the default
/// six significant digits printed "iso value 0.7 is outside the value range [.., 0.7]").
template <class T>
std::string shortest(T v) {
    char buf[64];
    auto r = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, r.ptr);
}

/// Where a position along one grid axis (local frame) falls: sample i0, weight t towards i1.
struct AxisSample {
    int i0 = 0, i1 = 0;
    float t = 0.0f;
    bool inside = false;
};

/// Everything the build needs to evaluate the trilinear field at world points.
class FieldSampler {
public:
    /// `samples`: the field's values with NaN at masked samples (SampleGrid; not owned).
    FieldSampler(const ScalarField& f, const std::vector<float>& samples, const dvec3& cubeOrigin, double h, int depth)
        : f_(f), cubeOrigin_(cubeOrigin), h_(h), samples_(samples) {
        dmat3 d = f.direction;
        separable_ = true;
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r)
                if (std::abs(d[c][r] - (r == c ? 1.0 : 0.0)) > 1e-12) separable_ = false;
        inverse_ = glm::transpose(d);  // orthonormal
        if (separable_) {
            const int n = (1 << depth) + 1;
            for (int a = 0; a < 3; ++a) {
                table_[a].resize(std::size_t(n));
                for (int c = 0; c < n; ++c) table_[a][std::size_t(c)] = locate(a, cubeOrigin[a] + c * h - f.origin[a]);
            }
        }
    }

    /// Bytes of the per-depth axis tables (for memory estimates).
    static std::uint64_t tableBytes(int depth) { return 3 * ((std::uint64_t(1) << depth) + 1) * sizeof(AxisSample); }

    /// Continuous position along axis a (local frame) -> samples and weight.
    AxisSample locate(int a, double u) const {
        AxisSample s;
        const int n = f_.dims[a];
        double idx;
        if (f_.coords[a].empty()) {
            idx = u / f_.spacing[a];
        } else {
            const auto& c = f_.coords[a];
            double span = c.back() - c.front();
            if (u < c.front() - 1e-9 * span || u > c.back() + 1e-9 * span) return s;
            auto it = std::upper_bound(c.begin(), c.end(), u);
            int i = int(it - c.begin()) - 1;
            i = std::clamp(i, 0, n - 2);
            idx = i + (u - c[std::size_t(i)]) / (c[std::size_t(i) + 1] - c[std::size_t(i)]);
        }
        const double tol = 1e-7;
        if (idx < -tol || idx > (n - 1) + tol) return s;
        idx = std::clamp(idx, 0.0, double(n - 1));
        int i0 = std::min(int(std::floor(idx)), n - 1);
        double t = idx - i0;
        s.inside = true;
        s.i0 = i0;
        s.t = float(t);
        s.i1 = (t > 0.0 && i0 + 1 < n) ? i0 + 1 : i0;
        if (s.i1 == i0) s.t = 0.0f;
        return s;
    }

    float trilinear(const AxisSample& x, const AxisSample& y, const AxisSample& z) const {
        if (!x.inside || !y.inside || !z.inside) return kNaN;
        auto at = [&](int i, int j, int k) { return samples_[f_.index(i, j, k)]; };
        float c00 = at(x.i0, y.i0, z.i0) * (1 - x.t) + at(x.i1, y.i0, z.i0) * x.t;
        float c10 = at(x.i0, y.i1, z.i0) * (1 - x.t) + at(x.i1, y.i1, z.i0) * x.t;
        float c01 = at(x.i0, y.i0, z.i1) * (1 - x.t) + at(x.i1, y.i0, z.i1) * x.t;
        float c11 = at(x.i0, y.i1, z.i1) * (1 - x.t) + at(x.i1, y.i1, z.i1) * x.t;
        float c0 = c00 * (1 - y.t) + c10 * y.t;
        float c1 = c01 * (1 - y.t) + c11 * y.t;
        return c0 * (1 - z.t) + c1 * z.t;
    }

    void locateWorld(const dvec3& p, AxisSample s[3]) const {
        dvec3 local = inverse_ * (p - f_.origin);
        for (int a = 0; a < 3; ++a) s[a] = locate(a, local[a]);
    }

    /// Trilinear value at a world point; NaN = a masked sample in the interpolation, or outside.
    float atWorld(const dvec3& p) const {
        AxisSample s[3];
        locateWorld(p, s);
        return trilinear(s[0], s[1], s[2]);
    }

    /// Trilinear value at lattice corner c (cell space); NaN = masked or outside.
    float corner(const ivec3& c) const {
        if (separable_)
            return trilinear(table_[0][std::size_t(c.x)], table_[1][std::size_t(c.y)], table_[2][std::size_t(c.z)]);
        AxisSample s[3];
        locateWorld(cubeOrigin_ + dvec3(c) * h_, s);
        return trilinear(s[0], s[1], s[2]);
    }

    /// Inclusive sample index box that the corners of the cell box [c0, c0+size] use;
    /// false when the box lies outside the grid.
    bool sampleRange(const ivec3& c0, int size, ivec3& lo, ivec3& hi) const {
        dvec3 wlo = cubeOrigin_ + dvec3(c0) * h_, whi = wlo + dvec3(size * h_);
        dvec3 llo(std::numeric_limits<double>::infinity()), lhi = -llo;
        for (int c = 0; c < 8; ++c) {
            dvec3 p((c & 4) ? whi.x : wlo.x, (c & 2) ? whi.y : wlo.y, (c & 1) ? whi.z : wlo.z);
            dvec3 l = inverse_ * (p - f_.origin);
            llo = glm::min(llo, l);
            lhi = glm::max(lhi, l);
        }
        for (int a = 0; a < 3; ++a) {
            double first = f_.axisPosition(a, 0), last = f_.axisPosition(a, f_.dims[a] - 1);
            double tol = 1e-9 * (last - first);
            if (lhi[a] < first - tol || llo[a] > last + tol) return false;
            AxisSample s0 = locate(a, std::max(llo[a], first)), s1 = locate(a, std::min(lhi[a], last));
            lo[a] = s0.i0;
            hi[a] = std::max(s1.i1, s1.i0);
        }
        return true;
    }

    /// Whether the cell box [c0, c0+size] lies wholly inside the grid (and so does every
    /// trilinear corner in it).
    bool boxInsideGrid(const ivec3& c0, int size) const {
        for (int c = 0; c < 8; ++c) {
            const ivec3 p = c0 + size * ivec3((c >> 2) & 1, (c >> 1) & 1, c & 1);
            AxisSample s[3];
            if (separable_) {
                for (int a = 0; a < 3; ++a) s[a] = table_[a][std::size_t(p[a])];
            } else {
                locateWorld(cubeOrigin_ + dvec3(p) * h_, s);
            }
            if (!s[0].inside || !s[1].inside || !s[2].inside) return false;
        }
        return true;
    }

    /// Gradient of the field in world space at world point p: per-sample central differences
    /// (one-sided at borders and next to masked samples) interpolated trilinearly.
    dvec3 gradientWorld(const dvec3& p) const {
        AxisSample s[3];
        locateWorld(p, s);
        if (!s[0].inside || !s[1].inside || !s[2].inside) return dvec3(0.0);
        dvec3 g(0.0);
        double wsum = 0.0;
        for (int c = 0; c < 8; ++c) {
            int i = (c & 4) ? s[0].i1 : s[0].i0, j = (c & 2) ? s[1].i1 : s[1].i0, k = (c & 1) ? s[2].i1 : s[2].i0;
            double w = ((c & 4) ? s[0].t : 1 - s[0].t) * ((c & 2) ? s[1].t : 1 - s[1].t) * ((c & 1) ? s[2].t : 1 - s[2].t);
            if (w == 0.0) continue;
            dvec3 gl = sampleGradientLocal(i, j, k);
            g += w * gl;
            wsum += w;
        }
        if (wsum > 0.0) g /= wsum;
        return f_.direction * g;
    }

private:
    dvec3 sampleGradientLocal(int i, int j, int k) const {
        dvec3 g(0.0);
        const int idx[3] = {i, j, k};
        for (int a = 0; a < 3; ++a) {
            int lo = idx[a] - 1, hi = idx[a] + 1;
            auto valueAt = [&](int n) {
                int q[3] = {i, j, k};
                q[a] = n;
                return samples_[f_.index(q[0], q[1], q[2])];
            };
            float vc = valueAt(idx[a]);
            float vl = lo >= 0 ? valueAt(lo) : kNaN;
            float vh = hi < f_.dims[a] ? valueAt(hi) : kNaN;
            if (!std::isnan(vl) && !std::isnan(vh))
                g[a] = (vh - vl) / (f_.axisPosition(a, hi) - f_.axisPosition(a, lo));
            else if (!std::isnan(vh))
                g[a] = (vh - vc) / (f_.axisPosition(a, hi) - f_.axisPosition(a, idx[a]));
            else if (!std::isnan(vl))
                g[a] = (vc - vl) / (f_.axisPosition(a, idx[a]) - f_.axisPosition(a, lo));
        }
        return g;
    }

    const ScalarField& f_;
    dvec3 cubeOrigin_;
    double h_;
    const std::vector<float>& samples_;
    bool separable_ = false;
    dmat3 inverse_{1.0};
    std::vector<AxisSample> table_[3];
};

/// What every depth's build reads: the field's values with NaN at masked samples, and their
/// min/max pyramid (which points into the samples: neither copied nor moved).
struct SampleGrid {
    explicit SampleGrid(const ScalarField& f) : samples(maskedSamples(f)), pyramid(samples.data(), f.dims) {}
    SampleGrid(const SampleGrid&) = delete;
    SampleGrid& operator=(const SampleGrid&) = delete;

    static std::uint64_t bytesFor(ivec3 dims) {
        return saturatingMultiply(sizeof(float), std::uint64_t(dims.x) * std::uint64_t(dims.y) * std::uint64_t(dims.z)) +
               detail::MinMaxPyramid::bytesFor(dims);
    }
    static std::vector<float> maskedSamples(const ScalarField& f) {
        std::vector<float> s(f.values.size());
        for (std::size_t i = 0; i < f.values.size(); ++i) s[i] = (f.isValid(i) && std::isfinite(f.values[i])) ? f.values[i] : kNaN;
        return s;
    }

    std::vector<float> samples;
    detail::MinMaxPyramid pyramid;
};

/// Counts the bytes the build allocates against the budget, before allocating them; shared by
/// the worker threads. The first allocation that would go over stops every worker: each
/// throws the same LimitError at its next allocation, so whichever one parallelFor passes on
/// says the same thing.
class MemoryGuard {
public:
    MemoryGuard(const ScalarField& f, int depth, std::uint64_t budget, std::uint64_t base, std::uint64_t estimate)
        : field_(f), depth_(depth), budget_(budget), estimate_(estimate), used_(base) {}

    void allocate(std::uint64_t bytes) {
        if (stopped_.load(std::memory_order_relaxed)) fail();
        if (used_.fetch_add(bytes) + bytes > budget_) {
            used_.fetch_sub(bytes);
            stopped_.store(true);
            fail();
        }
    }
    void release(std::uint64_t bytes) { used_.fetch_sub(bytes); }

private:
    [[noreturn]] void fail() const {
        throw LimitError(field_.source + ": building the octree of '" + field_.name + "' at depth " + std::to_string(depth_) +
                         " stopped before going over the memory budget of " + formatBytes(budget_) +
                         " (`max_memory`; it was estimated at " + formatBytes(estimate_) +
                         "); try a smaller `depth` or a larger `max_memory`");
    }

    const ScalarField& field_;
    int depth_;
    std::uint64_t budget_, estimate_;
    std::atomic<std::uint64_t> used_;
    std::atomic<bool> stopped_{false};
};

/// push_back that asks the guard (if any) before the vector grows, doubling as std::vector
/// does; while it grows, the old and the new buffer both exist.
template <class T>
void push(std::vector<T>& v, const T& x, MemoryGuard* guard) {
    if (guard && v.size() == v.capacity()) {
        const std::size_t oldCapacity = v.capacity(), newCapacity = std::max<std::size_t>(16, 2 * oldCapacity);
        guard->allocate(newCapacity * sizeof(T));
        v.reserve(newCapacity);
        guard->release(oldCapacity * sizeof(T));
    }
    v.push_back(x);
}

template <class T>
void shrink(std::vector<T>& v, MemoryGuard* guard) {
    if (v.capacity() == v.size()) return;
    const std::size_t oldCapacity = v.capacity();
    if (guard) guard->allocate(v.size() * sizeof(T));
    v.shrink_to_fit();
    if (guard) guard->release(oldCapacity * sizeof(T));
}

template <class T>
void reserveExactly(std::vector<T>& v, std::size_t n, MemoryGuard* guard) {
    if (guard) guard->allocate(n * sizeof(T));
    v.reserve(n);
}

/// Nodes and voxels of one subtree, with local indices (levels kept to relocate them).
struct Pool {
    std::vector<OctreeNode> nodes;
    std::vector<std::uint8_t> levels;
    std::vector<Voxel> voxels;

    std::uint64_t bytes() const {
        return nodes.capacity() * sizeof(OctreeNode) + levels.capacity() + voxels.capacity() * sizeof(Voxel);
    }
    void shrink(MemoryGuard* guard) {
        ::octrace::shrink(nodes, guard);
        ::octrace::shrink(levels, guard);
        ::octrace::shrink(voxels, guard);
    }
};

using detail::Octant;

class Builder {
public:
    Builder(const ScalarField& f, const SampleGrid& grid, const Octree& tree, float iso, MemoryGuard* guard,
            const std::function<bool()>& cancelled)
        : tree_(tree), iso_(iso), volume_(tree.form == OctreeForm::Volume), below_(tree.insideBelow),
          sampler_(f, grid.samples, tree.cubeOrigin, tree.voxelSize(), tree.depth), pyramid_(grid.pyramid), guard_(guard),
          cancelled_(cancelled), source_(f.source) {}

    /// Throws CancelledError when the caller asked the build to stop.
    void checkCancelled() const {
        if (cancelled_ && cancelled_()) throw CancelledError(source_ + ": octree build cancelled");
    }

    /// Builds the octant at `level` whose minimum cell is c0. Shell form: Empty when it holds
    /// no boundary voxel. Volume form: Empty when it holds no voxel of the solid, Term when
    /// every voxel in it is an interior voxel.
    Octant build(int level, const ivec3& c0, OctreeNode& out, Pool& pool) const {
        const int depth = tree_.depth;
        const int size = 1 << (depth - level);
        ivec3 lo, hi;
        if (!sampler_.sampleRange(c0, size, lo, hi)) return Octant::Empty;
        float mn, mx;
        pyramid_.query(lo, hi, mn, mx);
        if (!(mn <= mx)) return Octant::Empty;
        if (volume_) {
            if (!(below_ ? mn < iso_ : mx >= iso_)) return Octant::Empty;  // no sample inside the solid
            if (level < depth - 1 && wholeInterior(c0, size)) return Octant::Term;
        } else if (mx < iso_ || mn >= iso_) {
            return Octant::Empty;
        }
        if (level == depth - 4) checkCancelled();  // every 16^3 cells that hold the surface
        if (level == depth - 1) return volume_ ? buildVolumeLeafParent(c0, out, pool) : buildLeafParent(c0, out, pool);
        OctreeNode kids[8];
        Octant kinds[8];
        const int half = size / 2;
        for (int c = 0; c < 8; ++c) {
            ivec3 cc = c0 + half * ivec3((c >> 2) & 1, (c >> 1) & 1, c & 1);
            kinds[c] = build(level + 1, cc, kids[c], pool);
        }
        return emitNode(kinds, kids, level + 1, out, pool, guard_);
    }

    /// The node whose children are `kids` of kinds `kinds` (children pushed contiguously into
    /// the pool): Empty when all are, Term when all are terms (eight terms make one).
    static Octant emitNode(const Octant kinds[8], const OctreeNode kids[8], int childLevel, OctreeNode& out, Pool& pool,
                           MemoryGuard* guard) {
        unsigned mask, terms;
        detail::childMasks(kinds, mask, terms);
        if (!mask) return Octant::Empty;
        if (terms == 0xFFu) return Octant::Term;
        out = OctreeNode{};
        out.firstChild = std::uint32_t(pool.nodes.size());
        out.childMask = std::uint8_t(mask);
        out.termMask = std::uint8_t(terms);
        for (int c = 0; c < 8; ++c)
            if (mask & (1u << c)) {
                push(pool.nodes, kinds[c] == Octant::Term ? OctreeNode{} : kids[c], guard);
                push(pool.levels, std::uint8_t(childLevel), guard);
            }
        return Octant::Node;
    }

private:
    Octant buildLeafParent(const ivec3& c0, OctreeNode& out, Pool& pool) const {
        float v[27];
        for (int k = 0; k < 3; ++k)
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 3; ++i) v[i * 9 + j * 3 + k] = sampler_.corner(c0 + ivec3(i, j, k));
        unsigned mask = 0;
        Voxel vox[8];
        for (int c = 0; c < 8; ++c) {
            int x = (c >> 2) & 1, y = (c >> 1) & 1, z = c & 1;
            bool above = false, below = false, masked = false;
            float cv[8];
            for (int q = 0; q < 8; ++q) {
                float val = v[(x + ((q >> 2) & 1)) * 9 + (y + ((q >> 1) & 1)) * 3 + (z + (q & 1))];
                cv[q] = val;
                if (std::isnan(val)) masked = true;
                else if (val >= iso_) above = true;
                else below = true;
            }
            if (masked || !above || !below) continue;
            ivec3 cell = c0 + ivec3(x, y, z);
            vox[c].normal = encodeNormal(normalAt(cell, cv));
            mask |= 1u << c;
        }
        return emitVoxels(mask, 0u, vox, out, pool);
    }

    /// Volume form, the 8 voxels of the node at level depth-1 whose minimum cell is c0: a cell
    /// whose 8 corners are all inside the solid is an interior voxel, unless one of its 6 face
    /// neighbours is masked (a corner masked, outside the grid or outside the cube): then it is
    /// a boundary voxel of a cap, with the normal pointing out towards those neighbours. A cell
    /// that straddles the iso value is a boundary voxel with the field's normal, pointing out
    /// of the solid.
    Octant buildVolumeLeafParent(const ivec3& c0, OctreeNode& out, Pool& pool) const {
        // Corners c0-1 .. c0+3 (5^3): the 2^3 cells and their face neighbours (4^3 cells).
        float v[125];
        const int n = 1 << tree_.depth;
        for (int i = 0; i < 5; ++i)
            for (int j = 0; j < 5; ++j)
                for (int k = 0; k < 5; ++k) {
                    const ivec3 c = c0 + ivec3(i - 1, j - 1, k - 1);
                    const bool inCube = c.x >= 0 && c.y >= 0 && c.z >= 0 && c.x <= n && c.y <= n && c.z <= n;
                    v[(i * 5 + j) * 5 + k] = inCube ? sampler_.corner(c) : kNaN;
                }
        enum : std::uint8_t { kMasked, kOutside, kInside, kStraddle };
        auto classify = [&](const ivec3& l, float cv[8]) {  // l: cell relative to c0 - 1, in 0..3
            bool in = false, out = false;
            for (int q = 0; q < 8; ++q) {
                const float val = v[((l.x + ((q >> 2) & 1)) * 5 + l.y + ((q >> 1) & 1)) * 5 + l.z + (q & 1)];
                cv[q] = val;
                if (std::isnan(val)) return kMasked;
                ((val >= iso_) != below_ ? in : out) = true;
            }
            return in && out ? kStraddle : in ? kInside : kOutside;
        };
        unsigned mask = 0, interior = 0;
        Voxel vox[8];
        for (int c = 0; c < 8; ++c) {
            const ivec3 l(1 + ((c >> 2) & 1), 1 + ((c >> 1) & 1), 1 + (c & 1));
            float cv[8];
            const auto kind = classify(l, cv);
            if (kind == kMasked || kind == kOutside) continue;
            mask |= 1u << c;
            const ivec3 cell = c0 + l - 1;
            if (kind == kStraddle) {
                const vec3 nrm = normalAt(cell, cv);
                vox[c].normal = encodeNormal(below_ ? -nrm : nrm);
                continue;
            }
            vec3 cap(0.0f);
            for (int a = 0; a < 3; ++a)
                for (int s = -1; s <= 1; s += 2) {
                    ivec3 nb = l;
                    nb[a] += s;
                    float unused[8];
                    if (classify(nb, unused) == kMasked) cap[a] += float(s);
                }
            if (cap == vec3(0.0f)) interior |= 1u << c;
            else vox[c].normal = encodeNormal(glm::normalize(cap));
        }
        if (mask == 0xFFu && interior == 0xFFu) return Octant::Term;
        return emitVoxels(mask, interior, vox, out, pool);
    }

    /// The node at level depth-1 with these voxels (`interior`: the interior ones, volume form).
    Octant emitVoxels(unsigned mask, unsigned interior, const Voxel vox[8], OctreeNode& out, Pool& pool) const {
        if (!mask) return Octant::Empty;
        out = OctreeNode{};
        out.firstChild = std::uint32_t(pool.voxels.size());
        out.childMask = std::uint8_t(mask);
        out.termMask = std::uint8_t(interior);
        for (int c = 0; c < 8; ++c)
            if (mask & (1u << c)) push(pool.voxels, (interior & (1u << c)) ? Voxel{} : vox[c], guard_);
        return Octant::Node;
    }

    /// Volume form: whether every voxel of the octant at c0 (side `size` cells) is an interior
    /// voxel, from the pyramid: its cells and their face neighbours lie in the cube and the
    /// grid, no sample they use is masked, and every one is inside the solid.
    bool wholeInterior(const ivec3& c0, int size) const {
        const int n = 1 << tree_.depth;
        const ivec3 lo = c0 - 1;  // the neighbours' corners: lo .. lo + size + 2
        const int span = size + 2;
        for (int a = 0; a < 3; ++a)
            if (lo[a] < 0 || lo[a] + span > n) return false;
        if (!sampler_.boxInsideGrid(lo, span)) return false;
        ivec3 slo, shi;
        if (!sampler_.sampleRange(lo, span, slo, shi)) return false;
        float mn, mx;
        bool masked = false;
        pyramid_.query(slo, shi, mn, mx, &masked);
        if (masked || !(mn <= mx)) return false;
        return below_ ? mx < iso_ : mn >= iso_;
    }

    /// Unit normal pointing towards lower values; falls back to the cell's own trilinear
    /// gradient (then +z) where the sample gradient vanishes.
    vec3 normalAt(const ivec3& cell, const float cv[8]) const {
        const double h = tree_.voxelSize();
        dvec3 centre = tree_.cubeOrigin + (dvec3(cell) + 0.5) * h;
        dvec3 g = sampler_.gradientWorld(centre);
        if (!(glm::length(g) > 0.0) || !std::isfinite(glm::length(g))) {
            g = dvec3(0.0);
            for (int q = 0; q < 8; ++q) {
                double s = cv[q];
                g.x += ((q & 4) ? s : -s);
                g.y += ((q & 2) ? s : -s);
                g.z += ((q & 1) ? s : -s);
            }
            g /= 4.0 * h;
        }
        double len = glm::length(g);
        if (!(len > 0.0) || !std::isfinite(len)) return vec3(0, 0, 1);
        return vec3(-g / len);
    }

    const Octree& tree_;
    float iso_;
    bool volume_, below_;
    FieldSampler sampler_;
    const detail::MinMaxPyramid& pyramid_;
    MemoryGuard* guard_;
    const std::function<bool()>& cancelled_;
    const std::string& source_;
};

void appendPool(Pool& dst, const Pool& src, OctreeNode& subRoot, int subRootLevel, int depth) {
    const std::uint32_t nodeOffset = std::uint32_t(dst.nodes.size());
    const std::uint32_t voxelOffset = std::uint32_t(dst.voxels.size());
    auto relocate = [&](OctreeNode n, int level) {
        if (n.childMask == 0) return n;  // an interior term
        n.firstChild += (level == depth - 1) ? voxelOffset : nodeOffset;
        return n;
    };
    for (std::size_t i = 0; i < src.nodes.size(); ++i) {
        dst.nodes.push_back(relocate(src.nodes[i], src.levels[i]));
        dst.levels.push_back(src.levels[i]);
    }
    dst.voxels.insert(dst.voxels.end(), src.voxels.begin(), src.voxels.end());
    subRoot = relocate(subRoot, subRootLevel);
}

/// The iso value in the precision cells are classified in; throws for a bad depth or iso.
float checkedIso(const ScalarField& field, int depth, double iso) {
    if (depth < 1 || depth > Octree::kMaxDepth) {
        std::ostringstream s;
        s << "octree depth must be in 1.." << Octree::kMaxDepth << ", got " << depth;
        throw UsageError(s.str());
    }
    if (!std::isfinite(iso)) throw UsageError("iso value must be a finite number");
    auto [vmin, vmax] = field.validRange();
    // Cells are classified in float, against float(iso): check the range in the same precision,
    // so that e.g. --iso 0.7 on a field whose largest sample is 0.7f is accepted.
    const bool isoFitsFloat = std::abs(iso) <= double(std::numeric_limits<float>::max());
    const float isoF = isoFitsFloat ? float(iso) : 0.0f;
    if (!isoFitsFloat || isoF < vmin || isoF > vmax) {
        std::ostringstream s;
        s << field.source << ": iso value " << shortest(iso) << " is outside the value range [" << shortest(vmin) << ", "
          << shortest(vmax) << "] of '" << field.name << "'";
        throw EmptyResultError(s.str());
    }
    return isoF;
}

/// An empty octree of `depth` whose cube is centred on the field's world bounding box, with
/// the box's largest extent as its side.
Octree emptyTree(const ScalarField& field, int depth, double iso) {
    Octree tree;
    tree.depth = depth;
    tree.iso = iso;
    tree.setMetadata(octree_key::kFieldName, field.name);
    tree.setMetadata(octree_key::kFieldUnits, field.units);
    Box3 b = field.worldBounds();
    dvec3 ext = b.size();
    tree.cubeSide = std::max(ext.x, std::max(ext.y, ext.z));
    if (!(tree.cubeSide > 0.0)) throw FileError(field.source + ": the grid has zero extent");
    if (!std::isfinite(tree.cubeSide)) throw FileError(field.source + ": the grid's world extent is not finite");
    tree.cubeOrigin = b.centre() - dvec3(0.5 * tree.cubeSide);
    return tree;
}

/// The build proper, at tree.depth, over `grid`; `guard` may be null (no budget).
void buildInto(Octree& tree, const ScalarField& field, const SampleGrid& grid, float isoF, int threads,
               const BuildOptions& options, MemoryGuard* guard) {
    const std::function<void(double)>& progress = options.progress;
    const Builder builder(field, grid, tree, isoF, guard, options.cancelled);
    const int depth = tree.depth;
    // Split the top levels into independent subtrees, build them in parallel, and join them in
    // a fixed order so that the result does not depend on the number of threads.
    const int split = std::min(2, depth - 1);
    const int side = 1 << split;
    const std::size_t count = std::size_t(side) * side * side;
    std::vector<Pool> pools(count);
    std::vector<OctreeNode> roots(count);
    std::vector<Octant> kinds(count, Octant::Empty);
    // The progress callback runs on the worker threads; call it one call at a time and with
    // non-decreasing fractions (ending at 1), so that callers need no locking of their own.
    std::mutex progressMutex;
    std::size_t done = 0;
    const int subSize = 1 << (depth - split);
    parallelFor(count, threads, [&](std::size_t i) {
        builder.checkCancelled();
        int x = int(i) / (side * side), y = (int(i) / side) % side, z = int(i) % side;
        kinds[i] = builder.build(split, ivec3(x, y, z) * subSize, roots[i], pools[i]);
        pools[i].shrink(guard);  // up to half of each buffer is spare capacity: join without it
        if (progress) {
            std::lock_guard<std::mutex> lock(progressMutex);
            ++done;
            progress(double(done) / double(count));
        }
    });

    // The joined octree gets buffers of its exact size: the subtrees' nodes and voxels, plus
    // one node per distinct ancestor of a non-empty subtree at levels 1..split, plus the root.
    std::size_t nodeCount = 1, voxelCount = 0;
    for (std::size_t i = 0; i < count; ++i) {
        const bool present = kinds[i] != Octant::Empty;
        nodeCount += pools[i].nodes.size() + (split > 0 && present ? 1 : 0);  // depth 1: the subtree is the root
        voxelCount += pools[i].voxels.size();
    }
    for (int level = 1; level < split; ++level) {
        std::vector<std::uint8_t> seen(std::size_t(1) << (3 * level), 0);
        for (std::size_t i = 0; i < count; ++i) {
            if (kinds[i] == Octant::Empty) continue;
            const int shift = split - level, n = 1 << level;
            const int x = (int(i) / (side * side)) >> shift, y = ((int(i) / side) % side) >> shift, z = (int(i) % side) >> shift;
            std::uint8_t& s = seen[std::size_t(x) * n * n + std::size_t(y) * n + std::size_t(z)];
            nodeCount += s ? 0 : 1;
            s = 1;
        }
    }
    Pool all;
    reserveExactly(all.nodes, nodeCount, guard);
    reserveExactly(all.levels, nodeCount, guard);
    reserveExactly(all.voxels, voxelCount, guard);
    all.nodes.push_back(OctreeNode{});  // root slot
    all.levels.push_back(0);
    // Assemble levels 0..split-1 from the subtree roots, recursively, children contiguous.
    std::function<Octant(int, ivec3, OctreeNode&)> assemble = [&](int level, ivec3 c, OctreeNode& out) -> Octant {
        if (level == split) {
            std::size_t i = std::size_t(c.x) * side * side + std::size_t(c.y) * side + std::size_t(c.z);
            if (kinds[i] != Octant::Node) return kinds[i];
            out = roots[i];
            appendPool(all, pools[i], out, split, depth);
            if (guard) guard->release(pools[i].bytes());
            pools[i] = Pool{};
            return Octant::Node;
        }
        OctreeNode kids[8];
        Octant kidKinds[8];
        for (int q = 0; q < 8; ++q) kidKinds[q] = assemble(level + 1, c * 2 + ivec3((q >> 2) & 1, (q >> 1) & 1, q & 1), kids[q]);
        return Builder::emitNode(kidKinds, kids, level + 1, out, all, nullptr);  // reserved above
    };
    OctreeNode root;
    // A root that is one term would be a cube wholly inside the solid, whose faces are caps.
    if (assemble(0, ivec3(0), root) != Octant::Node || all.voxels.empty()) {
        std::ostringstream s;
        s << field.source << ": no cell of '" << field.name << "' straddles iso value " << shortest(tree.iso) << " at depth "
          << depth;
        throw EmptyResultError(s.str());
    }
    all.nodes[0] = root;
    tree.setTopology(std::move(all.nodes), std::move(all.voxels));  // reserved exactly: no slack to shrink
}

// Memory estimates (see estimateBuildMemory in the header).
constexpr int kProbeDepth = 6;
constexpr double kEstimateMargin = 1.25;

std::uint64_t fieldBytes(const ScalarField& f) {
    std::uint64_t n = f.values.capacity() * sizeof(float) + f.valid.capacity();
    for (const auto& c : f.coords) n += c.capacity() * sizeof(double);
    return n;
}

std::uint64_t samplerBytes(const ScalarField& f, int depth) {
    return SampleGrid::bytesFor(f.dims) + FieldSampler::tableBytes(depth);
}

/// Depth at which a voxel is as small as the grid's finest mean sample spacing: deeper, the
/// trilinear field has no more detail and a surface's voxels quadruple per level.
int gridDepth(const ScalarField& f, double cubeSide) {
    double finest = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a)
        finest = std::min(finest, std::abs(f.axisPosition(a, f.dims[a] - 1) - f.axisPosition(a, 0)) / double(f.dims[a] - 1));
    if (!(finest > 0.0)) return Octree::kMaxDepth;
    return std::clamp(int(std::ceil(std::log2(cubeSide / finest))), 0, Octree::kMaxDepth);
}

std::uint64_t toBytes(double bytes) { return bytes >= 1.8e19 ? std::numeric_limits<std::uint64_t>::max() : std::uint64_t(bytes); }

/// Bytes per boundary voxel of the attributes `options` asks the build to fill after joining
/// (BuildMemoryEstimate::attributeBytes).
double attributeBytesPerVoxel(const BuildOptions& options) {
    const bool corners = options.corners && options.form == OctreeForm::Shell;
    if (!corners && !options.voxelValues) return 0.0;
    return double(sizeof(ivec3)) + (corners ? double(sizeof(std::uint64_t)) : 0.0) +
           (options.voxelValues ? double(sizeof(float)) : 0.0);
}

std::vector<BuildMemoryEstimate> estimateWithGrid(const ScalarField& field, const SampleGrid& grid, double iso, float isoF,
                                                  int maxDepth, int threads, double attributesPerVoxel) {
    // Exact counts up to the probe depth, from octrees that small (a few ms).
    const int probe = std::min(maxDepth, kProbeDepth);
    std::vector<double> voxels(std::size_t(probe) + 1, 0.0), nodes(std::size_t(probe) + 1, 0.0);
    double cubeSide = 0.0;
    for (int d = 1; d <= probe; ++d) {
        Octree t = emptyTree(field, d, iso);
        cubeSide = t.cubeSide;
        try {
            buildInto(t, field, grid, isoF, threads, {}, nullptr);
        } catch (const EmptyResultError&) {
            continue;  // nothing at this depth: the surface is finer than its voxels
        }
        voxels[std::size_t(d)] = double(t.voxels().size());
        nodes[std::size_t(d)] = double(t.nodes().size());
    }
    const double vp = std::max(1.0, voxels[std::size_t(probe)]);
    const double before = probe > 1 ? voxels[std::size_t(probe) - 1] : 0.0;
    const double rate = before > 0.0 ? std::clamp(vp / before, 4.0, 8.0) : 8.0;
    const double nodesPerVoxel = voxels[std::size_t(probe)] > 0.0 ? std::max(nodes[std::size_t(probe)] / vp, 1.0 / 3.0) : 1.0;
    const int resolved = gridDepth(field, cubeSide);

    std::vector<BuildMemoryEstimate> out(static_cast<std::size_t>(maxDepth));
    for (int d = 1; d <= maxDepth; ++d) {
        BuildMemoryEstimate& e = out[std::size_t(d) - 1];
        e.depth = d;
        e.fieldBytes = fieldBytes(field);
        e.samplerBytes = samplerBytes(field, d);
        double v = 0.0, n = 0.0;
        if (d <= probe) {
            v = voxels[std::size_t(d)];
            n = nodes[std::size_t(d)];
        } else {
            const int rough = std::clamp(resolved - probe, 0, d - probe);  // levels still resolving the grid's detail
            v = vp * std::pow(rate, rough) * std::pow(4.0, d - probe - rough) * kEstimateMargin;
            n = v * nodesPerVoxel;
        }
        e.boundaryVoxels = v;
        // Subtree buffers (shrunk) and the joined octree exist together while joining.
        e.octreeBytes = toBytes(2.0 * (v * double(sizeof(Voxel)) + n * double(sizeof(OctreeNode) + 1)));
        e.attributeBytes = toBytes(v * attributesPerVoxel);
    }
    return out;
}

std::string aboutCount(double n) {
    char buf[48];
    if (n >= 1e9) std::snprintf(buf, sizeof buf, "%.3g billion", n / 1e9);
    else if (n >= 1e6) std::snprintf(buf, sizeof buf, "%.3g million", n / 1e6);
    else std::snprintf(buf, sizeof buf, "%.0f", n);
    return buf;
}

/// Refuses a build whose estimate exceeds the budget, naming the largest depth that fits.
void refuseOverBudget(const ScalarField& field, const std::vector<BuildMemoryEstimate>& est, std::uint64_t budget) {
    const BuildMemoryEstimate& e = est.back();
    if (e.total() <= budget) return;
    std::ostringstream s;
    if (est.size() == 1 && e.octreeBytes == 0) {  // checked before the sampler is made
        s << field.source << ": building the octree of '" << field.name << "' needs more than the memory budget of "
          << formatBytes(budget) << " (`max_memory`) at any depth: the field and the sampler alone need about "
          << formatBytes(e.total());
        throw LimitError(s.str());
    }
    s << field.source << ": the octree of '" << field.name << "' at depth " << e.depth << " needs about "
      << formatBytes(e.total()) << " (field " << formatBytes(e.fieldBytes) << ", sampler " << formatBytes(e.samplerBytes)
      << ", octree " << formatBytes(e.octreeBytes);
    if (e.attributeBytes) s << ", per-voxel attributes " << formatBytes(e.attributeBytes);
    s << " for about " << aboutCount(e.boundaryVoxels)
      << " boundary voxels), more than the memory budget of " << formatBytes(budget) << " (`max_memory`); ";
    int fits = 0;
    for (const auto& x : est)
        if (x.total() <= budget) fits = x.depth;
    if (fits > 0) s << "the largest depth that fits is " << fits << " (about " << formatBytes(est[std::size_t(fits) - 1].total()) << ")";
    else s << "no depth fits: the field and the sampler alone need " << formatBytes(est.front().fieldBytes + est.front().samplerBytes);
    throw LimitError(s.str());
}

/// BuildOptions::voxelValues.
void sampleVoxelValues(Octree& tree, const ScalarField& field, const SampleGrid& grid, float isoF, int threads) {
    std::vector<ivec3> cells(tree.voxels().size());
    tree.forEachVoxel([&](const ivec3& c, std::uint32_t i) { cells[i] = c; });
    const FieldSampler sampler(field, grid.samples, tree.cubeOrigin, tree.voxelSize(), tree.depth);
    const double h = tree.voxelSize();
    auto valueAt = [&](const dvec3& p) {
        AxisSample s[3];
        sampler.locateWorld(p, s);
        return sampler.trilinear(s[0], s[1], s[2]);
    };
    std::vector<float> values(cells.size(), isoF);
    constexpr std::size_t kChunk = 4096;
    parallelFor((cells.size() + kChunk - 1) / kChunk, threads, [&](std::size_t chunk) {
        const std::size_t end = std::min(cells.size(), (chunk + 1) * kChunk);
        for (std::size_t i = chunk * kChunk; i < end; ++i) {
            const dvec3 centre = tree.cubeOrigin + (dvec3(cells[i]) + 0.5) * h;
            // The normal points towards lower values: inside (>= iso) is against it.
            const dvec3 inside = centre - dvec3(decodeNormal(tree.voxels()[i].normal)) * h;
            float v = valueAt(inside);
            if (std::isnan(v)) v = valueAt(centre);
            if (!std::isnan(v)) values[i] = v;
        }
    });
    tree.setVoxelValues(std::move(values));
}

/// BuildOptions::corners: the corners each voxel was classified by (FieldSampler::corner).
void sampleCorners(Octree& tree, const ScalarField& field, const SampleGrid& grid, float isoF, int threads) {
    std::vector<ivec3> cells(tree.voxels().size());
    tree.forEachVoxel([&](const ivec3& c, std::uint32_t i) { cells[i] = c; });
    const FieldSampler sampler(field, grid.samples, tree.cubeOrigin, tree.voxelSize(), tree.depth);
    std::vector<std::uint64_t> codes(cells.size(), 0);
    constexpr std::size_t kChunk = 4096;
    parallelFor((cells.size() + kChunk - 1) / kChunk, threads, [&](std::size_t chunk) {
        const std::size_t end = std::min(cells.size(), (chunk + 1) * kChunk);
        for (std::size_t i = chunk * kChunk; i < end; ++i) {
            float v[8];
            for (int q = 0; q < 8; ++q) v[q] = sampler.corner(cells[i] + ivec3((q >> 2) & 1, (q >> 1) & 1, q & 1));
            codes[i] = encodeCorners(v, isoF);
        }
    });
    tree.setCorners(std::move(codes));
}

}  // namespace

std::vector<BuildMemoryEstimate> estimateBuildMemory(const ScalarField& field, double iso, int maxDepth, int threads) {
    const float isoF = checkedIso(field, maxDepth, iso);
    emptyTree(field, maxDepth, iso);  // checks the extent
    const SampleGrid grid(field);
    return estimateWithGrid(field, grid, iso, isoF, maxDepth, threads, 0.0);
}

std::vector<BuildMemoryEstimate> estimateBuildMemory(const ScalarField& field, const BuildOptions& options) {
    const float isoF = checkedIso(field, options.depth, options.iso);
    emptyTree(field, options.depth, options.iso);  // checks the extent
    const SampleGrid grid(field);
    return estimateWithGrid(field, grid, options.iso, isoF, options.depth, options.threads, attributeBytesPerVoxel(options));
}

Octree buildShellOctree(const ScalarField& field, const BuildOptions& options, BuildReport* report) {
    BuildOptions shell = options;
    shell.form = OctreeForm::Shell;
    return buildOctree(field, shell, report);
}

Octree buildOctree(const ScalarField& field, const BuildOptions& options, BuildReport* report) {
    if (field.planar)
        throw InputError(field.source + ": '" + field.name + "' is a 2-D field (a map, one level): a surface needs a 3-D field; "
                         "draw a map with slice");
    Timer timer;
    const float isoF = checkedIso(field, options.depth, options.iso);
    Octree tree = emptyTree(field, options.depth, options.iso);
    tree.form = options.form;
    tree.insideBelow = options.form == OctreeForm::Volume && options.insideBelow;
    const std::uint64_t budget = options.memoryBudget;
    if (budget) {
        // Before copying the samples: is there room for the copy and its pyramid at all?
        BuildMemoryEstimate fixed;
        fixed.depth = options.depth;
        fixed.fieldBytes = fieldBytes(field);
        fixed.samplerBytes = samplerBytes(field, 1);
        if (fixed.total() > budget) refuseOverBudget(field, {fixed}, budget);
    }
    const SampleGrid grid(field);
    std::optional<MemoryGuard> guard;
    if (budget) {
        auto est = estimateWithGrid(field, grid, options.iso, isoF, options.depth, options.threads, attributeBytesPerVoxel(options));
        refuseOverBudget(field, est, budget);
        guard.emplace(field, options.depth, budget, est.back().fieldBytes + est.back().samplerBytes, est.back().total());
    }
    buildInto(tree, field, grid, isoF, options.threads, options, guard ? &*guard : nullptr);
    if (guard) guard->allocate(toBytes(double(tree.voxels().size()) * attributeBytesPerVoxel(options)));
    if (options.voxelValues) sampleVoxelValues(tree, field, grid, isoF, options.threads);
    if (options.corners && tree.form == OctreeForm::Shell) sampleCorners(tree, field, grid, isoF, options.threads);
    if (report) {
        report->buildMs = timer.ms();
        report->boundaryVoxels = tree.form == OctreeForm::Volume ? countVoxels(tree).boundary : tree.voxels().size();
        report->nodes = tree.nodes().size();
    }
    return tree;
}

void fillVoxelValues(Octree& tree, const ScalarField& field, int threads) {
    field.validate();
    const SampleGrid grid(field);
    sampleVoxelValues(tree, field, grid, float(tree.iso), threads);
}

void fillCorners(Octree& tree, const ScalarField& field, int threads) {
    if (tree.form != OctreeForm::Shell) return;
    field.validate();
    const SampleGrid grid(field);
    sampleCorners(tree, field, grid, float(tree.iso), threads);
}

std::vector<float> sampleAtVoxels(const Octree& tree, const ScalarField& field, int threads) {
    field.validate();
    std::vector<std::pair<ivec3, std::uint32_t>> cells;
    cells.reserve(tree.voxels().size());
    tree.forEachVoxel([&](const ivec3& c, std::uint32_t v) { cells.push_back({c, v}); });
    const std::vector<float> samples = SampleGrid::maskedSamples(field);
    const double h = tree.voxelSize();
    const FieldSampler sampler(field, samples, tree.cubeOrigin, h, 0);
    std::vector<float> out(tree.voxels().size(), kNaN);
    constexpr std::size_t kChunk = 4096;
    parallelFor((cells.size() + kChunk - 1) / kChunk, threads, [&](std::size_t chunk) {
        const std::size_t end = std::min(cells.size(), (chunk + 1) * kChunk);
        for (std::size_t i = chunk * kChunk; i < end; ++i)
            out[cells[i].second] = sampler.atWorld(tree.cubeOrigin + (dvec3(cells[i].first) + 0.5) * h);
    });
    return out;
}

}  // namespace octrace
