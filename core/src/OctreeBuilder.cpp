#include "octrace/build/OctreeBuilder.h"

#include "MinMaxPyramid.h"
#include "octrace/util/Error.h"
#include "octrace/util/Log.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <limits>
#include <mutex>
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
    FieldSampler(const ScalarField& f, const dvec3& cubeOrigin, double h, int depth)
        : f_(f), cubeOrigin_(cubeOrigin), h_(h) {
        samples_.resize(f.values.size());
        for (std::size_t i = 0; i < f.values.size(); ++i)
            samples_[i] = (f.isValid(i) && std::isfinite(f.values[i])) ? f.values[i] : kNaN;
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

    const std::vector<float>& samples() const { return samples_; }
    bool separable() const { return separable_; }

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
    std::vector<float> samples_;
    bool separable_ = false;
    dmat3 inverse_{1.0};
    std::vector<AxisSample> table_[3];
};

/// Nodes and voxels of one subtree, with local indices (levels kept to relocate them).
struct Pool {
    std::vector<OctreeNode> nodes;
    std::vector<std::uint8_t> levels;
    std::vector<Voxel> voxels;
};

class Builder {
public:
    Builder(const ScalarField& f, const Octree& tree, float iso)
        : tree_(tree), iso_(iso), sampler_(f, tree.cubeOrigin, tree.voxelSize(), tree.depth),
          pyramid_(sampler_.samples().data(), f.dims) {}

