// Sphere scenes, the object octree and its three tracers (reference, samet, beam).
#include "octrace/build/OctreeBuilder.h"
#include "octrace/render/Renderer.h"
#include "octrace/scene/ObjectOctree.h"
#include "octrace/scene/Spheres.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace octrace;

namespace {
dvec3 randomUnit(std::mt19937_64& rng) {
    std::normal_distribution<double> n;
    return glm::normalize(dvec3(n(rng), n(rng), n(rng)));
}
Camera cameraFor(const ObjectOctree& t, int w, int h) { return Camera::framing(t.scene.bounds(), w, h, 30.0); }
}  // namespace

TEST(SphereFlake, HasHainesCountsAndTangentChildren) {
    // SPD balls: 10, 91, 820, 7381 spheres at levels 1..4.
    EXPECT_EQ(makeSphereFlake(1).spheres.size(), 10u);
    EXPECT_EQ(makeSphereFlake(2).spheres.size(), 91u);
    EXPECT_EQ(makeSphereFlake(3).spheres.size(), 820u);
    const SphereSet f = makeSphereFlake(4);
    EXPECT_EQ(f.spheres.size(), 7381u);
    // The root: radius 0.5 at the origin; its 9 children of radius 1/6 touch it, 6 on the
    // equator (z = 0) and 3 above.
    EXPECT_DOUBLE_EQ(f.spheres[0].radius, 0.5);
    const SphereSet one = makeSphereFlake(1);
    int equator = 0, above = 0;
    for (std::size_t i = 1; i < one.spheres.size(); ++i) {
        const Sphere& s = one.spheres[i];
        EXPECT_NEAR(s.radius, 0.5 / 3.0, 1e-15);
        EXPECT_NEAR(glm::length(s.centre), 0.5 + 0.5 / 3.0, 1e-12);
        if (std::abs(s.centre.z) < 1e-12) ++equator;
        else if (s.centre.z > 0.0) ++above;
    }
    EXPECT_EQ(equator, 6);
    EXPECT_EQ(above, 3);
    EXPECT_THROW(makeSphereFlake(7), UsageError);
}

TEST(RandomSpheres, AreReproducibleFromTheSeed) {
    const SphereSet a = makeRandomSpheres(100, 7), b = makeRandomSpheres(100, 7), c = makeRandomSpheres(100, 8);
    ASSERT_EQ(a.spheres.size(), 100u);
    EXPECT_EQ(a.spheres[42].centre, b.spheres[42].centre);
    EXPECT_NE(a.spheres[42].centre, c.spheres[42].centre);
    EXPECT_THROW(makeRandomSpheres(0, 1), UsageError);
}

TEST(ObjectOctree, SplitsWhileANodeHoldsMoreThanTheThreshold) {
    ObjectOctreeOptions o;
    o.leafObjects = 4;
    const ObjectOctree t = ObjectOctree::build(makeRandomSpheres(2000, 3, 0.01), o);
    t.validate();
    EXPECT_GT(t.nodes.size(), 8u);
    for (const ObjectNode& n : t.nodes)
        if (n.leaf()) { EXPECT_TRUE(int(n.objectCount) <= 4 || n.level == o.maxDepth); }
    // Every sphere is listed in every leaf its box meets (spot check by the leaf of its centre).
    for (std::uint32_t i = 0; i < 2000; i += 37) {
        const std::uint32_t leaf = t.locateLeaf(t.scene.spheres[i].centre, dvec3(1, 1, 1));
        const ObjectNode& n = t.nodes[leaf];
        bool found = false;
        for (std::uint32_t k = 0; k < n.objectCount; ++k) found = found || t.objects[n.firstObject + k] == i;
        EXPECT_TRUE(found) << i;
    }
    EXPECT_THROW(ObjectOctree::build(makeRandomSpheres(10, 3), {0, 10, 0}), UsageError);
}

