// The direct (object-order) renderers against the reference traversal, and the orthographic
// projection for every renderer.
#include "RenderTestUtil.h"

#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace octrace;
using namespace octrace::test;

namespace {

Camera orthographic(Camera c) {
    c.frameOrthographic(Box3{dvec3(-1.0), dvec3(1.0)});
    return c;
}

/// The test cameras, each also as an orthographic camera looking the same way.
std::vector<NamedCamera> camerasBothProjections(const Octree& t) {
    std::vector<NamedCamera> cams = allTestCameras(t);
    const std::size_t n = cams.size();
    for (std::size_t i = 0; i < n; ++i) cams.push_back({cams[i].name + ", orthographic", orthographic(cams[i].camera)});
    return cams;
}

/// Independent slab test: does the world ray meet the closed box?
bool rayMeetsBox(const Ray& r, const Box3& b) {
    double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
        if (r.direction[a] == 0.0) {
            if (r.origin[a] < b.lo[a] || r.origin[a] > b.hi[a]) return false;
            continue;
        }
        double u = (b.lo[a] - r.origin[a]) / r.direction[a], v = (b.hi[a] - r.origin[a]) / r.direction[a];
        if (u > v) std::swap(u, v);
        t0 = std::max(t0, u);
        t1 = std::min(t1, v);
    }
    // Relative slack: the renderer's slab test computes with the reciprocal of the direction.
    return t0 <= t1 * (1.0 + 1e-12) + 1e-12;
}

struct Agreement {
    std::uint64_t either = 0, both = 0, sameVoxel = 0;
    double maxDepthError = 0.0;
};

Agreement agreement(const Frame& a, const Frame& ref) {
    Agreement g;
    for (std::size_t i = 0; i < a.hitId.size(); ++i) {
        const bool h = a.hitId[i] != kNoHit, r = ref.hitId[i] != kNoHit;
        g.either += h || r;
        g.both += h && r;
        g.sameVoxel += h && a.hitId[i] == ref.hitId[i];
        if (h && r) g.maxDepthError = std::max(g.maxDepthError, double(std::abs(a.depth[i] - ref.depth[i])));
    }
    return g;
}

}  // namespace

TEST(DirectRenderers, AgreeWithTheReferenceOnHitsVoxelsAndDepthsInBothProjections) {
    const std::pair<std::string, const Octree*> trees[] = {
        {"sphere", &sphereTree()}, {"torus", &torusTree()}, {"noise", &noiseTree()}};
    for (const auto& [treeName, tree] : trees) {
        const double diagonal = tree->voxelSize() * std::sqrt(3.0);
        std::uint64_t seen = 0;
        for (const NamedCamera& nc : camerasBothProjections(*tree)) {
            // Eyes on the octree lattice send rays exactly through voxel edges, where the
            // direct renderers' closed boxes and the reference's half-open cells may pick
            // different neighbours, and a ray running along a face between two columns may
            // meet them at any depth: only hit/miss agreement is asked of those.
            const bool lattice = nc.name.find("along") != std::string::npos || nc.name.find("centre") != std::string::npos;
            SCOPED_TRACE(treeName + ", camera " + nc.name);
            Frame ref;
            render("reference", *tree, nc.camera, ref);
            for (const char* name : {"direct", "direct-f2b"}) {
                Frame f;
                render(name, *tree, nc.camera, f);
                const Agreement g = agreement(f, ref);
                seen += g.either;
                // The direct renderers draw the pixel's own ray's first voxel: they can differ
                // from the quantized reference only where a ray passes within rounding of a
                // voxel edge (and, for the lattice cameras, exactly through edges).
                EXPECT_GE(double(g.both), 0.999 * double(g.either)) << name << ": " << g.both << " of " << g.either;
                EXPECT_GE(double(g.sameVoxel), (lattice ? 0.9 : 0.99) * double(g.either)) << name;
                if (!lattice) {
                    EXPECT_LE(g.maxDepthError, diagonal) << name;
                }
            }
        }
        EXPECT_GT(seen, 0u) << treeName;
    }
}

TEST(DirectRenderers, BackToFrontAndFrontToBackGiveTheSameFrameBitForBit) {
    // The two visit the voxels in exactly reverse orders; where two voxels cover a pixel centre
    // (on their shared edge), the last written back to front is the first written front to back.
    for (const Octree* tree : {&sphereTree(), &torusTree(), &noiseTree()})
        for (const NamedCamera& nc : camerasBothProjections(*tree)) {
            SCOPED_TRACE(nc.name);
            Frame b2f, f2b;
            render("direct", *tree, nc.camera, b2f);
            render("direct-f2b", *tree, nc.camera, f2b);
            const FrameDiff d = diffFrames(b2f, f2b);
            EXPECT_TRUE(d.identical()) << d.first;
        }
}

