#include "octrace/build/CityVoxelizer.h"

#include "octrace/util/Error.h"
#include "octrace/util/Parallel.h"
#include "octrace/util/Timer.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>

namespace octrace {
namespace {

/// A triangle in cell space of the finest level (voxel (i,j,k) is [i,i+1) x ...).
struct CellTriangle {
    dvec3 p[3];
    dvec3 normal;  // unit, world and cell space alike (uniform scale)
};

/// Boxes are tested enlarged by this much (cell units) on every side. With the same margin at
/// every level the enlarged children cover their enlarged parent, so a triangle that meets a
/// node meets one of its children even where rounding decides a touching case differently.
constexpr double kMargin = 1e-6;

/// Akenine-Moeller's separating-axis test of a triangle against an axis-aligned cube (closed)
/// of half side `half`, enlarged by kMargin.
bool overlaps(const CellTriangle& t, const dvec3& centre, double half) {
    half += kMargin;
    const dvec3 v0 = t.p[0] - centre, v1 = t.p[1] - centre, v2 = t.p[2] - centre;
    // The box's axes.
    for (int a = 0; a < 3; ++a) {
        const double lo = std::min({v0[a], v1[a], v2[a]}), hi = std::max({v0[a], v1[a], v2[a]});
        if (lo > half || hi < -half) return false;
    }
    // The triangle's plane.
    const double d = glm::dot(t.normal, v0);
    const double r = half * (std::abs(t.normal.x) + std::abs(t.normal.y) + std::abs(t.normal.z));
    if (std::abs(d) > r) return false;
    // The nine cross products of edges and box axes.
    const dvec3 e[3] = {v1 - v0, v2 - v1, v0 - v2};
    const dvec3 v[3] = {v0, v1, v2};
    for (const dvec3& edge : e) {
        for (int a = 0; a < 3; ++a) {
            dvec3 axis(0.0);
            axis[(a + 1) % 3] = -edge[(a + 2) % 3];
            axis[(a + 2) % 3] = edge[(a + 1) % 3];
            double lo = std::numeric_limits<double>::infinity(), hi = -lo;
            for (const dvec3& p : v) {
                const double x = glm::dot(axis, p);
                lo = std::min(lo, x);
                hi = std::max(hi, x);
            }
            const double rad = half * (std::abs(axis.x) + std::abs(axis.y) + std::abs(axis.z));
            if (lo > rad || hi < -rad) return false;
        }
    }
    return true;
}

struct Pool {
    std::vector<OctreeNode> nodes;
    std::vector<std::uint8_t> levels;
    std::vector<Voxel> voxels;
    std::vector<std::uint32_t> colours;
};

/// Where the top pass stopped: a subtree root to build on its own.
struct Subtree {
    std::uint32_t slot = 0;  // its node's index in the joined pool
    ivec3 cell{0};
    std::vector<std::uint32_t> tris;
    Pool pool;
    OctreeNode root;
};

class Voxelizer {
public:
    /// `stop[t]`: the level down to which triangle t is voxelized; a node of that level or
    /// deeper whose triangles all stop there (or above) becomes a coarse leaf.
    Voxelizer(const CityModel& model, const std::vector<CellTriangle>& tris, const std::vector<std::uint8_t>& stop,
              const Octree& tree)
        : model_(model), tris_(tris), stop_(stop), tree_(tree),
          scratch_(std::size_t(tree.depth) + 1) {}