TEST(ObjectOctree, CoincidentSpheresStopTheSplittingInsteadOfFillingTheTree) {
    // 20 copies of one sphere plus a few others: no split can separate the copies, so the
    // tree stays small (without the overlap rule: about 8^maxDepth nodes over the shared box).
    SphereSet s;
    s.source = "test";
    for (int i = 0; i < 20; ++i) s.spheres.push_back({dvec3(0.3, 0.4, 0.5), 0.2});
    for (int i = 0; i < 5; ++i) s.spheres.push_back({dvec3(0.1 * i, 0.9, 0.1), 0.05});
    const ObjectOctree t = ObjectOctree::build(std::move(s));
    t.validate();
    EXPECT_LT(t.nodes.size(), 2000u);
    const dvec3 o(0.3, 0.4, -2.0), d(0.0, 0.0, 1.0);
    ObjectTraceCounters c;
    EXPECT_EQ(traceSamet(t, o, d, 0.0, c).t, traceBruteForce(t.scene, o, d, 0.0).t);
}

TEST(ObjectOctree, FaceNeighbourIsTheAdjacentNodeOfEqualOrLargerSize) {
    const ObjectOctree t = ObjectOctree::build(makeSphereFlake(3), {2, 8, 0});
    int checked = 0;
    for (std::uint32_t n = 1; n < t.nodes.size(); ++n) {
        const Box3 b = t.nodeBox(n);
        for (int axis = 0; axis < 3; ++axis)
            for (bool pos : {false, true}) {
                const std::uint32_t nb = t.faceNeighbour(n, axis, pos);
                const double face = pos ? b.hi[axis] : b.lo[axis];
                if (face == t.cube().lo[axis] || face == t.cube().hi[axis]) {
                    EXPECT_EQ(nb, 0xFFFFFFFFu);
                    continue;
                }
                ASSERT_NE(nb, 0xFFFFFFFFu);
                const Box3 o = t.nodeBox(nb);
                EXPECT_EQ(pos ? o.lo[axis] : o.hi[axis], face);  // shares the face
                EXPECT_LE(t.nodes[nb].level, t.nodes[n].level);  // equal or larger
                for (int a = 0; a < 3; ++a)
                    if (a != axis) { EXPECT_TRUE(o.lo[a] <= b.lo[a] && o.hi[a] >= b.hi[a]); }  // covers the face
                ++checked;
            }
    }
    EXPECT_GT(checked, 1000);
}

TEST(ObjectOctree, ReferenceAndSametFindTheBruteForceHitOnRandomRays) {
    for (int leafObjects : {1, 8}) {
        const ObjectOctree t = ObjectOctree::build(makeRandomSpheres(500, 11, 0.05), {leafObjects, 10, 0});
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> u(-0.5, 1.5);
        int hits = 0;
        for (int i = 0; i < 20000; ++i) {
            const dvec3 o(u(rng), u(rng), u(rng));
            const dvec3 d = randomUnit(rng);
            ObjectTraceCounters c;
            const SphereHit b = traceBruteForce(t.scene, o, d, 0.0);
            const SphereHit r = traceReference(t, o, d, 0.0, c);
            const SphereHit s = traceSamet(t, o, d, 0.0, c);
            ASSERT_EQ(r.sphere, b.sphere) << i;
            ASSERT_EQ(s.sphere, b.sphere) << i;
            if (b.hit()) { EXPECT_EQ(r.t, b.t); }
            hits += b.hit();
        }
        EXPECT_GT(hits, 2000);
    }
}

TEST(ObjectOctree, SametHandlesAxisParallelRays) {
    const ObjectOctree t = ObjectOctree::build(makeSphereFlake(2), {2, 8, 0});
    for (int a = 0; a < 3; ++a)
        for (double x = -0.9; x < 0.9; x += 0.01) {
            dvec3 o(x, 0.3 * x, -2.0), d(0, 0, 1);
            if (a == 1) { o = dvec3(x, -2.0, 0.1); d = dvec3(0, 1, 0); }
            if (a == 2) { o = dvec3(-2.0, x, x * 0.5); d = dvec3(1, 0, 0); }
            ObjectTraceCounters c;
            EXPECT_EQ(traceSamet(t, o, d, 0.0, c).sphere, traceBruteForce(t.scene, o, d, 0.0).sphere);
        }
}

