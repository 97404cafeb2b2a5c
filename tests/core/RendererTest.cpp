// Tests of the renderers (full, reference, reference-unquantized), the camera and the shading,
// on analytic scenes whose images are known: a sphere of radius 0.7 centred in [-1,1]^3, a
// torus and value noise.
#include "RenderTestUtil.h"

#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/render/Renderer.h"
#include "octrace/render/Shading.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

// The renderers that draw the voxel octree (samet and beam draw sphere scenes only).
static std::vector<std::string> voxelRendererNames() {
    std::vector<std::string> out;
    for (const std::string& n : octrace::rendererNames())
        if (octrace::makeRenderer(n)->drawsVoxels()) out.push_back(n);
    return out;
}
#include <sstream>

using namespace octrace;
using namespace octrace::test;


// ---------------------------------------------------------------------------------------------
// The fast renderer against the oracle

TEST(Renderer, FullAndReferenceGiveBitwiseIdenticalFrames) {
    const std::pair<std::string, const Octree*> trees[] = {
        {"sphere", &sphereTree()}, {"torus", &torusTree()}, {"noise", &noiseTree()}};
    for (const auto& [treeName, tree] : trees) {
        std::uint64_t hits = 0, pixels = 0;
        for (const NamedCamera& nc : allTestCameras(*tree)) {
            SCOPED_TRACE(treeName + ", camera " + nc.name);
            Frame full, ref;
            RenderStats sf = render("full", *tree, nc.camera, full);
            RenderStats sr = render("reference", *tree, nc.camera, ref);
            const FrameDiff d = diffFrames(full, ref);
            EXPECT_TRUE(d.identical()) << d.hitId << " hit ids, " << d.rgba << " colours, " << d.depth
                                       << " depths differ; first: " << d.first;
            EXPECT_EQ(sf.pixels, sr.pixels);
            EXPECT_EQ(sf.rays, sr.rays);
            EXPECT_EQ(sf.hits, sr.hits);
            hits += sf.hits;
            pixels += sf.pixels;
        }
        // Not vacuous: the cameras see both surface and background.
        EXPECT_GT(hits, pixels / 5) << treeName;
        EXPECT_LT(hits, pixels) << treeName;
    }
}

TEST(Renderer, ReferenceUnquantizedDiffersFromReferenceInAtMostATinyFractionOfPixels) {
    // Quantizing the ray moves its line by at most 2^-12 octree units, so it can change the hit
    // voxel only of rays that pass that close to a voxel edge or corner: in general position a
    // tiny fraction (in practice none in these images).
    //
    // An eye exactly on the octree lattice (the cube's centre, or its axis) is different: with
    // rational pixel offsets many rays then pass *exactly* through voxel edges. The quantized
    // ray resolves such ties by the documented half-open rule, while the unquantized reference
    // resolves them by the rounding of its double-precision end points; the two may pick the
    // neighbouring voxel. Those cameras are measured and reported separately, with a loose bound.
    const std::pair<std::string, const Octree*> trees[] = {
        {"sphere", &sphereTree()}, {"torus", &torusTree()}, {"noise", &noiseTree()}};
    std::size_t pixels = 0, differing = 0, latticePixels = 0, latticeDiffering = 0;
    for (const auto& [treeName, tree] : trees) {
        for (const NamedCamera& nc : generalTestCameras(*tree)) {
            Frame q, u;
            render("reference", *tree, nc.camera, q);
            render("reference-unquantized", *tree, nc.camera, u);
            const FrameDiff d = diffFrames(q, u);
            pixels += q.hitId.size();
            differing += d.hitId;
            EXPECT_LT(double(d.hitId), 0.005 * double(q.hitId.size())) << treeName << ", camera " << nc.name;
        }
        for (const NamedCamera& nc : latticeTestCameras(*tree)) {
            Frame q, u;
            render("reference", *tree, nc.camera, q);
            render("reference-unquantized", *tree, nc.camera, u);
            const FrameDiff d = diffFrames(q, u);
            latticePixels += q.hitId.size();
            latticeDiffering += d.hitId;
            std::cout << "[          ] eye on the lattice, " << treeName << ", " << nc.name << ": " << d.hitId << " of "
                      << q.hitId.size() << " pixels differ\n";
            EXPECT_LT(double(d.hitId), 0.06 * double(q.hitId.size())) << treeName << ", camera " << nc.name;
        }
    }
    std::cout << "[          ] quantization changes the hit voxel of " << differing << " of " << pixels
              << " pixels in general position, " << latticeDiffering << " of " << latticePixels
              << " with the eye on the lattice\n";
    EXPECT_LT(double(differing), 0.005 * double(pixels));
}

