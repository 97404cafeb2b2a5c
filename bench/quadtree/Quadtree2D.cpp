#include "quadtree/Quadtree2D.h"

#include "octrace/util/Error.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace octrace::quad {
namespace {

void addFlake(Scene2D& s, const dvec2& centre, double radius, double away, int level, bool root) {
    s.circles.push_back({centre, radius});
    if (level == 0) return;
    const double r = radius / 3.0;
    for (int k = 0; k < 6; ++k) {
        // Every 60 degrees from the direction away from the parent; the root has no parent.
        if (!root && k == 3) continue;
        const double a = away + double(k) * std::numbers::pi / 3.0;
        const dvec2 d(std::cos(a), std::sin(a));
        addFlake(s, centre + (radius + r) * d, r, a, level - 1, false);
    }
}

bool boxMeetsCircle(const dvec2& lo, const dvec2& hi, const Circle& c) {
    // The circle's bounding square, as the object octree tests spheres' boxes.
    return c.centre.x + c.radius >= lo.x && c.centre.x - c.radius <= hi.x && c.centre.y + c.radius >= lo.y &&
           c.centre.y - c.radius <= hi.y;
}

// The interval of t in which origin + t dir is inside [lo, hi] (t0 > t1: outside).
void slab(const dvec2& lo, const dvec2& hi, const dvec2& origin, const dvec2& dir, double& t0, double& t1) {
    t0 = -std::numeric_limits<double>::infinity();
    t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 2; ++a) {
        if (dir[a] == 0.0) {
            if (origin[a] < lo[a] || origin[a] > hi[a]) t0 = std::numeric_limits<double>::infinity();
            continue;
        }
        double ta = (lo[a] - origin[a]) / dir[a], tb = (hi[a] - origin[a]) / dir[a];
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
    }
}

// The rule every tracer applies in a leaf: the nearest of its circles hit at t > 0, provided
// it is not beyond tExit; else no hit.
Hit2D nearestInLeaf(const Quadtree& tree, const QuadNode& leaf, const dvec2& origin, const dvec2& dir, double tExit,
                    Trace2DCounters& c) {
    Hit2D best;
    for (std::uint32_t k = 0; k < leaf.objectCount; ++k) {
        const std::uint32_t id = tree.objects[leaf.firstObject + k];
        ++c.intersections;
        const double t = intersectCircle(tree.scene.circles[id], origin, dir);
        if (t < best.t || (t == best.t && id < best.circle)) best = {t, id};
    }
    if (!(best.t <= tExit)) return {};
    return best;
}

double leafExit(const Quadtree& tree, std::uint32_t leaf, const dvec2& origin, const dvec2& dir) {
    dvec2 lo, hi;
    tree.box(leaf, lo, hi);
    double t0, t1;
    slab(lo, hi, origin, dir, t0, t1);
    return t1;
}

}  // namespace

Scene2D makeFlake2D(int level) {
    if (level < 0 || level > 7) throw UsageError("2D sphereflake level must be 0..7, got " + std::to_string(level));
    Scene2D s;
    s.name = "flake2d-" + std::to_string(level);
    addFlake(s, dvec2(0.0), 0.5, 0.0, level, true);
    return s;
}

Scene2D makeRandom2D(std::size_t count, std::uint64_t seed, double radius) {
    if (count == 0 || count > 1000000) throw UsageError("random circles: count must be 1..1000000");
    if (!(radius > 0.0 && radius < 1.0)) throw UsageError("random circles: radius must be in (0, 1)");
    Scene2D s;
    s.name = "random2d-" + std::to_string(count);
    std::mt19937_64 rng(seed);
    auto uniform = [&] { return double(rng() >> 11) * 0x1.0p-53; };
    s.circles.reserve(count);
    for (std::size_t i = 0; i < count; ++i) {
        Circle c;
        c.centre = dvec2(uniform(), uniform());
        c.radius = radius * (0.2 + 0.8 * uniform());
        s.circles.push_back(c);
    }
    return s;
}