TEST(SphereRenderers, SametAndBeamGiveTheReferenceHitForEveryRay) {
    for (const char* scene : {"flake", "random"}) {
        ObjectOctree t = ObjectOctree::build(std::string(scene) == "flake" ? makeSphereFlake(3) : makeRandomSpheres(3000, 2, 0.03));
        for (bool ortho : {false, true}) {
            Camera cam = cameraFor(t, 160, 120);
            if (ortho) cam.frameOrthographic(t.scene.bounds());
            RenderSettings rs;
            rs.threads = 2;
            Frame ref, samet, beam;
            const RenderStats rst = makeRenderer("reference")->renderSpheres(t, cam, rs, ref);
            makeRenderer("samet")->renderSpheres(t, cam, rs, samet);
            const RenderStats bst = makeRenderer("beam")->renderSpheres(t, cam, rs, beam);
            EXPECT_GT(rst.hits, 2000u) << scene;
            EXPECT_EQ(bst.hits, rst.hits);
            EXPECT_EQ(samet.hitId, ref.hitId) << scene << ortho;
            EXPECT_EQ(beam.hitId, ref.hitId) << scene << ortho;
            EXPECT_EQ(beam.rgba, ref.rgba);
            // Brute force on a sample of pixels.
            const RayGenerator gen(cam);
            for (int y = 0; y < cam.height; y += 7)
                for (int x = 0; x < cam.width; x += 5) {
                    const Ray r = gen(x, y);
                    EXPECT_EQ(ref.hitId[ref.pixel(x, y)], traceBruteForce(t.scene, r.origin, r.direction, 0.0).sphere);
                }
        }
    }
}

namespace {
/// Beam and samet against the reference, ray by ray (the samples' colours average into the
/// pixel, so equal colours mean equal hits) and by the first sample's hit.
void expectBeamAndSametGiveTheReference(const ObjectOctree& t, const Camera& cam, int samples, const std::string& what) {
    RenderSettings rs;
    rs.threads = 2;
    rs.spheres.bounces = 0;
    rs.spheres.samples = samples;
    Frame ref, samet, beam;
    const RenderStats rst = makeRenderer("reference")->renderSpheres(t, cam, rs, ref);
    const RenderStats sst = makeRenderer("samet")->renderSpheres(t, cam, rs, samet);
    const RenderStats bst = makeRenderer("beam")->renderSpheres(t, cam, rs, beam);
    EXPECT_GT(rst.hits, 0u) << what;
    EXPECT_EQ(bst.hits, rst.hits) << what;
    EXPECT_EQ(bst.rays, rst.rays) << what;
    EXPECT_EQ(sst.rays, rst.rays) << what;
    EXPECT_EQ(beam.hitId, ref.hitId) << what;
    EXPECT_EQ(samet.hitId, ref.hitId) << what;
    EXPECT_EQ(beam.rgba, ref.rgba) << what;
}
}  // namespace

TEST(SphereRenderers, BeamRowsOfSeveralMaskWordsAndPartWords) {
    // Tiles of 128 x 128 rays in whole pixels: 3 x 3 samples give tiles of 42 pixels, rows of
    // 126 rays (a 64-bit word and part of one) and, at the image's right edge, 24; 5 x 5 give
    // 125; 16 x 16 give tiles of 8 pixels, 128 rays (two whole words).
    const ObjectOctree t = ObjectOctree::build(makeRandomSpheres(2000, 5, 0.04));
    for (int samples : {9, 25, 256}) {
        Camera cam = cameraFor(t, samples == 256 ? 24 : 50, samples == 256 ? 18 : 37);
        expectBeamAndSametGiveTheReference(t, cam, samples, "samples " + std::to_string(samples));
    }
}