TEST(Renderer, FullAndReferenceAgreeAtDepthOneAndAtTheMaximumDepth) {
    // Depth 1: eight voxels; the root's children are voxels.
    {
        Octree t = buildShellOctree(makeAnalyticField("sphere", 9), {1, 0.0, 1});
        ASSERT_GT(t.voxels().size(), 0u);
        for (const NamedCamera& nc : allTestCameras(t)) {
            Frame a, b;
            render("full", t, nc.camera, a);
            render("reference", t, nc.camera, b);
            const FrameDiff d = diffFrames(a, b);
            EXPECT_TRUE(d.identical()) << "depth 1, " << nc.name << ": " << d.first;
        }
    }
    // Depth 14 (one voxel = one octree integer unit): two thin walls across a long bar of
    // samples. f = |x - 512.3| - 0.5 on 1025 x 2 x 2 samples of spacing 1: iso 0 at x = 511.8
    // and 512.8; the cube is 1024 wide, so the bar is 16 voxels thick at depth 14.
    {
        ScalarField f = sampleFunction("walls", ivec3(1025, 2, 2), dvec3(0.0), dvec3(1.0),
                                       [](const dvec3& p) { return float(std::abs(p.x - 512.3) - 0.5); });
        Octree t = buildShellOctree(f, {Octree::kMaxDepth, 0.0, 0});
        ASSERT_NO_THROW(t.validate());
        EXPECT_EQ(t.voxels().size(), 2u * 16u * 16u);
        const dvec3 target(512.3, 0.5, 0.5);
        const Camera cams[] = {
            makeCamera(target + dvec3(-3.0, 1.7, 2.2), target, {0, 0, 1}, 30, 64, 48),
            makeCamera(target + dvec3(2.5, -0.3, 0.4), target + dvec3(0, 0.1, -0.05), {0, 0, 1}, 40, 64, 48),
            makeCamera(dvec3(512.0, 0.5, 0.5), dvec3(530.0, 0.5, 0.5), {0, 0, 1}, 50, 33, 33),  // on the axis
        };
        for (const Camera& c : cams) {
            Frame a, b;
            RenderStats sa = render("full", t, c, a);
            render("reference", t, c, b);
            const FrameDiff d = diffFrames(a, b);
            EXPECT_TRUE(d.identical()) << "depth 14: " << d.hitId << " hit ids differ; " << d.first;
            EXPECT_GT(sa.hits, 0u);
        }
    }
}

TEST(Renderer, PlacesAnOffsetScaledSceneInWorldUnits) {
    // A sphere of radius 1.4 centred at (12, -1, 102), on a grid over [10,14] x [-3,1] x [100,104]:
    // the world-to-octree mapping must carry the origin and the scale.
    const dvec3 centre(12.0, -1.0, 102.0);
    ScalarField f = sampleFunction("offset sphere", ivec3(33), centre - 2.0, dvec3(0.125),
                                   [&](const dvec3& p) { return float(1.4 - glm::length(p - centre)); });
    Octree t = buildShellOctree(f, {7, 0.0, 0});
    const Camera cam = Camera::framing(cubeOf(t), 121, 91);
    Frame img;
    render("full", t, cam, img);
    double sx = 0, sy = 0;
    std::size_t n = 0;
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            if (img.hitId[img.pixel(x, y)] != kNoHit) {
                sx += x + 0.5;
                sy += y + 0.5;
                ++n;
            }
    ASSERT_GT(n, 500u);
    EXPECT_NEAR(sx / double(n), 0.5 * img.width, 0.5);
    EXPECT_NEAR(sy / double(n), 0.5 * img.height, 0.5);
    const double D = glm::length(cam.position - centre);
    EXPECT_NEAR(img.depth[img.pixel(60, 45)], D - 1.4, std::sqrt(3.0) * t.voxelSize());
    // A camera inside the sphere sees its wall at distance 1.4 all around (within a voxel diagonal).
    const Camera inside = makeCamera(centre, centre + dvec3(0.3, -1.0, 0.2), {0, 0, 1}, 80, 41, 41);
    Frame in;
    render("full", t, inside, in);
    for (std::size_t p = 0; p < in.depth.size(); ++p) {
        ASSERT_NE(in.hitId[p], kNoHit);
        EXPECT_NEAR(in.depth[p], 1.4, std::sqrt(3.0) * t.voxelSize() + 0.01);
    }
    Frame ref;
    render("reference", t, cam, ref);
    EXPECT_TRUE(diffFrames(img, ref).identical());
}

