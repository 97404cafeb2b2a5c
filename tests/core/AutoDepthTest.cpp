// `depth` auto (build/AutoDepth.h) and the tight framing of the default camera (Camera::fit).
#include "octrace/build/AnalyticField.h"
#include "octrace/build/AutoDepth.h"
#include "octrace/render/Camera.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace octrace;

TEST(AutoDepth, AGridOfTwoToTheNCellsGetsDepthNExactly) {
    for (int n : {1, 4, 6, 9, 14}) EXPECT_EQ(shallowestDepthFor(2.0, 2.0 / double(1 << n)), n) << n;
    // One cell more than 2^n needs the next depth; a voxel larger than the spacing is never chosen.
    EXPECT_EQ(shallowestDepthFor(65.0, 1.0), 7);
    EXPECT_EQ(shallowestDepthFor(63.0, 1.0), 6);
    const ScalarField sphere = makeAnalyticField("sphere", 65);
    const DepthChoice c = depthForField(sphere);
    EXPECT_EQ(c.depth, 6);
    EXPECT_NE(c.reason.find("median sample spacing 0.03125 along"), std::string::npos) << c.reason;
    EXPECT_EQ(depthForField(makeAnalyticField("sphere", 129)).depth, 7);
}

TEST(AutoDepth, AnUnevenAxisIsJudgedByItsMedianStepNotItsFinest) {
    // 33 levels like an ocean's: 8 fine steps of 1 at the top, then 24 steps of 10. The cube's
    // side is the x extent, 640 (spacing 10); the finest level (1) would ask for depth 10.
    ScalarField f;
    f.dims = ivec3(65, 65, 33);
    f.spacing = dvec3(10.0, 10.0, 1.0);
    std::vector<double> z;
    double at = -248.0;
    for (int k = 0; k < 33; ++k) {
        z.push_back(at);
        at += k < 24 ? 10.0 : 1.0;
    }
    f.coords[2] = z;
    EXPECT_DOUBLE_EQ(medianSpacing(f, 2), 10.0);
    EXPECT_DOUBLE_EQ(medianSpacing(f, 0), 10.0);
    EXPECT_EQ(depthForField(f).depth, 6);  // 640 / 2^6 = 10
    // An even number of steps: the mean of the middle two.
    ScalarField g;
    g.dims = ivec3(2, 2, 5);
    g.coords[2] = {0.0, 1.0, 3.0, 6.0, 10.0};  // steps 1, 2, 3, 4
    EXPECT_DOUBLE_EQ(medianSpacing(g, 2), 2.5);
}

TEST(AutoDepth, GeometryGetsTheVoxelNearestOnePixel) {
    EXPECT_EQ(depthForPixel(1024.0, 1.0).depth, 10);
    EXPECT_EQ(depthForPixel(1024.0, 1.3).depth, 10);  // 1.3 pixels' voxel: 2^10 gives 0.77 px
    EXPECT_EQ(depthForPixel(1024.0, 1.5).depth, 9);   // 2^9 gives 1.33 px
    EXPECT_EQ(depthForPixel(1.0, 1.0).depth, 1);      // clamped
    EXPECT_THROW(depthForPixel(1.0, 0.0), Error);
}

namespace {

/// The rectangle (fractions of the image) that the box's corners project to.
std::array<double, 4> projected(const Camera& c, const Box3& b) {
    const RayGenerator rays(c);
    std::array<double, 4> r{1e300, 1e300, -1e300, -1e300};
    for (int k = 0; k < 8; ++k) {
        const dvec3 p((k & 4) ? b.hi.x : b.lo.x, (k & 2) ? b.hi.y : b.lo.y, (k & 1) ? b.hi.z : b.lo.z);
        const dvec3 o = p - rays.eye();
        double px = 0.0, py = 0.0;
        rays.toPixel(glm::dot(o, rays.right()), glm::dot(o, rays.up()), glm::dot(o, rays.back()), px, py);
        r[0] = std::min(r[0], px / c.width);
        r[1] = std::min(r[1], py / c.height);
        r[2] = std::max(r[2], px / c.width);
        r[3] = std::max(r[3], py / c.height);
    }
    return r;
}

}  // namespace

TEST(CameraFit, TheBoxFillsTheFrameCentredFromAnyDirection) {
    const Box3 slab{dvec3(-200.0, -100.0, -25.0), dvec3(200.0, 100.0, 0.0)};  // a thin ocean slab
    const Box3 cube{dvec3(0.0), dvec3(1.0)};
    for (const Box3& b : {slab, cube})
        for (const dvec3& dir : {Camera::obliqueDirection(), dvec3(0.0, -0.82, 0.57), dvec3(0.0, -1.0, 0.0)})
            for (const auto& [w, h] : {std::pair{160, 120}, std::pair{90, 200}}) {
                const Camera c = Camera::fit(b, w, h, 30.0, dir, dvec3(0.0, 0.0, 1.0));
                c.validate();
                const auto r = projected(c, b);
                EXPECT_GE(r[0], -1e-9);
                EXPECT_GE(r[1], -1e-9);
                EXPECT_LE(r[2], 1.0 + 1e-9);
                EXPECT_LE(r[3], 1.0 + 1e-9);
                // One pair of sides at 92 % of the frame, and the projection centred.
                EXPECT_NEAR(std::max(r[2] - r[0], r[3] - r[1]), 0.92, 1e-6);
                EXPECT_NEAR(r[0] + r[2], 1.0, 1e-6);
                EXPECT_NEAR(r[1] + r[3], 1.0, 1e-6);
                EXPECT_NEAR(glm::dot(glm::normalize(c.position - c.lookAt), glm::normalize(dir)), 1.0, 1e-12);
            }
    // The old framing leaves the slab's projection off centre and smaller.
    const auto old = projected(Camera::framing(slab, 160, 120), slab);
    EXPECT_LT(std::max(old[2] - old[0], old[3] - old[1]), 0.92);
}

TEST(CameraFit, APixelsFootprintIsTheViewHeightAtTheLookAtPointOverTheRows) {
    Camera c;
    c.position = dvec3(0.0, 0.0, 10.0);
    c.lookAt = dvec3(0.0);
    c.fovYDegrees = 90.0;
    c.height = 100;
    EXPECT_NEAR(c.pixelFootprint(), 20.0 / 100.0, 1e-12);
    c.projection = Camera::Projection::Orthographic;
    c.orthoHeight = 5.0;
    EXPECT_NEAR(c.pixelFootprint(), 0.05, 1e-12);
}