TEST(SphereRenderers, RaysCountsEverySampleWhoseRayMeetsTheSceneCube) {
    // The statistic is counted from the cube's outline on the screen, with the slab test only
    // near its edges (or everywhere when the eye is inside the cube or beside it); it must be
    // the count of slab tests over every ray.
    const ObjectOctree t = ObjectOctree::build(makeRandomSpheres(300, 3, 0.05));
    const Box3 cube = t.cube();
    std::vector<Camera> cams;
    cams.push_back(cameraFor(t, 61, 47));
    Camera c = cameraFor(t, 61, 47);
    c.position = cube.centre() + dvec3(0.9, -0.4, 0.3) * cube.size().x;  // the cube leaves the screen
    c.fovYDegrees = 70.0;
    cams.push_back(c);
    c.position = cube.centre() + dvec3(0.1, 0.2, -0.1);  // inside
    cams.push_back(c);
    c.position = cube.centre() + dvec3(0.0, 0.0, 0.6) * cube.size().x;  // beside: corners behind the eye
    c.lookAt = c.position + dvec3(1.0, 0.0, 0.0);
    cams.push_back(c);
    Camera o = cameraFor(t, 61, 47);
    o.frameOrthographic(t.scene.bounds());
    cams.push_back(o);
    o.position = cube.centre() + dvec3(0.0, 0.0, 3.0);  // along an axis: the outline is a square
    o.lookAt = cube.centre();
    o.up = dvec3(0.0, 1.0, 0.0);
    cams.push_back(o);
    for (std::size_t k = 0; k < cams.size(); ++k)
        for (int samples : {1, 4}) {
            RenderSettings rs;
            rs.spheres.bounces = 0;
            rs.spheres.samples = samples;
            Frame f;
            const RenderStats st = makeRenderer("beam")->renderSpheres(t, cams[k], rs, f);
            Camera fine = cams[k];
            const int side = samples == 4 ? 2 : 1;
            fine.width *= side;
            fine.height *= side;
            const RayGenerator gen(fine);
            std::uint64_t expected = 0;
            for (int y = 0; y < fine.height; ++y)
                for (int x = 0; x < fine.width; ++x) {
                    const Ray r = gen(x, y);
                    double t0, t1;
                    slabInterval(cube, r.origin, 1.0 / r.direction, r.direction, t0, t1);
                    expected += t0 <= t1 && t1 >= 0.0;
                }
            EXPECT_EQ(st.rays, expected) << "camera " << k << ", samples " << samples;
            if (k == 0 || k == 2) {
                EXPECT_GT(expected, 0u);
            }
        }
}

TEST(SphereRenderers, TheLightShowsWhereRaysBesideTheSceneCubePointAtIt) {
    // Rays beside the scene cube are not traced (they miss every sphere) but still show the
    // light where they point within half a degree of it: a far camera, the light ahead and to
    // the right of the small cube, a black background. Every pixel is checked against the rule.
    const ObjectOctree t = ObjectOctree::build(makeSphereFlake(2));
    const Box3 cube = t.cube();
    Camera cam;
    cam.position = cube.centre() + dvec3(0.0, -8.0, 0.0) * cube.size().x;
    cam.lookAt = cube.centre();
    cam.width = 240;
    cam.height = 180;
    cam.fovYDegrees = 20.0;
    cam.up = dvec3(0.0, 0.0, 1.0);
    dvec3 right, up, back;
    cam.basis(right, up, back);
    for (int samples : {1, 4}) {
        RenderSettings rs;
        rs.spheres.bounces = 0;
        rs.spheres.samples = samples;
        rs.background = vec4(0.0f, 0.0f, 0.0f, 1.0f);
        rs.lightCamera = dvec3(0.12, 0.05, -1.0);
        const dvec3 l = glm::normalize(rs.lightCamera);
        const dvec3 light = glm::normalize(l.x * right + l.y * up + l.z * back);
        Frame f;
        makeRenderer("beam")->renderSpheres(t, cam, rs, f);
        Camera fine = cam;
        const int side = samples == 4 ? 2 : 1;
        fine.width *= side;
        fine.height *= side;
        const RayGenerator gen(fine);
        int lit = 0;
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width; ++x) {
                float expected = 0.0f;
                bool beside = true;
                for (int b = 0; b < side; ++b)
                    for (int a = 0; a < side; ++a) {
                        const Ray r = gen(x * side + a, y * side + b);
                        double t0, t1;
                        slabInterval(cube, r.origin, 1.0 / r.direction, r.direction, t0, t1);
                        beside = beside && !(t0 <= t1 && t1 >= 0.0);
                        expected += glm::dot(r.direction, light) > 0.99996192306 ? 1.0f : 0.0f;
                    }
                if (!beside) continue;
                expected /= float(side * side);
                lit += expected > 0.0f;
                ASSERT_EQ(f.rgba[f.pixel(x, y)], vec4(vec3(expected), 1.0f)) << x << " " << y << ", samples " << samples;
            }
        EXPECT_GT(lit, 10) << "the light is not on the screen, samples " << samples;
    }
}