// ---------------------------------------------------------------------------------------------
// Determinism

TEST(Renderer, GivesBitwiseIdenticalFramesAndCountersForOneTwoAndSevenThreads) {
    for (const std::string& name : voxelRendererNames()) {
        SCOPED_TRACE(name);
        const Camera cam = Camera::framing(cubeOf(noiseTree()), 150, 110);  // tiles of 32: ragged edges
        Frame f1, f2, f7;
        RenderSettings s;
        s.threads = 1;
        RenderStats r1 = render(name, noiseTree(), cam, f1, s);
        s.threads = 2;
        RenderStats r2 = render(name, noiseTree(), cam, f2, s);
        s.threads = 7;
        RenderStats r7 = render(name, noiseTree(), cam, f7, s);
        for (const auto* pair : {&f2, &f7}) {
            const FrameDiff d = diffFrames(f1, *pair);
            EXPECT_TRUE(d.identical()) << d.first;
        }
        for (const RenderStats* r : {&r2, &r7}) {
            EXPECT_EQ(r->renderer, r1.renderer);
            EXPECT_EQ(r->pixels, r1.pixels);
            EXPECT_EQ(r->rays, r1.rays);
            EXPECT_EQ(r->hits, r1.hits);
            EXPECT_EQ(r->nodesVisited, r1.nodesVisited);
            EXPECT_EQ(r->raysCommonPath, r1.raysCommonPath);
            EXPECT_EQ(r->colourFilled, r1.colourFilled);
            EXPECT_EQ(r->missFilled, r1.missFilled);
        }
        EXPECT_EQ(r1.renderer, name);
    }
}

// ---------------------------------------------------------------------------------------------
// Geometry of the image

TEST(Renderer, CentresTheFramedSphereAndPutsItAtTheAnalyticDistance) {
    const Octree& t = sphereTree();
    const Camera cam = Camera::framing(cubeOf(t), 161, 121);  // odd: a pixel sits on the axis
    Frame f;
    render("full", t, cam, f);
    double sx = 0, sy = 0;
    std::size_t n = 0;
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x)
            if (f.hitId[f.pixel(x, y)] != kNoHit) {
                sx += x + 0.5;
                sy += y + 0.5;
                ++n;
            }
    ASSERT_GT(n, 1000u);
    // A sphere centred on the optical axis projects to a disc centred in the image.
    EXPECT_NEAR(sx / double(n), 0.5 * f.width, 0.5);
    EXPECT_NEAR(sy / double(n), 0.5 * f.height, 0.5);
    // The disc's radius: the sphere (radius 0.7) at distance D subtends asin(0.7 / D).
    const double D = glm::length(cam.position - dvec3(0.0));
    const double pixelsPerTan = 0.5 * f.height / std::tan(glm::radians(cam.fovYDegrees) * 0.5);
    const double discRadius = pixelsPerTan * std::tan(std::asin(0.7 / D));
    EXPECT_NEAR(std::sqrt(double(n) / M_PI), discRadius, 1.5);
    // The centre pixel looks straight at the centre: the sphere is D - 0.7 away. The depth is
    // where the ray enters the hit voxel, which holds the surface: at most a voxel diagonal off.
    const float centreDepth = f.depth[f.pixel(f.width / 2, f.height / 2)];
    const double diag = std::sqrt(3.0) * t.voxelSize();
    std::cout << "[          ] centre depth " << centreDepth << ", analytic " << D - 0.7 << ", voxel diagonal " << diag
              << "\n";
    EXPECT_NEAR(centreDepth, D - 0.7, diag);
}