double intersectCircle(const Circle& c, const dvec2& origin, const dvec2& dir) {
    const dvec2 oc = origin - c.centre;
    const double a = glm::dot(dir, dir), b = glm::dot(oc, dir), cc = glm::dot(oc, oc) - c.radius * c.radius;
    const double disc = b * b - a * cc;
    if (disc < 0.0) return std::numeric_limits<double>::infinity();
    const double s = std::sqrt(disc);
    const double t0 = (-b - s) / a;
    if (t0 > 0.0) return t0;
    const double t1 = (-b + s) / a;
    return t1 > 0.0 ? t1 : std::numeric_limits<double>::infinity();
}

Quadtree Quadtree::build(Scene2D scene, int leafObjects, int maxDepth) {
    if (leafObjects < 1) throw UsageError("leaf objects must be at least 1");
    if (maxDepth < 1 || maxDepth > kMaxDepth) throw UsageError("quadtree depth must be 1.." + std::to_string(kMaxDepth));
    if (scene.circles.empty()) throw UsageError("empty 2D scene");
    Quadtree t;
    dvec2 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const Circle& c : scene.circles) {
        lo = glm::min(lo, c.centre - dvec2(c.radius));
        hi = glm::max(hi, c.centre + dvec2(c.radius));
    }
    t.side = std::max(hi.x - lo.x, hi.y - lo.y) * (1.0 + 1e-9);
    t.origin = lo - dvec2(t.side * 0.5e-9);
    t.scene = std::move(scene);
    t.nodes.push_back({});
    // Breadth-first: each node is split while it holds too many circles.
    std::vector<std::vector<std::uint32_t>> lists(1);
    lists[0].resize(t.scene.circles.size());
    for (std::uint32_t i = 0; i < lists[0].size(); ++i) lists[0][i] = i;
    for (std::uint32_t n = 0; n < t.nodes.size(); ++n) {
        std::vector<std::uint32_t> list = std::move(lists[n]);
        const QuadNode node = t.nodes[n];
        t.depth = std::max(t.depth, int(node.level));
        if (int(list.size()) <= leafObjects || node.level >= maxDepth) {
            t.nodes[n].firstObject = std::uint32_t(t.objects.size());
            t.nodes[n].objectCount = std::uint32_t(list.size());
            t.objects.insert(t.objects.end(), list.begin(), list.end());
            continue;
        }
        const std::uint32_t half = 1u << (kMaxDepth - node.level - 1);
        QuadNode children[4];
        std::vector<std::uint32_t> childLists[4];
        std::size_t copies = 0;
        for (std::uint8_t q = 0; q < 4; ++q) {
            QuadNode& ch = children[q];
            ch.parent = n;
            ch.level = std::uint8_t(node.level + 1);
            ch.quadrant = q;
            ch.cell[0] = node.cell[0] + ((q >> 1) & 1u) * half;
            ch.cell[1] = node.cell[1] + (q & 1u) * half;
            const double step = t.side / double(1u << kMaxDepth);
            const dvec2 clo(t.origin.x + double(ch.cell[0]) * step, t.origin.y + double(ch.cell[1]) * step);
            const dvec2 chi(t.origin.x + double(ch.cell[0] + half) * step, t.origin.y + double(ch.cell[1] + half) * step);
            for (std::uint32_t id : list)
                if (boxMeetsCircle(clo, chi, t.scene.circles[id])) childLists[q].push_back(id);
            copies += childLists[q].size();
        }
        // Circles whose squares overlap too much stay together: a split that would list them
        // more than twice over in its children gains nothing (tangent circles of the flake
        // would otherwise be split down to maxDepth around every contact).
        if (copies > 2 * list.size()) {
            t.nodes[n].firstObject = std::uint32_t(t.objects.size());
            t.nodes[n].objectCount = std::uint32_t(list.size());
            t.objects.insert(t.objects.end(), list.begin(), list.end());
            continue;
        }
        const auto first = std::uint32_t(t.nodes.size());
        t.nodes[n].firstChild = first;
        for (std::uint8_t q = 0; q < 4; ++q) {
            t.nodes.push_back(children[q]);
            lists.push_back(std::move(childLists[q]));
        }
    }
    return t;
}