TEST(SphereRenderers, BeamGivesTheReferenceFromAnEyeInsideTheScene) {
    // Nodes and spheres that reach behind the eye do not cut the beam; the spheres around the
    // eye are hit from inside or behind.
    const ObjectOctree t = ObjectOctree::build(makeRandomSpheres(3000, 6, 0.02));
    for (const dvec3& eye : {dvec3(0.5, 0.5, 0.5), dvec3(0.1, 0.9, 0.3)}) {
        Camera cam;
        cam.position = eye;
        cam.lookAt = eye + dvec3(0.3, -0.2, 1.0);
        cam.fovYDegrees = 100.0;
        cam.width = 64;
        cam.height = 48;
        expectBeamAndSametGiveTheReference(t, cam, 1, "inside");
        expectBeamAndSametGiveTheReference(t, cam, 4, "inside, 4 samples");
    }
}

TEST(SphereRenderers, BeamGivesTheReferenceForRaysInNodeFaces) {
    // The eye on the root's mid-plane x (a face of a node at every level) looking along it: the
    // middle column's rays (odd width: screen x exactly 0) lie in that plane, and so do the
    // orthographic rays of the middle column; spheres are centred on it too.
    SphereSet s = makeRandomSpheres(1500, 9, 0.03);
    ObjectOctree probe = ObjectOctree::build(makeRandomSpheres(1500, 9, 0.03));
    const double mid = probe.nodeBox(probe.nodes[0].firstChild).hi.x;
    // Copies of every third sphere moved onto the plane: the bounds, hence the cube, stay.
    for (std::size_t i = 0, n = s.spheres.size(); i < n; i += 3) {
        Sphere c = s.spheres[i];
        c.centre.x = mid;
        s.spheres.push_back(c);
    }
    const ObjectOctree t = ObjectOctree::build(std::move(s));
    ASSERT_EQ(t.nodeBox(t.nodes[0].firstChild).hi.x, mid);
    for (bool ortho : {false, true}) {
        Camera cam;
        cam.position = dvec3(mid, 0.35, 3.0);
        cam.lookAt = dvec3(mid, 0.5, 0.5);
        cam.width = 41;
        cam.height = 31;
        if (ortho) cam.frameOrthographic(t.scene.bounds());
        const Ray r = RayGenerator(cam)(20, 7);
        ASSERT_EQ(ortho ? r.origin.x : r.direction.x, ortho ? mid : 0.0);
        expectBeamAndSametGiveTheReference(t, cam, 1, ortho ? "face, orthographic" : "face");
    }
}

TEST(SphereRenderers, BeamBreaksTiesOfCoincidentSpheresAsTheReference) {
    // Copies of spheres (a higher number, another colour) give exactly equal hits: the leaf rule
    // takes the earlier sphere of the leaf's list, and the beam, which keeps each ray's nearest
    // hit across leaves, must take the same one. Copies placed before the originals in the
    // list too (the set is built with them first).
    SphereSet base = makeRandomSpheres(1500, 11, 0.04);
    for (bool copiesFirst : {false, true}) {
        SphereSet s;
        s.materials = base.materials;
        std::vector<Sphere> copies;
        for (std::size_t i = 0; i < base.spheres.size(); i += 3) {
            Sphere c = base.spheres[i];
            c.colour = vec3(1.0f, 0.0f, 1.0f) - c.colour;
            copies.push_back(c);
        }
        if (copiesFirst) s.spheres = copies;
        s.spheres.insert(s.spheres.end(), base.spheres.begin(), base.spheres.end());
        if (!copiesFirst) s.spheres.insert(s.spheres.end(), copies.begin(), copies.end());
        for (int leafObjects : {1, 8}) {
            ObjectOctreeOptions opt;
            opt.leafObjects = leafObjects;
            SphereSet scene;
            scene.materials = s.materials;
            scene.spheres = s.spheres;
            const ObjectOctree t = ObjectOctree::build(std::move(scene), opt);
            expectBeamAndSametGiveTheReference(t, cameraFor(t, 90, 70), 1, "coincident, leaf objects " + std::to_string(leafObjects));
            expectBeamAndSametGiveTheReference(t, cameraFor(t, 45, 35), 4, "coincident, 4 samples");
        }
    }
}