TEST(Renderer, ReportsTheDistanceWhereTheRayEntersTheHitVoxel) {
    for (const Octree* tree : {&sphereTree(), &noiseTree()})
        for (const NamedCamera& nc : allTestCameras(*tree)) {
            SCOPED_TRACE(nc.name);
            Frame f;
            render("full", *tree, nc.camera, f);
            std::vector<ivec3> cells(tree->voxels().size());
            tree->forEachVoxel([&](const ivec3& c, std::uint32_t i) { cells[i] = c; });
            const double eps = 1e-3 * tree->voxelSize();
            std::size_t bad = 0;
            for (int y = 0; y < f.height; ++y)
                for (int x = 0; x < f.width; ++x) {
                    const std::size_t p = f.pixel(x, y);
                    if (f.hitId[p] == kNoHit) {
                        if (!std::isinf(f.depth[p])) ++bad;
                        continue;
                    }
                    const Ray r = nc.camera.primaryRay(x, y);
                    const Box3 b = tree->voxelBox(cells[f.hitId[p]]);
                    const dvec3 q = r.origin + r.direction * double(f.depth[p]);
                    // q lies in the box (closed, with rounding slack) and, unless the eye is in
                    // the box itself, on its surface.
                    bool inBox = true, onFace = false;
                    for (int a = 0; a < 3; ++a) {
                        inBox &= q[a] >= b.lo[a] - eps && q[a] <= b.hi[a] + eps;
                        onFace |= std::abs(q[a] - b.lo[a]) <= eps || std::abs(q[a] - b.hi[a]) <= eps;
                    }
                    if (!(f.depth[p] >= 0.0f) || !inBox || (!onFace && f.depth[p] > 0.0f)) ++bad;
                }
            EXPECT_EQ(bad, 0u);
        }
}

// ---------------------------------------------------------------------------------------------
// Shading

TEST(Renderer, ShadesEveryHitAsTwoSidedLambertWithTheLightInCameraSpace) {
    const Octree& t = noiseTree();
    const Camera cam = Camera::framing(cubeOf(t), 100, 80);
    RenderSettings s;
    s.lightCamera = dvec3(-0.3, 0.8, 0.5);
    s.colour = vec3(0.9f, 0.5f, 0.2f);
    Frame f;
    render("full", t, cam, f, s);
    // Camera space: x right, y up, z towards the viewer.
    dvec3 right, up, back;
    cam.basis(right, up, back);
    const dvec3 l = glm::normalize(s.lightCamera);
    const dvec3 light = glm::normalize(l.x * right + l.y * up + l.z * back);
    std::size_t hits = 0, bad = 0;
    for (std::size_t p = 0; p < f.hitId.size(); ++p) {
        if (f.hitId[p] == kNoHit) continue;
        ++hits;
        const dvec3 n(decodeNormal(t.voxels()[f.hitId[p]].normal));
        const double intensity = s.ambient + s.diffuse * std::abs(glm::dot(n, light));
        for (int c = 0; c < 3; ++c)
            if (std::abs(f.rgba[p][c] - s.colour[c] * intensity) > 1e-5) ++bad;
        if (f.rgba[p].a != 1.0f) ++bad;
    }
    EXPECT_GT(hits, 1000u);
    EXPECT_EQ(bad, 0u);
}

