// Tests of samet and beam on the voxel octree: per ray (traverseSamet) against the reference
// traversal on random, grazing and lattice rays, and as renderers against the reference's
// frames on the analytic scenes, on a tree with coarse leaves, with perspective and
// orthographic cameras, eyes on split planes, and for any thread count.
#include "RenderTestUtil.h"
#include "TraversalTestUtil.h"

#include "octrace/build/CityVoxelizer.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

using namespace octrace;
using namespace octrace::test;
using namespace octrace::testutil;

namespace {

/// Samet against the reference for one ray; fills `why` on a mismatch.
bool sametAgrees(const Octree& t, const dvec3& o, const dvec3& d, std::uint64_t& hits, std::string& why) {
    const QuantizedRay q = quantizeRay(o, d);
    TraversalCounters c1, c2;
    const TraversalHit a = traverseSamet(t, q, c1);
    const TraversalHit b = traverseReference(t, referenceRayFromQuantized(q), c2);
    hits += b.hit();
    if (a.voxel == b.voxel && (!a.hit() || (a.cell == b.cell && a.leafShift == b.leafShift))) return true;
    std::ostringstream s;
    s << describe(o, d) << " samet=" << a.voxel << " reference=" << b.voxel;
    why = s.str();
    return false;
}

/// Cameras beside the test cameras: orthographic ones (one along an axis, its pixel centres on
/// voxel edges), and pinhole eyes exactly on split planes of the root and deeper levels.
std::vector<NamedCamera> moreCameras(const Octree& t) {
    std::vector<NamedCamera> out;
    Camera framed = Camera::framing(cubeOf(t), 96, 72);
    framed.frameOrthographic(cubeOf(t));
    out.push_back({"orthographic, framing", framed});
    Camera axis = makeCamera({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 30, 64, 64);
    axis.projection = Camera::Projection::Orthographic;
    axis.orthoHeight = 2.0;  // pixel centres at odd multiples of 1/64: on the edges of depth-6 voxels
    out.push_back({"orthographic, along -z", axis});
    const double side = t.cubeSide;
    const dvec3 lo = t.cubeOrigin;
    // x on the root's mid-plane, y on a level-3 plane, z outside; and an eye inside on two planes.
    out.push_back({"eye on split planes", makeCamera(lo + side * dvec3(0.5, 0.375, 1.6), lo + side * dvec3(0.45, 0.5, 0.4),
                                                     {0, 0, 1}, 40, 80, 60)});
    out.push_back({"eye inside on split planes", makeCamera(lo + side * dvec3(0.25, 0.625, 0.53), lo + side * dvec3(0.8, 0.2, 0.4),
                                                            {0, 0, 1}, 80, 80, 60)});
    return out;
}

/// Frames of samet and beam against the oracle's (the reference, or full: bitwise the
/// reference's frames on these scenes, RendererTest's FullAndReferenceGiveBitwiseIdenticalFrames).
void expectSameFrames(const Octree& t, const std::string& treeName, const std::string& oracle) {
    std::vector<NamedCamera> cams = allTestCameras(t);
    for (const NamedCamera& c : moreCameras(t)) cams.push_back(c);
    std::uint64_t hits = 0;
    for (const NamedCamera& nc : cams) {
        Frame ref;
        const RenderStats rs = render(oracle, t, nc.camera, ref);
        hits += rs.hits;
        for (const char* name : {"samet", "beam"}) {
            SCOPED_TRACE(treeName + ", " + name + ", camera " + nc.name);
            Frame f;
            const RenderStats s = render(name, t, nc.camera, f);
            const FrameDiff d = diffFrames(f, ref);
            EXPECT_TRUE(d.identical()) << d.hitId << " hit ids, " << d.rgba << " colours, " << d.depth
                                       << " depths differ; first: " << d.first;
            EXPECT_EQ(s.rays, rs.rays);
            EXPECT_EQ(s.hits, rs.hits);
            if (rs.rays > 0) { EXPECT_GT(s.nodesVisited, 0u); }
            if (std::string(name) == "beam" && rs.hits > 0) {
                EXPECT_GT(s.beams, 0u);
                EXPECT_GE(s.intersections, s.hits);
            }
        }
    }
    EXPECT_GT(hits, 0u) << treeName;
}

}  // namespace

TEST(VoxelTracers, SametFollowsTheReferenceRayByRay) {
    const std::pair<std::string, const Octree*> trees[] = {
        {"sphere", &sphereTree()}, {"noise", &noiseTree()}, {"coarse leaves", &coarseLeafTree()}};
    for (const auto& [treeName, tree] : trees) {
        const VoxelCells cells(*tree);
        std::mt19937_64 rng(20261125);
        std::uint64_t hits = 0, mismatches = 0;
        std::string first;
        for (int i = 0; i < 20000; ++i) {
            dvec3 o, d;
            switch (i % 4) {
                case 0: rayAtVoxel(cells, rng, o, d); break;
                case 1: randomRay(rng, o, d); break;
                case 2: insideRay(rng, o, d); break;
                default: latticeRay(rng, o, d); break;
            }
            std::string why;
            if (!sametAgrees(*tree, o, d, hits, why)) {
                if (mismatches++ == 0) first = why;
            }
        }
        EXPECT_EQ(mismatches, 0u) << treeName << ": first " << first;
        EXPECT_GT(hits, 5000u) << treeName;  // not vacuous
    }
}

TEST(VoxelTracers, SametAndBeamGiveFullsFrames) {
    expectSameFrames(sphereTree(), "sphere", "full");
    expectSameFrames(torusTree(), "torus", "full");
    expectSameFrames(noiseTree(), "noise", "full");
}

TEST(VoxelTracers, SametAndBeamDrawCoarseLeavesAsTheReferenceDoes) {
    expectSameFrames(coarseLeafTree(), "coarse leaves", "reference");
}

TEST(VoxelTracers, AreDeterministicForAnyThreadCount) {
    const Camera cam = Camera::framing(cubeOf(noiseTree()), 150, 110);  // ragged tiles
    for (const char* name : {"samet", "beam"}) {
        SCOPED_TRACE(name);
        Frame f1;
        RenderSettings s;
        s.threads = 1;
        const RenderStats r1 = render(name, noiseTree(), cam, f1, s);
        for (int threads : {2, 3, 7}) {
            Frame f;
            s.threads = threads;
            const RenderStats r = render(name, noiseTree(), cam, f, s);
            EXPECT_TRUE(diffFrames(f1, f).identical()) << threads << " threads";
            EXPECT_EQ(r.nodesVisited, r1.nodesVisited);
            EXPECT_EQ(r.beams, r1.beams);
            EXPECT_EQ(r.intersections, r1.intersections);
            EXPECT_EQ(r.rays, r1.rays);
        }
    }
}

TEST(VoxelTracers, RenderIntoAFrameHoldingAnotherImageAsIntoAFreshOne) {
    // The frame is not cleared when its size stays (Frame::reshape): every pixel is written.
    const Camera a = Camera::framing(cubeOf(torusTree()), 90, 70);
    const Camera b = makeCamera({0.35, -0.2, 0.15}, {-0.5, 0.6, -0.1}, {0, 0, 1}, 70, 90, 70);
    for (const char* name : {"samet", "beam", "reference"}) {
        Frame fresh, reused;
        render(name, torusTree(), a, fresh);
        render(name, noiseTree(), b, reused);
        render(name, torusTree(), a, reused);
        EXPECT_TRUE(diffFrames(fresh, reused).identical()) << name;
    }
}

TEST(VoxelTracers, RefuseAMultiResolutionCut) {
    Octree t = buildShellOctree(makeAnalyticField("sphere", 33), {6, 0.0, 0});
    t.computeSummaries();
    const Camera cam = Camera::framing(cubeOf(t), 40, 30);
    for (const char* name : {"samet", "beam"}) {
        EXPECT_FALSE(makeRenderer(name)->multiResolution());
        RenderSettings s;
        s.detail.lodPixels = 2.0;
        Frame f;
        EXPECT_THROW(render(name, t, cam, f, s), UsageError) << name;
        s.detail.lodPixels = 0.0;
        s.detail.level = 3;
        EXPECT_THROW(render(name, t, cam, f, s), UsageError) << name;
    }
}