void Quadtree::box(std::uint32_t n, dvec2& lo, dvec2& hi) const {
    const QuadNode& nd = nodes[n];
    const double step = side / double(1u << kMaxDepth);
    const std::uint32_t size = 1u << (kMaxDepth - nd.level);
    for (int a = 0; a < 2; ++a) {
        lo[a] = origin[a] + double(nd.cell[a]) * step;
        hi[a] = origin[a] + double(nd.cell[a] + size) * step;
    }
}

std::size_t Quadtree::leaves() const {
    return std::size_t(std::count_if(nodes.begin(), nodes.end(), [](const QuadNode& n) { return n.leaf(); }));
}

std::size_t Quadtree::occupiedLeaves() const {
    return std::size_t(
        std::count_if(nodes.begin(), nodes.end(), [](const QuadNode& n) { return n.leaf() && n.objectCount > 0; }));
}

std::uint32_t Quadtree::descendToLeaf(std::uint32_t n, const dvec2& p, const dvec2& dir) const {
    while (!nodes[n].leaf()) {
        // The children's shared edges, computed as a child's corner (bit for bit the same).
        dvec2 clo, chi;
        box(nodes[n].firstChild + 3, clo, chi);
        std::uint8_t q = 0;
        for (int a = 0; a < 2; ++a) {
            const bool high = p[a] > clo[a] || (p[a] == clo[a] && dir[a] > 0.0);
            if (high) q = std::uint8_t(q | (a == 0 ? 2u : 1u));
        }
        n = nodes[n].firstChild + q;
    }
    return n;
}

std::uint32_t Quadtree::neighbour(std::uint32_t n, int axis, bool positive) const {
    const std::uint8_t bit = axis == 0 ? 2u : 1u;
    // Climb to the first ancestor in which the path turns away from the side we leave by:
    // the mirrored sibling there is the neighbour's ancestor (or the neighbour).
    std::uint8_t path[kMaxDepth];
    int length = 0;
    std::uint32_t cur = n;
    for (;;) {
        if (cur == 0) return kNone;  // on the square's boundary
        const std::uint8_t q = nodes[cur].quadrant;
        path[length++] = q;
        cur = nodes[cur].parent;
        if (bool(q & bit) != positive) break;
    }
    // Descend the mirrored path while the nodes exist.
    while (length > 0 && !nodes[cur].leaf()) cur = nodes[cur].firstChild + std::uint8_t(path[--length] ^ bit);
    return cur;
}

Fan fanOver(const Quadtree& tree, const dvec2& eye, std::size_t n) {
    const dvec2 lo = tree.origin, hi = tree.origin + dvec2(tree.side);
    const dvec2 gap = glm::max(lo - eye, eye - hi);
    if (std::max(gap.x, gap.y) < 0.5 * tree.side)
        throw UsageError("the eye must lie outside the quadtree's square, at least half its side away");
    if (n == 0) throw UsageError("a fan needs at least one ray");
    Fan f;
    f.eye = eye;
    f.forward = glm::normalize(0.5 * (lo + hi) - eye);
    f.right = dvec2(-f.forward.y, f.forward.x);
    f.n = n;
    f.u0 = std::numeric_limits<double>::infinity();
    f.u1 = -std::numeric_limits<double>::infinity();
    for (int k = 0; k < 4; ++k) {
        const dvec2 corner((k & 2) ? hi.x : lo.x, (k & 1) ? hi.y : lo.y);
        const double u = f.uOf(corner);
        f.u0 = std::min(f.u0, u);
        f.u1 = std::max(f.u1, u);
    }
    return f;
}