TEST(Renderer, LightsTheSphereBrightestWhereItFacesTheLightAndNeverAboveAmbientPlusDiffuse) {
    const Octree& t = sphereTree();
    const Camera cam = makeCamera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30, 101, 101);
    RenderSettings s;
    s.lightCamera = dvec3(0, 0, 1);  // from the viewer
    s.colour = vec3(1.0f);
    Frame f;
    render("full", t, cam, f, s);
    const float maximum = s.ambient + s.diffuse;
    ASSERT_EQ(maximum, 1.0f);
    float brightest = 0.0f;
    for (std::size_t p = 0; p < f.hitId.size(); ++p)
        if (f.hitId[p] != kNoHit) {
            EXPECT_LE(f.rgba[p].r, maximum + 1e-6f);
            EXPECT_GE(f.rgba[p].r, s.ambient - 1e-6f);
            brightest = std::max(brightest, f.rgba[p].r);
        }
    // Centre: the normal faces the light (and the viewer). The last hit pixel of the middle row:
    // the silhouette, where the normal is nearly perpendicular to the light.
    const int mid = f.height / 2;
    const float centre = f.rgba[f.pixel(f.width / 2, mid)].r;
    int edgeX = -1;
    for (int x = f.width / 2; x < f.width; ++x)
        if (f.hitId[f.pixel(x, mid)] != kNoHit) edgeX = x;
    ASSERT_GT(edgeX, f.width / 2);
    const float edge = f.rgba[f.pixel(edgeX, mid)].r;
    std::cout << "[          ] centre " << centre << ", silhouette " << edge << ", brightest " << brightest << "\n";
    EXPECT_GT(centre, 0.99f * maximum);
    // The axis runs between four voxels whose normals lean ~0.5 degrees off it: nothing is lit
    // noticeably more than the centre.
    EXPECT_GE(centre, brightest - 1e-3f);
    EXPECT_LT(edge, centre - 0.3f);

    // Two-sided: the light from behind the sphere lights it the same way.
    RenderSettings behind = s;
    behind.lightCamera = dvec3(0, 0, -1);
    Frame g;
    render("full", t, cam, g, behind);
    EXPECT_TRUE(diffFrames(f, g).identical());
}

TEST(Renderer, FillsMissesWithTheBackgroundColour) {
    RenderSettings s;
    s.background = vec4(0.1f, 0.2f, 0.3f, 0.25f);
    for (const std::string& name : voxelRendererNames()) {
        Frame f;
        const Camera cam = Camera::framing(cubeOf(torusTree()), 80, 60);
        render(name, torusTree(), cam, f, s);
        std::size_t misses = 0, bad = 0;
        for (std::size_t p = 0; p < f.hitId.size(); ++p) {
            if (f.hitId[p] != kNoHit) continue;
            ++misses;
            if (std::memcmp(&f.rgba[p], &s.background, sizeof(vec4)) != 0 || !std::isinf(f.depth[p])) ++bad;
        }
        EXPECT_GT(misses, 100u) << name;
        EXPECT_EQ(bad, 0u) << name;
        // The image's corner sees the background (the torus has a hole; corners are outside).
        EXPECT_EQ(f.hitId[0], kNoHit);
    }
}

TEST(Renderer, ColoursByHeightWithAKnownColormapAndRejectsAnUnknownOne) {
    const Octree& t = sphereTree();
    const Camera cam = makeCamera({5, 0, 0}, {0, 0, 0}, {0, 0, 1}, 30, 61, 61);
    RenderSettings s;
    s.colormap = "no-such-map";
    Frame f;
    EXPECT_THROW(render("full", t, cam, f, s), UsageError);
    EXPECT_THROW(colormap("no-such-map", 0.5f), UsageError);
    for (const std::string& name : colormapNames()) {
        s.colormap = name;
        ASSERT_NO_THROW(render("full", t, cam, f, s)) << name;
        // Looking along -x with z up: the top of the sphere gets the high end of the map.
        const int x = f.width / 2;
        int top = -1, bottom = -1;
        for (int y = 0; y < f.height; ++y)
            if (f.hitId[f.pixel(x, y)] != kNoHit) {
                if (top < 0) top = y;
                bottom = y;
            }
        ASSERT_GE(top, 0);
        const vec4 a = f.rgba[f.pixel(x, top)], b = f.rgba[f.pixel(x, bottom)];
        EXPECT_GT(glm::length(dvec3(a - b)), 0.05) << name;
    }
    EXPECT_GE(colormapNames().size(), 1u);
}

// ---------------------------------------------------------------------------------------------
// Camera

