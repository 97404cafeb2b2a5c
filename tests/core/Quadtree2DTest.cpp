// Paper B's 2D experiment (bench/quadtree/Quadtree2D.h): the scenes, the quadtree,
// and the three tracers, which must give every ray the same hit (circle and parameter).
#include "quadtree/Quadtree2D.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace octrace;
using namespace octrace::quad;

namespace {

// The number of rays whose hit differs from the brute force's.
std::size_t mismatches(const std::vector<Hit2D>& a, const std::vector<Hit2D>& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += a[i] == b[i] ? 0 : 1;
    return n;
}

void expectTracersAgree(const Scene2D& scene, const dvec2& eye, std::size_t rays, int leafObjects) {
    Quadtree tree = Quadtree::build(scene, leafObjects);
    Fan fan = fanOver(tree, eye, rays);
    auto ref = traceBruteForce(tree.scene, fan);
    Trace2DCounters cs, cb;
    auto samet = traceSamet(tree, fan, cs);
    auto beams = traceBeams(tree, fan, cb);
    std::size_t hits = 0;
    for (const auto& h : ref) hits += h.hit() ? 1 : 0;
    EXPECT_GT(hits, rays / 20) << scene.name << ": the fan should meet the scene";
    EXPECT_LT(hits, rays) << scene.name << ": some rays should pass between the circles";
    EXPECT_EQ(mismatches(samet, ref), 0u) << scene.name << " samet, eye " << eye.x << "," << eye.y;
    EXPECT_EQ(mismatches(beams, ref), 0u) << scene.name << " beam, eye " << eye.x << "," << eye.y;
    // Beam tracing intersects fewer rays with circles than Samet's tracing does, never more.
    EXPECT_LE(cb.intersections, cs.intersections) << scene.name;
}

}  // namespace

TEST(Quadtree2D, TheFlakeHasItsCircleCountAndNoTwoCirclesOverlap) {
    for (int level = 0; level <= 4; ++level) {
        Scene2D s = makeFlake2D(level);
        const double expected = 1.0 + 6.0 * (std::pow(5.0, level) - 1.0) / 4.0;
        EXPECT_EQ(double(s.circles.size()), expected) << level;
    }
    Scene2D s = makeFlake2D(3);
    for (std::size_t i = 0; i < s.circles.size(); ++i)
        for (std::size_t j = i + 1; j < s.circles.size(); ++j) {
            const double d = glm::length(s.circles[i].centre - s.circles[j].centre);
            EXPECT_GE(d, s.circles[i].radius + s.circles[j].radius - 1e-12) << i << " " << j;
        }
    EXPECT_THROW(makeFlake2D(8), UsageError);
}

TEST(Quadtree2D, LeavesTileTheSquareAndHoldEveryCircleTheyMeet) {
    Quadtree t = Quadtree::build(makeRandom2D(500, 7), 4);
    double area = 0.0;
    for (std::uint32_t n = 0; n < t.nodes.size(); ++n) {
        if (!t.nodes[n].leaf()) continue;
        dvec2 lo, hi;
        t.box(n, lo, hi);
        area += (hi.x - lo.x) * (hi.y - lo.y);
        std::size_t meets = 0;
        for (const Circle& c : t.scene.circles)
            meets += (c.centre.x + c.radius >= lo.x && c.centre.x - c.radius <= hi.x && c.centre.y + c.radius >= lo.y &&
                      c.centre.y - c.radius <= hi.y)
                         ? 1
                         : 0;
        EXPECT_EQ(meets, t.nodes[n].objectCount);
        EXPECT_TRUE(t.nodes[n].objectCount <= 4 || t.nodes[n].level == 16);
    }
    EXPECT_NEAR(area, t.side * t.side, 1e-12 * t.side * t.side);
    EXPECT_GT(t.occupiedLeaves(), 100u);
}

TEST(Quadtree2D, SametsNeighbourIsTheAdjacentNodeOfEqualOrLargerSize) {
    Quadtree t = Quadtree::build(makeFlake2D(3), 2);
    for (std::uint32_t n = 1; n < t.nodes.size(); ++n)
        for (int axis = 0; axis < 2; ++axis)
            for (bool positive : {false, true}) {
                const std::uint32_t nb = t.neighbour(n, axis, positive);
                dvec2 lo, hi, nlo, nhi;
                t.box(n, lo, hi);
                const double side = positive ? hi[axis] : lo[axis];
                const double rootSide = positive ? t.origin[axis] + t.side : t.origin[axis];
                if (nb == Quadtree::kNone) {
                    EXPECT_EQ(side, rootSide);
                    continue;
                }
                t.box(nb, nlo, nhi);
                EXPECT_EQ(positive ? nlo[axis] : nhi[axis], side);
                EXPECT_LE(t.nodes[nb].level, t.nodes[n].level);
                EXPECT_LE(nlo[1 - axis], lo[1 - axis]);
                EXPECT_GE(nhi[1 - axis], hi[1 - axis]);
            }
}

TEST(Quadtree2D, SametAndBeamsGiveEveryRayTheBruteForcesHitOnBothScenes) {
    const Scene2D flake = makeFlake2D(3), random = makeRandom2D(300, 1);
    // Eyes on every side, at a corner's diagonal and level with a side (three exit sides).
    const dvec2 eyes[] = {{-3.0, 0.3}, {2.5, -2.0}, {0.1, 4.0}, {-2.0, -2.0}, {0.3, -2.0}};
    for (const dvec2& e : eyes) {
        expectTracersAgree(flake, e, 20000, 8);
        expectTracersAgree(random, e + dvec2(0.5), 20000, 8);
        expectTracersAgree(random, e + dvec2(0.5), 3001, 1);
    }
}

TEST(Quadtree2D, RefusesAnEyeInsideOrTooCloseAndBadParameters) {
    Quadtree t = Quadtree::build(makeFlake2D(1));
    EXPECT_THROW(fanOver(t, dvec2(0.0), 10), UsageError);
    EXPECT_THROW(fanOver(t, dvec2(t.origin.x - 0.1 * t.side, 0.0), 10), UsageError);
    EXPECT_THROW(fanOver(t, dvec2(-5.0, 0.0), 0), UsageError);
    EXPECT_THROW(Quadtree::build(makeFlake2D(1), 0), UsageError);
    EXPECT_THROW(Quadtree::build(Scene2D{}), UsageError);
}