std::vector<Hit2D> traceBruteForce(const Scene2D& scene, const Fan& fan) {
    std::vector<Hit2D> out(fan.n);
    for (std::size_t i = 0; i < fan.n; ++i) {
        const dvec2 d = fan.direction(i);
        Hit2D best;
        for (std::uint32_t id = 0; id < scene.circles.size(); ++id) {
            const double t = intersectCircle(scene.circles[id], fan.eye, d);
            if (t < best.t) best = {t, id};
        }
        out[i] = best;
    }
    return out;
}

std::vector<Hit2D> traceSamet(const Quadtree& tree, const Fan& fan, Trace2DCounters& c) {
    std::vector<Hit2D> out(fan.n);
    const dvec2 lo = tree.origin, hi = tree.origin + dvec2(tree.side);
    for (std::size_t i = 0; i < fan.n; ++i) {
        const dvec2 d = fan.direction(i);
        double t0, t1;
        slab(lo, hi, fan.eye, d, t0, t1);
        if (!(t0 <= t1) || t1 <= 0.0) continue;
        std::uint32_t leaf = tree.descendToLeaf(0, fan.eye + std::max(t0, 0.0) * d, d);
        for (std::size_t guard = 0; guard <= 4 * tree.nodes.size(); ++guard) {
            ++c.nodes;
            dvec2 llo, lhi;
            tree.box(leaf, llo, lhi);
            double e0, tExit;
            slab(llo, lhi, fan.eye, d, e0, tExit);
            const QuadNode& node = tree.nodes[leaf];
            if (node.objectCount > 0) {
                const Hit2D h = nearestInLeaf(tree, node, fan.eye, d, tExit, c);
                if (h.hit()) {
                    out[i] = h;
                    break;
                }
            }
            // The side the ray leaves by: the axis whose exit parameter is tExit (x first on a corner).
            int axis = 1;
            for (int a = 0; a < 2; ++a) {
                if (d[a] == 0.0) continue;
                const double ta = ((d[a] > 0.0 ? lhi[a] : llo[a]) - fan.eye[a]) / d[a];
                if (ta == tExit) {
                    axis = a;
                    break;
                }
            }
            ++c.neighbourSteps;
            const std::uint32_t nb = tree.neighbour(leaf, axis, d[axis] > 0.0);
            if (nb == Quadtree::kNone) break;
            dvec2 p = fan.eye + tExit * d;
            // The exit point lies on the shared side: put it there exactly.
            dvec2 nlo, nhi;
            tree.box(nb, nlo, nhi);
            p[axis] = d[axis] > 0.0 ? nlo[axis] : nhi[axis];
            p[1 - axis] = std::clamp(p[1 - axis], nlo[1 - axis], nhi[1 - axis]);
            leaf = tree.descendToLeaf(nb, p, d);
        }
    }
    return out;
}

namespace {

// A beam: the rays [first, last) of the fan, all entering `leaf` through one side.
struct Beam {
    std::uint32_t leaf;
    std::size_t first, last;
};

// The leaves of node n touching its side (axis, high) (the side facing the beam's origin leaf).
void leavesAlongSide(const Quadtree& tree, std::uint32_t n, int axis, bool high, std::vector<std::uint32_t>& out) {
    if (tree.nodes[n].leaf()) {
        out.push_back(n);
        return;
    }
    const std::uint8_t bit = axis == 0 ? 2u : 1u;
    const std::uint8_t other = axis == 0 ? 1u : 2u;
    for (std::uint8_t side : {std::uint8_t(0), other}) {
        const std::uint8_t q = std::uint8_t(side | (high ? bit : 0u));
        leavesAlongSide(tree, tree.nodes[n].firstChild + q, axis, high, out);
    }
}

}  // namespace