    /// Builds the node at `level`, `cell` (crossed by `tris`) into `pool`; its own record goes
    /// to `out`. With `subtrees`, stops at level `stop` and records the nodes there instead.
    void build(int level, const ivec3& cell, const std::vector<std::uint32_t>& tris, Pool& pool, OctreeNode& out,
               int stop = -1, std::vector<Subtree>* subtrees = nullptr) {
        auto& kids = scratch_[std::size_t(level)];
        const double half = 0.5 * std::ldexp(1.0, tree_.depth - level - 1);
        unsigned mask = 0;
        for (int c = 0; c < 8; ++c) {
            kids[std::size_t(c)].clear();
            const ivec3 cc = cell * 2 + ivec3((c >> 2) & 1, (c >> 1) & 1, c & 1);
            const dvec3 centre = (dvec3(cc) + 0.5) * (2.0 * half);
            for (std::uint32_t t : tris)
                if (overlaps(tris_[t], centre, half)) kids[std::size_t(c)].push_back(t);
            if (!kids[std::size_t(c)].empty()) mask |= 1u << c;
        }
        out = OctreeNode{};
        out.childMask = std::uint8_t(mask);
        if (level + 1 == tree_.depth) {
            out.firstChild = std::uint32_t(pool.voxels.size());
            for (int c = 0; c < 8; ++c) {
                if (!(mask & (1u << c))) continue;
                const ivec3 cc = cell * 2 + ivec3((c >> 2) & 1, (c >> 1) & 1, c & 1);
                leaf(cc, tree_.depth, kids[std::size_t(c)], pool);
            }
            return;
        }
        out.firstChild = std::uint32_t(pool.nodes.size());
        const int count = std::popcount(mask);
        pool.nodes.resize(pool.nodes.size() + std::size_t(count));
        pool.levels.resize(pool.nodes.size(), std::uint8_t(level + 1));
        std::uint32_t slot = out.firstChild;
        // The recursion writes only the scratch lists of deeper levels: this level's stay.
        for (int c = 0; c < 8; ++c) {
            if (!(mask & (1u << c))) continue;
            const ivec3 cc = cell * 2 + ivec3((c >> 2) & 1, (c >> 1) & 1, c & 1);
            const auto& kt = kids[std::size_t(c)];
            if (std::all_of(kt.begin(), kt.end(), [&](std::uint32_t t) { return stop_[t] <= level + 1; })) {
                // Only triangles that stop here (terrain, shallower sources): a coarse leaf.
                out.termMask |= std::uint8_t(1u << c);
                pool.nodes[slot] = OctreeNode{std::uint32_t(pool.voxels.size()), 0, 0, 0};
                leaf(cc, level + 1, kt, pool);
            } else if (subtrees && level + 1 == stop) {
                Subtree s;
                s.slot = slot;
                s.cell = cc;
                s.tris = kids[std::size_t(c)];
                subtrees->push_back(std::move(s));
            } else {
                OctreeNode child;
                build(level + 1, cc, kids[std::size_t(c)], pool, child, stop, subtrees);
                pool.nodes[slot] = child;
            }
            ++slot;
        }
    }

private:
    /// The voxel (normal, colour) of the leaf at `level`, `cell` (a voxel at level depth).
    void leaf(const ivec3& cell, int level, const std::vector<std::uint32_t>& tris, Pool& pool) const {
        const dvec3 centre = (dvec3(cell) + 0.5) * std::ldexp(1.0, tree_.depth - level);
        std::uint32_t best = tris.front();
        double bestDistance = std::numeric_limits<double>::infinity();
        for (std::uint32_t t : tris) {
            const double d = std::abs(glm::dot(tris_[t].normal, centre - tris_[t].p[0]));
            if (d < bestDistance) {
                bestDistance = d;
                best = t;
            }
        }
        Voxel v;
        v.normal = encodeNormal(vec3(tris_[best].normal));
        pool.voxels.push_back(v);
        const CityObject& object = model_.objects[model_.triangles[best].object];
        std::uint32_t colour = object.colour;
        if (object.role == CityRole::Terrain && !model_.texture.empty()) {
            const dvec3 world = tree_.cubeOrigin + centre * tree_.voxelSize();
            const std::uint32_t t = model_.texture.at(world.x, world.y);
            if (t >> 24) colour = t;
        }
        pool.colours.push_back(colour);
    }

