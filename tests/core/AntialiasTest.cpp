// Antialiasing (renderAntialiased, Camera::sampleOffset): every voxel renderer draws each
// sample exactly, and the samples are averaged with their alpha.
#include "../TestScale.h"
#include "RenderTestUtil.h"

#include "octrace/render/Renderer.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

using namespace octrace;
using namespace octrace::test;

namespace {

RenderSettings withSamples(int samples) {
    RenderSettings s;
    s.spheres.samples = samples;
    return s;
}

}  // namespace

TEST(Antialias, AnOffsetMovesTheRayWithinThePixelAndToPixelFollowsIt) {
    for (const NamedCamera& nc : generalTestCameras(sphereTree())) {
        SCOPED_TRACE(nc.name);
        Camera right = nc.camera, left = nc.camera;
        right.sampleOffset = dvec2(0.5, 0.5);
        left.sampleOffset = dvec2(-0.5, -0.5);
        const RayGenerator r(right), l(left), c(nc.camera);
        // The right edge of pixel (x, y) is the left edge of pixel (x + 1, y + 1), bit for bit.
        for (int y = 0; y + 1 < nc.camera.height; y += 7)
            for (int x = 0; x + 1 < nc.camera.width; x += 5) {
                const Ray a = r(x, y), b = l(x + 1, y + 1);
                EXPECT_EQ(a.direction, b.direction);
                EXPECT_EQ(a.origin, b.origin);
            }
        // A point on a sample's ray projects to the centre of its pixel in that camera, and half
        // a pixel away from it in the unshifted one.
        dvec3 rt, up, back;
        nc.camera.basis(rt, up, back);
        const Ray ray = r(10, 20);
        const dvec3 p = ray.origin + 1.7 * ray.direction - nc.camera.position;
        double px = 0, py = 0;
        r.toPixel(glm::dot(p, rt), glm::dot(p, up), glm::dot(p, back), px, py);
        EXPECT_NEAR(px, 10.5, 1e-9);
        EXPECT_NEAR(py, 20.5, 1e-9);
        c.toPixel(glm::dot(p, rt), glm::dot(p, up), glm::dot(p, back), px, py);
        EXPECT_NEAR(px, 11.0, 1e-9);
        EXPECT_NEAR(py, 21.0, 1e-9);
    }
    Camera bad = Camera::framing(cubeOf(sphereTree()), 40, 30);
    bad.sampleOffset = dvec2(0.0, 0.75);
    EXPECT_THROW(bad.validate(), UsageError);
}

TEST(Antialias, OneSampleIsTheRenderItselfAndANonSquareCountIsRefused) {
    const Camera cam = Camera::framing(cubeOf(sphereTree()), 90, 70);
    Frame plain, one;
    render("full", sphereTree(), cam, plain);
    renderAntialiased(*makeRenderer("full"), sphereTree(), cam, withSamples(1), one);
    EXPECT_TRUE(diffFrames(plain, one).identical());
    for (int bad : {0, 2, 3, 289}) EXPECT_THROW(renderAntialiased(*makeRenderer("full"), sphereTree(), cam, withSamples(bad), one), UsageError) << bad;
}

TEST(Antialias, EveryExactRendererGivesTheReferencesAveragedFrameByteForByte) {
    const std::pair<std::string, const Octree*> trees[] = {{"sphere", &sphereTree()}, {"torus", &torusTree()}};
    for (const auto& [treeName, tree] : trees)
        for (const NamedCamera& nc : generalTestCameras(*tree))
            for (int samples : {4, 9}) {
                if (samples == 9 && testutil::testScale() < 1.0) continue;  // the sanitizer run: 4 only
                SCOPED_TRACE(treeName + ", " + nc.name + ", samples " + std::to_string(samples));
                const RenderSettings s = withSamples(samples);
                Frame ref;
                const RenderStats rs = renderAntialiased(*makeRenderer("reference"), *tree, nc.camera, s, ref);
                EXPECT_EQ(rs.pixels, std::uint64_t(nc.camera.width) * std::uint64_t(nc.camera.height));
                for (const char* name : {"full", "tile", "linear-exact", "area-exact", "direct", "direct-f2b", "beam", "samet"}) {
                    SCOPED_TRACE(name);
                    Frame f;
                    RenderSettings threads = s;
                    threads.threads = samples == 4 ? 1 : 3;
                    renderAntialiased(*makeRenderer(name), *tree, nc.camera, threads, f);
                    const FrameDiff d = diffFrames(f, ref);
                    EXPECT_TRUE(d.identical()) << d.hitId << " hit ids, " << d.rgba << " colours, " << d.depth << " depths differ";
                }
            }
}

TEST(Antialias, ThePixelIsTheAlphaWeightedMeanOfItsSamplesAndEdgesArePartlyCovered) {
    const Octree& tree = sphereTree();
    const Camera cam = Camera::framing(cubeOf(tree), 200, 150);
    RenderSettings s = withSamples(4);
    s.background = vec4(0.0f);  // transparent: coverage shows in alpha
    Frame aa;
    renderAntialiased(*makeRenderer("full"), tree, cam, s, aa);
    // The four samples drawn one by one with their offsets.
    std::vector<Frame> samples(4);
    for (int b = 0; b < 2; ++b)
        for (int a = 0; a < 2; ++a) {
            Camera c = cam;
            c.sampleOffset = dvec2(a * 0.5 - 0.25, b * 0.5 - 0.25);
            makeRenderer("reference")->render(tree, c, s, samples[std::size_t(b * 2 + a)]);
        }
    std::size_t partial = 0, covered = 0, mismatched = 0;
    for (std::size_t i = 0; i < aa.rgba.size(); ++i) {
        vec4 sum(0.0f);
        for (const Frame& f : samples) sum += vec4(vec3(f.rgba[i]) * f.rgba[i].a, f.rgba[i].a);
        const vec4 want = sum.a > 0.0f ? vec4(vec3(sum) / sum.a, sum.a / 4.0f) : vec4(0.0f);
        mismatched += glm::any(glm::greaterThan(glm::abs(aa.rgba[i] - want), vec4(1e-6f)));
        partial += aa.rgba[i].a > 0.0f && aa.rgba[i].a < 1.0f;
        covered += aa.rgba[i].a > 0.0f;
        // Depth and hit are the first (top-left) sample's.
        EXPECT_EQ(aa.hitId[i], samples[0].hitId[i]);
    }
    EXPECT_EQ(mismatched, 0u);
    // Most pixels along the silhouette (a disc of `covered` pixels has a rim of about
    // 2 sqrt(pi covered)) are partly covered.
    EXPECT_GT(double(partial), std::sqrt(M_PI * double(covered))) << partial << " of " << covered;
}