TEST(Camera, RejectsDegenerateGeometryAsUsageErrors) {
    Camera ok = makeCamera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30, 64, 48);
    EXPECT_NO_THROW(ok.validate());
    Camera c = ok;
    c.lookAt = c.position;
    EXPECT_THROW(c.validate(), UsageError);
    c = ok;
    c.up = dvec3(0, 0, 1);  // along the view direction
    EXPECT_THROW(c.validate(), UsageError);
    c.up = dvec3(0, 0, -3);  // against it
    EXPECT_THROW(c.validate(), UsageError);
    c.up = dvec3(0.0);
    EXPECT_THROW(c.validate(), UsageError);
    for (double fov : {0.0, 180.0, -10.0, 200.0, std::numeric_limits<double>::quiet_NaN()}) {
        c = ok;
        c.fovYDegrees = fov;
        EXPECT_THROW(c.validate(), UsageError) << fov;
    }
    for (double fov : {0.5, 179.0}) {
        c = ok;
        c.fovYDegrees = fov;
        EXPECT_NO_THROW(c.validate()) << fov;
    }
    c = ok;
    c.width = 0;
    EXPECT_THROW(c.validate(), UsageError);
    c = ok;
    c.height = -2;
    EXPECT_THROW(c.validate(), UsageError);
    c = ok;
    c.position = dvec3(std::numeric_limits<double>::quiet_NaN(), 0, 0);
    EXPECT_THROW(c.validate(), UsageError);
    // Rendering validates the camera first.
    Frame f;
    c = ok;
    c.lookAt = c.position;
    EXPECT_THROW(render("full", sphereTree(), c, f), UsageError);
}

TEST(Camera, PutsPixelCentresAtHalfIntegersWithRowZeroAtTheTop) {
    const Camera c = makeCamera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40, 81, 61);
    // The centre pixel of an odd-sized image looks exactly at lookAt.
    const Ray centre = c.primaryRay(40, 30);
    EXPECT_EQ(centre.direction, dvec3(0, 0, -1));
    // Row 0 is at the top (+y here), column 0 on the left (-x).
    const Ray topLeft = c.primaryRay(0, 0);
    EXPECT_LT(topLeft.direction.x, 0.0);
    EXPECT_GT(topLeft.direction.y, 0.0);
    EXPECT_NEAR(glm::length(topLeft.direction), 1.0, 1e-12);
    // Pixel centres at +0.5: the top row's centre is half a pixel below the top edge of the
    // vertical field of view.
    const Ray top = c.primaryRay(40, 0);
    const double tanTop = top.direction.y / -top.direction.z;
    EXPECT_NEAR(tanTop, std::tan(glm::radians(20.0)) * (1.0 - 1.0 / 61), 1e-12);
    // Mirror-symmetric pixels give mirror-symmetric rays; square pixels.
    const Ray a = c.primaryRay(3, 7), b = c.primaryRay(77, 53);
    EXPECT_NEAR(a.direction.x, -b.direction.x, 1e-12);
    EXPECT_NEAR(a.direction.y, -b.direction.y, 1e-12);
    const Ray r0 = c.primaryRay(40, 30), rx = c.primaryRay(41, 30), ry = c.primaryRay(40, 29);
    EXPECT_NEAR(rx.direction.x / -rx.direction.z, ry.direction.y / -ry.direction.z, 1e-12);
    EXPECT_EQ(r0.origin, c.position);
}