    const CityModel& model_;
    const std::vector<CellTriangle>& tris_;
    const std::vector<std::uint8_t>& stop_;
    const Octree& tree_;
    std::vector<std::array<std::vector<std::uint32_t>, 8>> scratch_;
};

void append(Pool& dst, Pool& src, OctreeNode& root, int rootLevel, int depth) {
    const std::uint32_t nodeOffset = std::uint32_t(dst.nodes.size()), voxelOffset = std::uint32_t(dst.voxels.size());
    // Nodes above the voxels index nodes, except coarse leaves (no children): they index voxels.
    auto offset = [&](int level, const OctreeNode& n) { return level == depth - 1 || n.childMask == 0 ? voxelOffset : nodeOffset; };
    for (std::size_t i = 0; i < src.nodes.size(); ++i) {
        OctreeNode n = src.nodes[i];
        n.firstChild += offset(src.levels[i], n);
        dst.nodes.push_back(n);
    }
    dst.levels.insert(dst.levels.end(), src.levels.begin(), src.levels.end());
    dst.voxels.insert(dst.voxels.end(), src.voxels.begin(), src.voxels.end());
    dst.colours.insert(dst.colours.end(), src.colours.begin(), src.colours.end());
    root.firstChild += offset(rootLevel, root);
    src = Pool{};
}

}  // namespace

Octree voxelizeCity(const CityModel& model, const CityBuildOptions& options, BuildReport* report) {
    Timer timer;
    if (options.depth < 1 || options.depth > Octree::kMaxDepth)
        throw UsageError("octree depth must be in 1.." + std::to_string(Octree::kMaxDepth) + ", got " + std::to_string(options.depth));
    const Box3 b = model.bounds();
    Octree tree;
    tree.depth = options.depth;
    tree.setMetadata(octree_key::kCrs, model.crs);
    tree.setMetadata(octree_key::kFieldName, "city");
    tree.setMetadata(octree_key::kSource, model.source);
    const dvec3 ext = b.size();
    tree.cubeSide = std::max({ext.x, ext.y, ext.z});
    if (!(tree.cubeSide > 0.0) || !std::isfinite(tree.cubeSide))
        throw EmptyResultError(model.source + ": the city model has no triangles with extent");
    tree.cubeOrigin = b.centre() - dvec3(0.5 * tree.cubeSide);

    // Triangles in cell space; those without area are left out.
    const double scale = 1.0 / tree.voxelSize();
    std::vector<CellTriangle> tris(model.triangles.size());
    std::vector<std::uint32_t> all;
    all.reserve(model.triangles.size());
    for (std::size_t i = 0; i < model.triangles.size(); ++i) {
        CellTriangle& t = tris[i];
        for (int k = 0; k < 3; ++k) t.p[k] = (model.vertices[model.triangles[i].v[std::size_t(k)]] - tree.cubeOrigin) * scale;
        const dvec3 n = glm::cross(t.p[1] - t.p[0], t.p[2] - t.p[0]);
        const double len = glm::length(n);
        if (!(len > 0.0) || !std::isfinite(len)) continue;
        t.normal = n / len;
        all.push_back(std::uint32_t(i));
    }
    if (all.empty()) throw EmptyResultError(model.source + ": the city model has no triangle with area");
    if (options.terrainDepth < 0 || options.terrainDepth > Octree::kMaxDepth)
        throw UsageError("terrain depth must be in 1.." + std::to_string(Octree::kMaxDepth) + ", got " + std::to_string(options.terrainDepth));
    const int terrainDepth = options.terrainDepth > 0 && options.terrainDepth < options.depth ? options.terrainDepth : options.depth;
    std::vector<std::uint8_t> stop(model.triangles.size());
    for (std::size_t i = 0; i < model.triangles.size(); ++i) {
        const CityObject& o = model.objects[model.triangles[i].object];
        if (o.depth > options.depth)
            throw UsageError("object '" + o.id + "' asks for depth " + std::to_string(o.depth) + ", deeper than the octree's " +
                             std::to_string(options.depth) + " (give a larger `depth`)");
        const int d = o.depth > 0 ? o.depth : o.role == CityRole::Terrain ? terrainDepth : options.depth;
        stop[i] = std::uint8_t(std::clamp(d, 1, options.depth));
    }

    // The top levels serially down to `split`, the subtrees below in parallel, joined in a
    // fixed order so that the result does not depend on the number of threads.
    const int split = options.depth >= 5 ? 3 : 0;
    Pool joined;
    joined.nodes.resize(1);
    joined.levels.resize(1, 0);
    OctreeNode root;
    if (split == 0) {
        Voxelizer(model, tris, stop, tree).build(0, ivec3(0), all, joined, root);
    } else {
        std::vector<Subtree> subs;
        Voxelizer(model, tris, stop, tree).build(0, ivec3(0), all, joined, root, split, &subs);
        parallelFor(subs.size(), options.threads, [&](std::size_t i) {
            Voxelizer v(model, tris, stop, tree);
            v.build(split, subs[i].cell, subs[i].tris, subs[i].pool, subs[i].root);
            subs[i].tris = {};
        });
        for (Subtree& s : subs) {
            append(joined, s.pool, s.root, split, options.depth);
            joined.nodes[s.slot] = s.root;
        }
    }
    joined.nodes[0] = root;
    joined.nodes.shrink_to_fit();
    joined.voxels.shrink_to_fit();
    joined.colours.shrink_to_fit();
    tree.setTopology(std::move(joined.nodes), std::move(joined.voxels));
    tree.setColours(std::move(joined.colours));  // one per voxel: every leaf appends its colour
    if (report) *report = BuildReport{timer.ms(), tree.voxels().size(), tree.nodes().size()};
    return tree;
}

}  // namespace octrace