TEST(SphereRenderers, BeamTestsASphereMetLaterWhoseHitTiesTheNearestSoFar) {
    // The beam leaves out a sphere's test for a ray whose nearest hit so far lies nearer than the
    // sphere's distance from the eye minus its radius, less a margin for rounding. Here a large
    // sphere Y (lower number, so tested first in their leaf) and a small one X share their
    // nearest point on one pixel's ray: along that ray the two hits differ by rounding only, and
    // X's hit may be the nearer; without the margin X's test would be left out for such a ray.
    std::mt19937_64 rng(23);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Camera cam;
    cam.position = dvec3(0.3, -0.2, 0.1);
    cam.lookAt = dvec3(7.0, 3.0, 2.0);
    cam.up = dvec3(0, 0, 1);
    cam.fovYDegrees = 30.0;
    cam.width = 24;
    cam.height = 18;
    const RayGenerator gen(cam);
    for (int config = 0; config < 150; ++config) {
        const Ray ray = gen(int(u(rng) * cam.width), int(u(rng) * cam.height));
        const double near = 3.0 + 40.0 * u(rng), ry = 0.3 + 2.0 * u(rng), rx = ry * (0.1 + 0.8 * u(rng));
        SphereSet s;
        s.spheres.resize(2);
        s.spheres[0].centre = ray.origin + (near + ry) * ray.direction;
        s.spheres[0].radius = ry;
        s.spheres[1].centre = ray.origin + (near + rx) * ray.direction;
        s.spheres[1].radius = rx;
        s.spheres[1].colour = vec3(0.1f, 0.9f, 0.2f);
        expectBeamAndSametGiveTheReference(ObjectOctree::build(std::move(s)), cam, 1, "touching pair " + std::to_string(config));
    }
}

TEST(SphereRenderers, RenderingIntoAUsedFrameGivesTheFreshFrame) {
    // The sphere tracers write every field of every pixel and do not clear the frame first
    // (Frame::reshape), nor their per-tile buffers: a frame of the same size full of other
    // values, and a second render on the same thread, give the fresh frame's every field.
    const ObjectOctree t = ObjectOctree::build(makeRandomSpheres(800, 3, 0.05));
    const Camera cam = cameraFor(t, 61, 47);
    for (const char* name : {"reference", "samet", "beam"})
        for (int samples : {1, 4}) {
            RenderSettings rs;
            rs.threads = 2;
            rs.spheres.samples = samples;
            Frame fresh, used(cam.width, cam.height);
            for (std::size_t p = 0; p < used.rgba.size(); ++p) {
                used.rgba[p] = vec4(0.3f, float(p % 7), -1.0f, 0.25f);
                used.depth[p] = float(p);
                used.hitId[p] = std::uint32_t(p * 31);
                used.flags[p] = std::uint8_t(p);
            }
            makeRenderer(name)->renderSpheres(t, cam, rs, fresh);
            makeRenderer(name)->renderSpheres(t, Camera::framing(t.scene.bounds(), 61, 47, 45.0), rs, used);  // other rays first
            makeRenderer(name)->renderSpheres(t, cam, rs, used);
            const std::string what = std::string(name) + ", " + std::to_string(samples) + " samples";
            EXPECT_EQ(used.rgba, fresh.rgba) << what;
            EXPECT_EQ(used.depth, fresh.depth) << what;
            EXPECT_EQ(used.hitId, fresh.hitId) << what;
            EXPECT_EQ(used.flags, fresh.flags) << what;
        }
}

TEST(SphereRenderers, SupersamplingTracesTheRaysOfTheFinerGrid) {
    ObjectOctree t = ObjectOctree::build(makeSphereFlake(2));
    Camera cam = cameraFor(t, 40, 30), fine = cameraFor(t, 80, 60);
    RenderSettings rs, four;
    rs.spheres.bounces = 0;
    four = rs;
    four.spheres.samples = 4;
    Frame a, b, f;
    const RenderStats sa = makeRenderer("beam")->renderSpheres(t, cam, four, a);
    makeRenderer("samet")->renderSpheres(t, cam, four, b);
    const RenderStats sf = makeRenderer("reference")->renderSpheres(t, fine, rs, f);
    EXPECT_EQ(a.rgba, b.rgba);
    EXPECT_EQ(sa.hits, sf.hits);
    EXPECT_EQ(sa.pixels, 40u * 30u);
    EXPECT_EQ(sa.rays, sf.rays);
    for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) EXPECT_EQ(a.hitId[a.pixel(x, y)], f.hitId[f.pixel(2 * x, 2 * y)]);
    four.spheres.samples = 3;
    EXPECT_THROW(makeRenderer("beam")->renderSpheres(t, cam, four, a), UsageError);
}