std::vector<Hit2D> traceBeams(const Quadtree& tree, const Fan& fan, Trace2DCounters& c) {
    std::vector<Hit2D> out(fan.n);
    std::vector<double> us(fan.n);
    for (std::size_t i = 0; i < fan.n; ++i) us[i] = fan.u(i);
    std::vector<Beam> stack;
    std::vector<std::uint32_t> along;
    // The beam of the rays [first, last) crossing the segment a-b into `leaf`, cut to the rays
    // whose u lies between those of a and b (binary search in the sorted fan).
    auto push = [&](std::uint32_t leaf, const dvec2& a, const dvec2& b, std::size_t first, std::size_t last) {
        double ua = fan.uOf(a), ub = fan.uOf(b);
        if (ua > ub) std::swap(ua, ub);
        const auto begin = us.begin() + std::ptrdiff_t(first), end = us.begin() + std::ptrdiff_t(last);
        const auto f = std::lower_bound(begin, end, ua);
        const auto l = std::lower_bound(f, end, ub);
        if (f < l) stack.push_back({leaf, std::size_t(f - us.begin()), std::size_t(l - us.begin())});
    };
    // The leaves of node `n` along its side (axis, high), each with the part of the segment
    // [lo, hi] on that side they share: one beam each (paper B, fig. 3).
    auto cut = [&](std::uint32_t n, int axis, bool high, const dvec2& lo, const dvec2& hi, std::size_t first,
                   std::size_t last) {
        along.clear();
        leavesAlongSide(tree, n, axis, high, along);
        for (std::uint32_t next : along) {
            dvec2 nlo, nhi;
            tree.box(next, nlo, nhi);
            dvec2 a = lo, b = hi;
            a[axis] = b[axis] = high ? nhi[axis] : nlo[axis];
            a[1 - axis] = std::max(lo[1 - axis], nlo[1 - axis]);
            b[1 - axis] = std::min(hi[1 - axis], nhi[1 - axis]);
            push(next, a, b, first, last);
        }
    };
    // The initial beams: the root's sides that face the eye, cut by the leaves behind them
    // (paper B: "cut by the octants of the tree face visible from the eye").
    dvec2 rlo, rhi;
    tree.box(0, rlo, rhi);
    for (int axis = 0; axis < 2; ++axis)
        for (bool high : {false, true})
            if (high ? fan.eye[axis] > rhi[axis] : fan.eye[axis] < rlo[axis]) cut(0, axis, high, rlo, rhi, 0, fan.n);
    // The rays [first, last) leave `leaf` by its sides away from the eye; each side's part of
    // them goes on into the leaves behind it, or leaves the scene (no hit: background).
    auto moveOn = [&](std::uint32_t leaf, std::size_t first, std::size_t last) {
        dvec2 lo, hi;
        tree.box(leaf, lo, hi);
        for (int axis = 0; axis < 2; ++axis)
            for (bool high : {false, true}) {
                if (!(high ? fan.eye[axis] < hi[axis] : fan.eye[axis] > lo[axis])) continue;
                ++c.neighbourSteps;
                const std::uint32_t nb = tree.neighbour(leaf, axis, high);
                if (nb != Quadtree::kNone) cut(nb, axis, !high, lo, hi, first, last);
            }
    };
    while (!stack.empty()) {
        const Beam beam = stack.back();
        stack.pop_back();
        ++c.beams;
        ++c.nodes;
        const QuadNode& node = tree.nodes[beam.leaf];
        if (node.objectCount == 0) {
            moveOn(beam.leaf, beam.first, beam.last);  // empty: only the beam moves
            continue;
        }
        // Occupied: the beam's rays one by one (none of them is hit yet: a hit ray leaves its
        // beam); the runs of rays still unhit go on as beams, a beam all hit ends.
        c.raySelections += beam.last - beam.first;
        for (std::size_t i = beam.first; i < beam.last; ++i) {
            const dvec2 d = fan.direction(i);
            out[i] = nearestInLeaf(tree, node, fan.eye, d, leafExit(tree, beam.leaf, fan.eye, d), c);
        }
        for (std::size_t i = beam.first; i < beam.last;) {
            while (i < beam.last && out[i].hit()) ++i;
            std::size_t j = i;
            while (j < beam.last && !out[j].hit()) ++j;
            if (i < j) moveOn(beam.leaf, i, j);
            i = j;
        }
    }
    return out;
}

}  // namespace octrace::quad