TEST(Camera, FramesTheWholeBoxFromTheSouthEastAbove) {
    const Box3 box{dvec3(-3, 10, 0.5), dvec3(5, 12, 1.5)};
    for (auto [w, h] : {std::pair{640, 480}, std::pair{300, 600}, std::pair{100, 100}}) {
        const Camera c = Camera::framing(box, w, h, 35.0);
        ASSERT_NO_THROW(c.validate());
        const dvec3 from = c.position - box.centre();
        EXPECT_GT(from.x, 0.0);
        EXPECT_LT(from.y, 0.0);
        EXPECT_GT(from.z, 0.0);
        EXPECT_EQ(c.lookAt, box.centre());
        dvec3 right, up, back;
        c.basis(right, up, back);
        const double th = std::tan(glm::radians(35.0) * 0.5), aspect = double(w) / h;
        for (int k = 0; k < 8; ++k) {
            const dvec3 p((k & 4) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 1) ? box.hi.z : box.lo.z);
            const dvec3 v = p - c.position;
            const double z = -glm::dot(v, back);
            ASSERT_GT(z, 0.0);
            EXPECT_LE(std::abs(glm::dot(v, right) / z), th * aspect) << w << "x" << h << " corner " << k;
            EXPECT_LE(std::abs(glm::dot(v, up) / z), th) << w << "x" << h << " corner " << k;
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Stats and the renderer registry

TEST(Renderer, CountsPixelsRaysAndHitsConsistently) {
    for (const std::string& name : voxelRendererNames()) {
        SCOPED_TRACE(name);
        for (const NamedCamera& nc : allTestCameras(noiseTree())) {
            Frame f;
            const RenderStats s = render(name, noiseTree(), nc.camera, f);
            EXPECT_EQ(s.renderer, name);
            EXPECT_EQ(s.pixels, std::uint64_t(nc.camera.width) * std::uint64_t(nc.camera.height));
            EXPECT_LE(s.rays, s.pixels);
            if (tracesRays(name)) {
                EXPECT_LE(s.hits, s.rays);
                EXPECT_GT(s.rays, 0u) << nc.name;
            } else {
                EXPECT_EQ(s.rays, 0u);
                EXPECT_GT(s.voxelsSplatted, 0u);
            }
            EXPECT_EQ(s.hits, hitCount(f)) << nc.name;
            EXPECT_GT(s.nodesVisited, 0u);
            EXPECT_GE(s.renderMs, 0.0);
        }
        // Looking away from the cube: no ray meets it, nothing is hit.
        Frame f;
        const RenderStats away = render(name, noiseTree(), makeCamera({0, 0, 3}, {0, 0, 10}, {0, 1, 0}, 30, 40, 30), f);
        EXPECT_EQ(away.pixels, 1200u);
        EXPECT_EQ(away.rays, 0u);
        EXPECT_EQ(away.hits, 0u);
        EXPECT_EQ(hitCount(f), 0u);
        // From inside the cube every ray meets it.
        const RenderStats inside = render(name, noiseTree(), generalTestCameras(noiseTree())[1].camera, f);
        if (tracesRays(name)) {
            EXPECT_EQ(inside.rays, inside.pixels);
        }
    }
}

TEST(Renderer, NeverCountsMoreHitsThanRaysForRaysGrazingACubeFace) {
    // A plane x = 0.3 that reaches every face of the cube, seen by rays that run parallel to
    // the top face y = 1, a hair inside it: the quantized ray is rounded onto the face (outside,
    // the cells being half-open), the unquantized one stays inside and hits the plane.
    const ScalarField f = sampleFunction("plane", ivec3(33), dvec3(-1.0), dvec3(2.0 / 32),
                                         [](const dvec3& p) { return float(p.x - 0.3); });
    const Octree t = buildShellOctree(f, {6, 0.0, 1});
    for (double eps : {1e-9, 1e-7, 1e-5}) {
        const Camera c = makeCamera({-2, 1 - eps, 0.1}, {5, 1 - eps, 0.1}, {0, 0, 1}, 20, 9, 9);
        for (const std::string& name : voxelRendererNames()) {
            Frame img;
            const RenderStats s = render(name, t, c, img);
            if (tracesRays(name)) {
                EXPECT_LE(s.hits, s.rays) << name << ", " << eps << " below the face";
            }
            EXPECT_EQ(s.hits, hitCount(img)) << name;
            EXPECT_GT(s.hits, 0u) << name;
        }
    }
}

TEST(Renderer, MakeRendererKnowsItsNamesAndRejectsOthers) {
    const auto names = rendererNames();
    for (const char* expected : {"full", "reference", "reference-unquantized"})
        EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
    for (const auto& n : names) EXPECT_EQ(makeRenderer(n)->name(), n);
    try {
        makeRenderer("fastest");
        ADD_FAILURE() << "no exception";
    } catch (const UsageError& e) {
        EXPECT_NE(std::string(e.what()).find("fastest"), std::string::npos);
        EXPECT_NE(std::string(e.what()).find("reference"), std::string::npos);
    }
}
