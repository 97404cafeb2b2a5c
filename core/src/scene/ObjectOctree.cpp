#include "octrace/scene/ObjectOctree.h"

#include "octrace/util/Error.h"
#include "octrace/util/Memory.h"

#include <algorithm>
#include <cmath>

namespace octrace {

namespace {
constexpr std::uint32_t kNone = 0xFFFFFFFFu;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr std::uint64_t kMaxListCopies = 4;

bool overlaps(const Box3& node, const Sphere& s) {
    for (int a = 0; a < 3; ++a)
        if (s.centre[a] + s.radius < node.lo[a] || s.centre[a] - s.radius > node.hi[a]) return false;
    return true;
}
/// Spheres that overlap too much to be separated: splitting the node would copy its list into
/// the children more than kMaxListCopies times over. Such a node stays a leaf; without this, a
/// few coincident spheres (a file listing an atom twice) would be split down to maxDepth over
/// their whole shared box: millions of nodes, each listing all of them.
bool inseparable(const Box3& node, const std::vector<std::uint32_t>& list, const std::vector<Sphere>& spheres) {
    const dvec3 mid = node.centre();
    std::uint64_t copies = 0;
    for (std::uint32_t s : list) {
        const Sphere& sp = spheres[s];
        std::uint64_t children = 1;
        for (int a = 0; a < 3; ++a)
            children *= std::uint64_t(sp.centre[a] - sp.radius <= mid[a]) + std::uint64_t(sp.centre[a] + sp.radius >= mid[a]);
        copies += children;
    }
    return copies > kMaxListCopies * list.size();
}
}  // namespace

void slabInterval(const Box3& b, const dvec3& o, const dvec3& inv, const dvec3& d, double& t0, double& t1) {
    t0 = -kInf;
    t1 = kInf;
    for (int a = 0; a < 3; ++a) {
        if (d[a] == 0.0) {
            if (o[a] < b.lo[a] || o[a] > b.hi[a]) { t0 = kInf; t1 = -kInf; return; }
            continue;
        }
        double ta = (b.lo[a] - o[a]) * inv[a], tb = (b.hi[a] - o[a]) * inv[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
}

ObjectOctree ObjectOctree::build(SphereSet scene, const ObjectOctreeOptions& opt) {
    if (opt.leafObjects < 1) throw UsageError("`leaf_objects` must be at least 1, got " + std::to_string(opt.leafObjects));
    if (opt.maxDepth < 0 || opt.maxDepth > kMaxDepth)
        throw UsageError("object octree depth must be 0.." + std::to_string(kMaxDepth) + ", got " + std::to_string(opt.maxDepth));
    scene.validate();
    ObjectOctree t;
    const Box3 b = scene.bounds();
    const double side = std::max({b.size().x, b.size().y, b.size().z});
    // A little margin so that no sphere touches the cube's faces.
    t.cubeSide = side * (1.0 + 1e-6) + 1e-300;
    t.cubeOrigin = b.centre() - dvec3(0.5 * t.cubeSide);
    t.leafObjects = opt.leafObjects;
    t.scene = std::move(scene);
    const auto& spheres = t.scene.spheres;

    t.nodes.push_back(ObjectNode{});
    // Work list: node and its candidate spheres (the parent's list filtered by the box).
    struct Item { std::uint32_t node; std::vector<std::uint32_t> list; };
    std::vector<Item> stack;
    {
        std::vector<std::uint32_t> all(spheres.size());
        for (std::uint32_t i = 0; i < all.size(); ++i) all[i] = i;
        stack.push_back({0, std::move(all)});
    }
    std::uint64_t listBytes = 0;
    while (!stack.empty()) {
        Item it = std::move(stack.back());
        stack.pop_back();
        const int level = t.nodes[it.node].level;
        if (int(it.list.size()) <= opt.leafObjects || level >= opt.maxDepth || inseparable(t.nodeBox(it.node), it.list, spheres)) {
            t.nodes[it.node].firstObject = std::uint32_t(t.objects.size());
            t.nodes[it.node].objectCount = std::uint32_t(it.list.size());
            t.objects.insert(t.objects.end(), it.list.begin(), it.list.end());
            t.depth = std::max(t.depth, level);
            continue;
        }
        const std::uint32_t first = std::uint32_t(t.nodes.size());
        t.nodes[it.node].firstChild = first;
        const std::uint32_t half = 1u << (kMaxDepth - level - 1);
        for (std::uint32_t c = 0; c < 8; ++c) {
            ObjectNode ch;
            ch.parent = it.node;
            ch.level = std::uint8_t(level + 1);
            ch.octant = std::uint8_t(c);
            const ObjectNode& p = t.nodes[it.node];
            ch.cell[0] = p.cell[0] + ((c >> 2) & 1) * half;
            ch.cell[1] = p.cell[1] + ((c >> 1) & 1) * half;
            ch.cell[2] = p.cell[2] + (c & 1) * half;
            t.nodes.push_back(ch);
        }
        for (std::uint32_t c = 8; c-- > 0;) {
            const Box3 box = t.nodeBox(first + c);
            std::vector<std::uint32_t> sub;
            for (std::uint32_t s : it.list)
                if (overlaps(box, spheres[s])) sub.push_back(s);
            listBytes += sub.size() * 4;
            stack.push_back({first + c, std::move(sub)});
        }
        if (opt.memoryBudget)
            checkMemoryBudget(t.scene.source + ": object octree (" + std::to_string(t.nodes.size()) + " nodes)",
                              t.bytes() + listBytes, opt.memoryBudget);
    }
    t.nodes.shrink_to_fit();
    t.objects.shrink_to_fit();
    return t;
}

std::size_t ObjectOctree::leaves() const {
    return std::size_t(std::count_if(nodes.begin(), nodes.end(), [](const ObjectNode& n) { return n.leaf(); }));
}
std::size_t ObjectOctree::occupiedLeaves() const {
    return std::size_t(std::count_if(nodes.begin(), nodes.end(), [](const ObjectNode& n) { return n.leaf() && n.objectCount; }));
}

std::uint32_t ObjectOctree::descendToLeaf(std::uint32_t n, const dvec3& p, const dvec3& dir) const {
    const double step = cubeSide / double(1u << kMaxDepth);
    while (!nodes[n].leaf()) {
        const ObjectNode& nd = nodes[n];
        const std::uint32_t half = 1u << (kMaxDepth - nd.level - 1);
        unsigned c = 0;
        for (int a = 0; a < 3; ++a) {
            const double mid = cubeOrigin[a] + double(nd.cell[a] + half) * step;
            if (p[a] > mid || (p[a] == mid && dir[a] > 0.0)) c |= 4u >> a;
        }
        n = nd.firstChild + c;
    }
    return n;
}

std::uint32_t ObjectOctree::faceNeighbour(std::uint32_t n, int axis, bool positive, std::uint64_t* steps) const {
    const unsigned bit = 4u >> axis;
    std::uint8_t path[kMaxDepth + 1];
    int k = 0;
    std::uint32_t m = n;
    bool found = false;
    // Climb until the node lies on the side of its parent that has the neighbour as sibling.
    while (m != 0) {
        const ObjectNode& nd = nodes[m];
        path[k++] = std::uint8_t(nd.octant ^ bit);
        m = nd.parent;
        if (((nd.octant & bit) == 0) == positive) { found = true; break; }
    }
    if (steps) *steps += std::uint64_t(k);
    if (!found) return kNone;
    // Descend the mirrored path as far as the tree goes.
    while (k > 0 && !nodes[m].leaf()) {
        m = nodes[m].firstChild + path[--k];
        if (steps) ++*steps;
    }
    return m;
}

void ObjectOctree::validate() const {
    if (nodes.empty()) throw Error("object octree: no root");
    for (std::uint32_t i = 0; i < nodes.size(); ++i) {
        const ObjectNode& n = nodes[i];
        if (n.leaf()) {
            if (std::uint64_t(n.firstObject) + n.objectCount > objects.size()) throw Error("object octree: leaf " + std::to_string(i) + " lists objects past the end");
            // Ascending: the beam tracer breaks ties of equal hits by the sphere number, the leaf
            // rule by the list order.
            if (!std::is_sorted(objects.begin() + n.firstObject, objects.begin() + n.firstObject + n.objectCount))
                throw Error("object octree: leaf " + std::to_string(i) + " lists its spheres out of order");
            continue;
        }
        if (n.firstChild + 8 > nodes.size() || n.firstChild <= i) throw Error("object octree: node " + std::to_string(i) + " has children out of range");
        for (unsigned c = 0; c < 8; ++c) {
            const ObjectNode& ch = nodes[n.firstChild + c];
            if (ch.parent != i || ch.octant != c || ch.level != n.level + 1)
                throw Error("object octree: child " + std::to_string(c) + " of node " + std::to_string(i) + " does not link back");
        }
    }
}

SphereHit traceBruteForce(const SphereSet& scene, const dvec3& o, const dvec3& d, double tMin) {
    SphereHit h;
    for (std::uint32_t i = 0; i < scene.spheres.size(); ++i) {
        const double t = intersectSphere(scene.spheres[i], o, d, tMin);
        if (t < h.t) { h.t = t; h.sphere = i; }
    }
    return h;
}

SphereHit nearestInLeaf(const ObjectOctree& tree, const ObjectNode& leaf, const dvec3& o, const dvec3& d, double tMin, double tExit,
                        ObjectTraceCounters& c) {
    SphereHit h;
    const std::uint32_t* list = tree.objects.data() + leaf.firstObject;
    for (std::uint32_t i = 0; i < leaf.objectCount; ++i) {
        const double t = intersectSphere(tree.scene.spheres[list[i]], o, d, tMin);
        if (t < h.t) { h.t = t; h.sphere = list[i]; }
    }
    c.intersections += leaf.objectCount;
    if (h.t > tExit) return {};
    return h;
}

namespace {

SphereHit referenceVisit(const ObjectOctree& tree, std::uint32_t n, double tExit, const dvec3& o, const dvec3& d, const dvec3& inv,
                         double tMin, ObjectTraceCounters& c) {
    ++c.nodes;
    const ObjectNode& nd = tree.nodes[n];
    if (nd.leaf()) return nd.objectCount ? nearestInLeaf(tree, nd, o, d, tMin, tExit, c) : SphereHit{};
    struct Child { double t0, t1; std::uint32_t node; };
    Child kids[8];
    int count = 0;
    for (std::uint32_t k = 0; k < 8; ++k) {
        double t0, t1;
        slabInterval(tree.nodeBox(nd.firstChild + k), o, inv, d, t0, t1);
        if (t0 <= t1 && t1 >= tMin) kids[count++] = {t0, t1, nd.firstChild + k};
    }
    std::stable_sort(kids, kids + count, [](const Child& a, const Child& b) { return a.t0 < b.t0; });
    for (int k = 0; k < count; ++k) {
        SphereHit h = referenceVisit(tree, kids[k].node, kids[k].t1, o, d, inv, tMin, c);
        if (h.hit()) return h;
    }
    return {};
}

}  // namespace

SphereHit traceReference(const ObjectOctree& tree, const dvec3& o, const dvec3& d, double tMin, ObjectTraceCounters& c) {
    const dvec3 inv = 1.0 / d;
    double t0, t1;
    slabInterval(tree.cube(), o, inv, d, t0, t1);
    if (t0 > t1 || t1 < tMin) return {};
    return referenceVisit(tree, 0, t1, o, d, inv, tMin, c);
}

SphereHit traceSamet(const ObjectOctree& tree, const dvec3& o, const dvec3& d, double tMin, ObjectTraceCounters& c) {
    const dvec3 inv = 1.0 / d;
    double t0, t1;
    slabInterval(tree.cube(), o, inv, d, t0, t1);
    if (t0 > t1 || t1 < tMin) return {};
    std::uint32_t leaf = tree.locateLeaf(o + d * std::max(t0, tMin), d);
    for (;;) {
        ++c.nodes;
        const ObjectNode& nd = tree.nodes[leaf];
        const Box3 box = tree.nodeBox(leaf);
        // Exit parameter per axis: the face the ray leaves through.
        double exitT = kInf;
        int axis = -1;
        for (int a = 0; a < 3; ++a) {
            if (d[a] == 0.0) continue;
            const double ta = ((d[a] > 0.0 ? box.hi[a] : box.lo[a]) - o[a]) * inv[a];
            if (ta < exitT) { exitT = ta; axis = a; }
        }
        if (nd.objectCount) {
            SphereHit h = nearestInLeaf(tree, nd, o, d, tMin, exitT, c);
            if (h.hit()) return h;
        }
        if (axis < 0) return {};
        std::uint64_t steps = 0;
        const std::uint32_t nb = tree.faceNeighbour(leaf, axis, d[axis] > 0.0, &steps);
        c.nodes += steps;
        if (nb == kNone) return {};
        leaf = tree.descendToLeaf(nb, o + d * exitT, d);
    }
}

}  // namespace octrace