    /// Builds the node at `level` whose minimum cell is c0; false when it holds no boundary voxel.
    bool build(int level, const ivec3& c0, OctreeNode& out, Pool& pool) const {
        const int depth = tree_.depth;
        const int size = 1 << (depth - level);
        ivec3 lo, hi;
        if (!sampler_.sampleRange(c0, size, lo, hi)) return false;
        float mn, mx;
        pyramid_.query(lo, hi, mn, mx);
        if (!(mn <= mx) || mx < iso_ || mn >= iso_) return false;
        if (level == depth - 1) return buildLeafParent(c0, out, pool);
        OctreeNode kids[8];
        unsigned mask = 0;
        const int half = size / 2;
        for (int c = 0; c < 8; ++c) {
            ivec3 cc = c0 + half * ivec3((c >> 2) & 1, (c >> 1) & 1, c & 1);
            if (build(level + 1, cc, kids[c], pool)) mask |= 1u << c;
        }
        if (!mask) return false;
        out = OctreeNode{};
        out.firstChild = std::uint32_t(pool.nodes.size());
        out.childMask = std::uint8_t(mask);
        for (int c = 0; c < 8; ++c)
            if (mask & (1u << c)) {
                pool.nodes.push_back(kids[c]);
                pool.levels.push_back(std::uint8_t(level + 1));
            }
        return true;
    }

private:
    bool buildLeafParent(const ivec3& c0, OctreeNode& out, Pool& pool) const {
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
        if (!mask) return false;
        out = OctreeNode{};
        out.firstChild = std::uint32_t(pool.voxels.size());
        out.childMask = std::uint8_t(mask);
        for (int c = 0; c < 8; ++c)
            if (mask & (1u << c)) pool.voxels.push_back(vox[c]);
        return true;
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
    FieldSampler sampler_;
    detail::MinMaxPyramid pyramid_;
};

void appendPool(Pool& dst, const Pool& src, OctreeNode& subRoot, int subRootLevel, int depth) {
    const std::uint32_t nodeOffset = std::uint32_t(dst.nodes.size());
    const std::uint32_t voxelOffset = std::uint32_t(dst.voxels.size());
    auto relocate = [&](OctreeNode n, int level) {
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

}  // namespace

Octree buildShellOctree(const ScalarField& field, const BuildOptions& options, BuildReport* report) {
    Timer timer;
    if (options.depth < 1 || options.depth > Octree::kMaxDepth) {
        std::ostringstream s;
        s << "octree depth must be in 1.." << Octree::kMaxDepth << ", got " << options.depth;
        throw UsageError(s.str());
    }
    if (!std::isfinite(options.iso)) throw UsageError("iso value must be a finite number");
    auto [vmin, vmax] = field.validRange();
    // Cells are classified in float, against float(iso): check the range in the same precision,
    // so that e.g. --iso 0.7 on a field whose largest sample is 0.7f is accepted.
    const bool isoFitsFloat = std::abs(options.iso) <= double(std::numeric_limits<float>::max());
    const float isoF = isoFitsFloat ? float(options.iso) : 0.0f;
    if (!isoFitsFloat || isoF < vmin || isoF > vmax) {
        std::ostringstream s;
        s << field.source << ": iso value " << shortest(options.iso) << " is outside the value range [" << shortest(vmin)
          << ", " << shortest(vmax) << "] of '" << field.name << "'";
        throw EmptyResultError(s.str());
    }

    Octree tree;
    tree.depth = options.depth;
    tree.iso = options.iso;
    tree.fieldName = field.name;
    tree.fieldUnits = field.units;
    Box3 b = field.worldBounds();
    dvec3 ext = b.size();
    tree.cubeSide = std::max(ext.x, std::max(ext.y, ext.z));
    if (!(tree.cubeSide > 0.0)) throw FileError(field.source + ": the grid has zero extent");
    tree.cubeOrigin = b.centre() - dvec3(0.5 * tree.cubeSide);

    const Builder builder(field, tree, isoF);
    const int depth = tree.depth;
    // Split the top levels into independent subtrees, build them in parallel, and join them in
    // a fixed order so that the result does not depend on the number of threads.
    const int split = std::min(2, depth - 1);
    const int side = 1 << split;
    const std::size_t count = std::size_t(side) * side * side;
    std::vector<Pool> pools(count);
    std::vector<OctreeNode> roots(count);
    std::vector<std::uint8_t> present(count, 0);
    // The progress callback runs on the worker threads; call it one call at a time and with
    // non-decreasing fractions (ending at 1), so that callers need no locking of their own.
    std::mutex progressMutex;
    std::size_t done = 0;
    const int subSize = 1 << (depth - split);
    parallelFor(count, options.threads, [&](std::size_t i) {
        int x = int(i) / (side * side), y = (int(i) / side) % side, z = int(i) % side;
        present[i] = builder.build(split, ivec3(x, y, z) * subSize, roots[i], pools[i]) ? 1 : 0;
        if (options.progress) {
            std::lock_guard<std::mutex> lock(progressMutex);
            ++done;
            options.progress(double(done) / double(count));
        }
    });

    Pool all;
    all.nodes.push_back(OctreeNode{});  // root slot
    all.levels.push_back(0);
    // Assemble levels 0..split-1 from the subtree roots, recursively, children contiguous.
    std::function<bool(int, ivec3, OctreeNode&)> assemble = [&](int level, ivec3 c, OctreeNode& out) -> bool {
        if (level == split) {
            std::size_t i = std::size_t(c.x) * side * side + std::size_t(c.y) * side + std::size_t(c.z);
            if (!present[i]) return false;
            out = roots[i];
            appendPool(all, pools[i], out, split, depth);
            pools[i] = Pool{};
            return true;
        }
        OctreeNode kids[8];
        unsigned mask = 0;
        for (int q = 0; q < 8; ++q)
            if (assemble(level + 1, c * 2 + ivec3((q >> 2) & 1, (q >> 1) & 1, q & 1), kids[q])) mask |= 1u << q;
        if (!mask) return false;
        out = OctreeNode{};
        out.firstChild = std::uint32_t(all.nodes.size());
        out.childMask = std::uint8_t(mask);
        for (int q = 0; q < 8; ++q)
            if (mask & (1u << q)) {
                all.nodes.push_back(kids[q]);
                all.levels.push_back(std::uint8_t(level + 1));
            }
        return true;
    };
    OctreeNode root;
    if (!assemble(0, ivec3(0), root) || all.voxels.empty()) {
        std::ostringstream s;
        s << field.source << ": no cell of '" << field.name << "' straddles iso value " << shortest(options.iso) << " at depth "
          << depth;
        throw EmptyResultError(s.str());
    }
    all.nodes[0] = root;
    tree.nodes = std::move(all.nodes);
    tree.voxels = std::move(all.voxels);
    tree.nodes.shrink_to_fit();
    tree.voxels.shrink_to_fit();
    if (report) {
        report->buildMs = timer.ms();
        report->boundaryVoxels = tree.voxels.size();
        report->nodes = tree.nodes.size();
    }
    return tree;
}

}  // namespace octrace