TEST(SphereRenderers, WhittedRaysChangeTheMirrorsAndShadowsDarken) {
    ObjectOctree t = ObjectOctree::build(makeSphereFlake(2));
    Camera cam = cameraFor(t, 64, 48);
    RenderSettings flat, whitted;
    flat.spheres.bounces = 0;
    flat.shadows = false;
    Frame a, b;
    makeRenderer("samet")->renderSpheres(t, cam, flat, a);
    const RenderStats st = makeRenderer("samet")->renderSpheres(t, cam, whitted, b);
    EXPECT_EQ(a.hitId, b.hitId);
    EXPECT_NE(a.rgba, b.rgba);
    EXPECT_GT(st.secondaryRays, st.hits);
}

TEST(SphereRenderers, VoxelRenderersRefuseSphereScenesAndTheBruteForceVoxels) {
    ObjectOctree t = ObjectOctree::build(makeSphereFlake(1));
    Frame f;
    EXPECT_THROW(makeRenderer("full")->renderSpheres(t, cameraFor(t, 8, 8), {}, f), UsageError);
    Octree empty;
    EXPECT_THROW(makeBruteForceSphereRenderer()->render(empty, cameraFor(t, 8, 8), {}, f), UsageError);
    EXPECT_FALSE(makeBruteForceSphereRenderer()->drawsVoxels());
    // samet and beam draw both kinds: an empty voxel octree is all background.
    for (const char* name : {"samet", "beam"}) {
        EXPECT_TRUE(makeRenderer(name)->drawsVoxels());
        const RenderStats st = makeRenderer(name)->render(empty, cameraFor(t, 8, 8), {}, f);
        EXPECT_EQ(st.hits, 0u) << name;
        EXPECT_EQ(st.pixels, 64u) << name;
    }
}

TEST(SphereDistanceField, IsNegativeInsideAndCentredOnZero) {
    const SphereSet s = makeSphereFlake(1);
    const ScalarField f = sphereDistanceField(s, 65);
    auto [lo, hi] = f.validRange();
    EXPECT_FLOAT_EQ(lo, -hi);
    EXPECT_EQ(std::max({f.dims.x, f.dims.y, f.dims.z}), 65);
    EXPECT_THROW(sphereDistanceField(s, 2000, 1000), LimitError);
}

TEST(SphereVoxels, KeepTheColourOfTheSphereWhoseSurfaceIsNearest) {
    // A big red sphere and a small blue one overlapping it, a green one apart.
    SphereSet set;
    set.spheres = {{{0, 0, 0}, 1.0, {1.0f, 0.0f, 0.0f}, 0}, {{1.2, 0, 0}, 0.5, {0.0f, 0.0f, 1.0f}, 0}, {{0, 2.0, 0}, 0.4, {0.0f, 1.0f, 0.0f}, 0}};
    set.name = set.source = "three spheres";
    const Octree t = buildShellOctree(sphereDistanceField(set, (1 << 6) + 5), {6, 0.0, 0});
    const std::vector<std::uint32_t> colours = sphereColoursAtVoxels(t, set, 1);
    ASSERT_EQ(colours.size(), t.voxels().size());
    EXPECT_EQ(sphereColoursAtVoxels(t, set, 3), colours);
    const std::uint32_t red = packColour({1, 0, 0}), blue = packColour({0, 0, 1}), green = packColour({0, 1, 0});
    std::size_t n[3] = {0, 0, 0};
    const double h = t.voxelSize();
    t.forEachVoxel([&](const ivec3& cell, std::uint32_t v) {
        const dvec3 p = t.cubeOrigin + (dvec3(cell) + 0.5) * h;
        if (p.y > 1.3) {  // around the green sphere only
            EXPECT_EQ(colours[v], green);
            ++n[2];
        } else if (p.x < 0.6) {  // the red sphere's side of where the two surfaces cross (x = 0.7708)
            EXPECT_EQ(colours[v], red) << p.x << "," << p.y << "," << p.z;
            ++n[0];
        } else if (p.x > 1.0) {
            EXPECT_EQ(colours[v], blue) << p.x << "," << p.y << "," << p.z;
            ++n[1];
        }
    });
    EXPECT_GT(n[0], 500u);
    EXPECT_GT(n[1], 50u);
    EXPECT_GT(n[2], 50u);
}