TEST(DirectRenderers, DrawAVoxelOnlyOnPixelsWhoseRayMeetsItsBoxAndAtWhereTheRayEntersIt) {
    const Octree& tree = noiseTree();
    for (const NamedCamera& nc : camerasBothProjections(tree)) {
        SCOPED_TRACE(nc.name);
        Frame f;
        render("direct", tree, nc.camera, f);
        const RayGenerator rays(nc.camera);
        std::vector<ivec3> cellOf(tree.voxels().size());
        tree.forEachVoxel([&](const ivec3& cell, std::uint32_t v) { cellOf[v] = cell; });
        std::size_t checked = 0;
        for (int y = 0; y < f.height; ++y)
            for (int x = 0; x < f.width; ++x) {
                const std::size_t p = f.pixel(x, y);
                if (f.hitId[p] == kNoHit) {
                    EXPECT_TRUE(std::isinf(f.depth[p]));
                    continue;
                }
                const Ray r = rays(x, y);
                const Box3 box = tree.voxelBox(cellOf[f.hitId[p]]);
                ASSERT_TRUE(rayMeetsBox(r, box)) << "pixel " << x << "," << y;
                // The depth is the distance to the box along the ray.
                const dvec3 at = r.origin + double(f.depth[p]) * r.direction;
                for (int a = 0; a < 3; ++a) {
                    EXPECT_GE(at[a], box.lo[a] - 1e-5);
                    EXPECT_LE(at[a], box.hi[a] + 1e-5);
                }
                EXPECT_EQ(f.flags[p], Frame::kSplatted);
                ++checked;
            }
        EXPECT_GT(checked, 0u);
    }
}

TEST(DirectRenderers, FrontToBackSkipsOccludedSubtrees) {
    const Camera cam = Camera::framing(cubeOf(noiseTree()), 160, 120);
    Frame a, b;
    const RenderStats b2f = render("direct", noiseTree(), cam, a);
    const RenderStats f2b = render("direct-f2b", noiseTree(), cam, b);
    EXPECT_LT(f2b.nodesVisited, b2f.nodesVisited / 2) << f2b.nodesVisited << " vs " << b2f.nodesVisited;
    EXPECT_LT(f2b.voxelsSplatted, b2f.voxelsSplatted);
    EXPECT_EQ(f2b.hits, b2f.hits);
    EXPECT_FALSE(makeRenderer("direct")->tracesRays());
    EXPECT_EQ(b2f.rays, 0u);
}

// ---------------------------------------------------------------------------------------------
// Orthographic projection

TEST(Camera, OrthographicRaysAreParallelAndStartOnTheViewPlaneInAWindowOfTheGivenHeight) {
    Camera c = makeCamera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30, 40, 20);
    c.projection = Camera::Projection::Orthographic;
    c.orthoHeight = 2.0;
    const Ray topLeft = c.primaryRay(0, 0), bottomRight = c.primaryRay(39, 19);
    EXPECT_EQ(topLeft.direction, dvec3(0, 0, -1));
    EXPECT_EQ(bottomRight.direction, dvec3(0, 0, -1));
    // Pixel size 2/20 = 0.1: the centre of the top-left pixel is half a pixel in from (-2, 1).
    EXPECT_NEAR(topLeft.origin.x, -2.0 + 0.05, 1e-12);
    EXPECT_NEAR(topLeft.origin.y, 1.0 - 0.05, 1e-12);
    EXPECT_NEAR(bottomRight.origin.x, 2.0 - 0.05, 1e-12);
    EXPECT_NEAR(bottomRight.origin.y, -1.0 + 0.05, 1e-12);
    EXPECT_EQ(topLeft.origin.z, 5.0);
    c.orthoHeight = 0.0;
    EXPECT_THROW(c.validate(), UsageError);
    c.orthoHeight = std::numeric_limits<double>::quiet_NaN();
    EXPECT_THROW(c.validate(), UsageError);
}

TEST(Camera, FrameOrthographicShowsTheWholeBoxWithItsCornersInFrontOfTheViewPlane) {
    const Box3 box{dvec3(-1, -2, 0), dvec3(3, 1, 0.5)};
    // The eye starts inside the box: the view plane must be moved back.
    Camera c = makeCamera(dvec3(0.5, 0, 0.2), dvec3(1, 1, 0.3), dvec3(0, 0, 1), 30, 64, 48);
    c.frameOrthographic(box);
    ASSERT_TRUE(c.orthographic());
    dvec3 right, up, back;
    c.basis(right, up, back);
    const double halfW = 0.5 * c.orthoHeight * 64.0 / 48.0;
    for (int k = 0; k < 8; ++k) {
        const dvec3 p((k & 4) ? box.hi.x : box.lo.x, (k & 2) ? box.hi.y : box.lo.y, (k & 1) ? box.hi.z : box.lo.z);
        const dvec3 o = p - c.position;
        EXPECT_LT(glm::dot(o, back), 0.0) << "corner " << k << " behind the view plane";
        EXPECT_LE(std::abs(glm::dot(p - c.lookAt, up)), 0.5 * c.orthoHeight);
        EXPECT_LE(std::abs(glm::dot(p - c.lookAt, right)), halfW);
    }
}

TEST(Renderer, FullAndReferenceGiveBitwiseIdenticalFramesUnderOrthographicProjection) {
    for (const Octree* tree : {&sphereTree(), &noiseTree()})
        for (const NamedCamera& nc : allTestCameras(*tree)) {
            SCOPED_TRACE(nc.name);
            const Camera cam = orthographic(nc.camera);
            Frame full, ref, exact;
            // full skips pixels outside the cube's projected outline; the reference does not:
            // the same rays must meet the cube.
            const RenderStats sf = render("full", *tree, cam, full);
            const RenderStats sr = render("reference", *tree, cam, ref);
            EXPECT_EQ(sf.rays, sr.rays);
            render("area-exact", *tree, cam, exact);
            const FrameDiff d = diffFrames(full, ref), e = diffFrames(exact, full);
            EXPECT_TRUE(d.identical()) << d.first;
            EXPECT_TRUE(e.identical()) << e.first;
            EXPECT_GT(hitCount(full), 0u);
        }
}
