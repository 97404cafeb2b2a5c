// The per-pixel ray set-up shared by the ray casters (core/src/render/traversal/PixelRays.h): the screen-space
// outlines that let a renderer skip work must never change what a pixel shows or counts.
#include "RenderTestUtil.h"

#include "render/traversal/PixelRays.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <climits>

using namespace octrace;
using namespace octrace::test;

namespace {

std::vector<NamedCamera> camerasNearAndFar(const Octree& t) {
    std::vector<NamedCamera> cams = allTestCameras(t);
    // Close to the cube (its outline fills and leaves the screen) and far (a few pixels).
    cams.push_back({"close", makeCamera(dvec3(1.3, 0.4, 0.9), dvec3(0.0), dvec3(0, 0, 1), 60, 97, 61)});
    cams.push_back({"far", makeCamera(dvec3(40.0, -25.0, 18.0), dvec3(0.0), dvec3(0, 0, 1), 20, 97, 61)});
    const std::size_t n = cams.size();
    for (std::size_t i = 0; i < n; ++i) {
        Camera o = cams[i].camera;
        o.frameOrthographic(cubeOf(t));
        cams.push_back({cams[i].name + ", orthographic", o});
    }
    return cams;
}

}  // namespace

TEST(PixelRays, APixelSaidSurelyToMeetTheCubeHasAQuantizedRayThatMeetsIt) {
    const Octree& tree = sphereTree();
    std::size_t sure = 0, meet = 0;
    for (const NamedCamera& nc : camerasNearAndFar(tree)) {
        SCOPED_TRACE(nc.name);
        const detail::PixelRays rays(tree, nc.camera);
        for (int y = 0; y < nc.camera.height; ++y)
            for (int x = 0; x < nc.camera.width; ++x) {
                const bool meets = rays.quantized(x, y, rays.direction(x, y)).meetsCube;
                meet += meets;
                if (rays.surelyMeetsCube(x, y)) {
                    ++sure;
                    ASSERT_TRUE(meets) << "pixel " << x << "," << y;
                    ASSERT_TRUE(rays.mayMeetCube(x, y));
                }
                if (!rays.mayMeetCube(x, y)) { ASSERT_FALSE(meets) << "pixel " << x << "," << y; }
                ASSERT_EQ(rays.meetsCube(x, y), meets);
            }
    }
    // The shortcut must actually apply to most of the pixels whose rays meet the cube.
    EXPECT_GT(sure, meet / 2);
}

TEST(PixelRays, RenderingIntoAUsedFrameGivesTheFreshFrame) {
    // The ray casters re-render into a frame of the same size without clearing it first (the
    // CLI's --repeat, the studio's kept frames), and size a new frame without clearing it
    // (Frame::reshape, DefaultInitAllocator): every field of every pixel must be written. Every
    // renderer a menu lists, into a frame whose every field holds other values.
    const Octree& tree = torusTree();
    const Camera cam = Camera::framing(cubeOf(tree), 120, 90);
    const Camera other = makeCamera({-1.3, 1.1, -0.9}, {0.1, -0.05, 0.2}, {0, 1, 0}, 50, 120, 90);
    const std::vector<std::string> names = rendererMenuNames();
    ASSERT_NE(std::find(names.begin(), names.end(), "tile"), names.end());
    for (const std::string& name : names) {
        SCOPED_TRACE(name);
        Frame fresh, used;
        render(name, tree, cam, fresh);
        render(name, noiseTree(), other, used);  // another scene and view, same size
        ASSERT_EQ(used.width, fresh.width);
        for (std::size_t p = 0; p < used.rgba.size(); ++p) {
            used.rgba[p] = vec4(0.3f, float(p % 7), -1.0f, 0.25f);
            used.depth[p] = float(p);
            used.hitId[p] = std::uint32_t(p * 31);
            used.flags[p] = std::uint8_t(p | 0x80);
        }
        render(name, tree, cam, used);
        const FrameDiff d = diffFrames(used, fresh);
        EXPECT_TRUE(d.identical()) << d.first;
        EXPECT_EQ(used.flags, fresh.flags);
    }
}

namespace {
/// The box of every leaf, the long way; checks that `t` has some.
void expectOccupiedCellsAreTheLeaves(const Octree& t) {
    ivec3 lo(INT_MAX), hi(INT_MIN);
    std::size_t leaves = 0;
    t.forEachLeaf([&](const ivec3& c, int shift, std::uint32_t) {
        lo = glm::min(lo, c);
        hi = glm::max(hi, c + ((1 << shift) - 1));
        ++leaves;
    });
    ASSERT_GT(leaves, 0u);
    ivec3 olo, ohi;
    t.occupiedCells(olo, ohi);
    EXPECT_EQ(olo, lo);
    EXPECT_EQ(ohi, hi);
}
}  // namespace

TEST(PixelRays, TheSurfaceBoxIsTheBoxOfEveryLeaf) {
    // Octree::occupiedCells skips nodes inside the box found so far; it must still give the
    // box of all leaves.
    for (const Octree* t : {&sphereTree(), &torusTree(), &noiseTree()}) expectOccupiedCellsAreTheLeaves(*t);
    Octree empty;
    ivec3 lo, hi;
    empty.occupiedCells(lo, hi);
    EXPECT_GT(lo.x, hi.x);
}

// occupiedCells keeps its answer between frames: it must follow the octree's topology, depth
// and form, and moves.
TEST(PixelRays, TheKeptSurfaceBoxFollowsTheOctree) {
    Octree t = noiseTree().copy();
    expectOccupiedCellsAreTheLeaves(t);
    expectOccupiedCellsAreTheLeaves(t);  // the kept answer
    const Octree& torus = torusTree();
    ivec3 nlo, nhi, tlo, thi;
    t.occupiedCells(nlo, nhi);
    torus.occupiedCells(tlo, thi);
    ASSERT_TRUE(nlo != tlo || nhi != thi) << "the two scenes must have different boxes";
    t.setTopology(std::vector<OctreeNode>(torus.nodes()), std::vector<Voxel>(torus.voxels()));
    t.depth = torus.depth;
    expectOccupiedCellsAreTheLeaves(t);
    // The same nodes one level shallower: every cell halves.
    t.depth = torus.depth - 1;
    ivec3 slo, shi;
    t.occupiedCells(slo, shi);
    EXPECT_EQ(slo, tlo / 2);
    EXPECT_EQ(shi, thi / 2);
    t.depth = torus.depth;
    expectOccupiedCellsAreTheLeaves(t.copy());  // a copy of a tree that keeps its box
    Octree moved = std::move(t);
    expectOccupiedCellsAreTheLeaves(moved);
    // The tree moved from, given nodes again: it answers without keeping.
    t.setTopology(std::vector<OctreeNode>(noiseTree().nodes()), std::vector<Voxel>(noiseTree().voxels()));
    t.depth = noiseTree().depth;
    expectOccupiedCellsAreTheLeaves(t);
    expectOccupiedCellsAreTheLeaves(t);
    Octree assigned;
    assigned = std::move(moved);
    expectOccupiedCellsAreTheLeaves(assigned);
    assigned.setTopology({}, {});
    ivec3 lo, hi;
    assigned.occupiedCells(lo, hi);
    EXPECT_GT(lo.x, hi.x);
}

// RayGenerator::row computes four (AVX2) or two rays at a time: the same bits as one at a time,
// for odd and even row lengths and starts, perspective and orthographic, rows off the image too.
TEST(RayGenerator, RowGivesTheSameRaysBitForBitAsOneAtATime) {
    std::vector<Camera> cams = {makeCamera(dvec3(1.3, 0.4, 0.9), dvec3(0.0), dvec3(0, 0, 1), 60, 97, 61),
                                makeCamera(dvec3(40.0, -25.0, 18.0), dvec3(0.1, 0.2, -0.3), dvec3(0, 0, 1), 20, 1600, 1200),
                                makeCamera(dvec3(-0.2, 3.0, -1.0), dvec3(0.0), dvec3(0, 1, 0), 90, 33, 200)};
    Camera o = cams[0];
    o.frameOrthographic(Box3{dvec3(-1.0), dvec3(1.0)});
    cams.push_back(o);
    for (const Camera& cam : cams) {
        const RayGenerator gen(cam);
        for (int y : {-1, 0, 7, cam.height - 1, cam.height + 3})
            for (int x0 : {-2, 0, 5, cam.width - 9})
                for (int n : {0, 1, 2, 9, 64}) {
                    std::vector<Ray> row(std::size_t(n) + 1);
                    row[std::size_t(n)].origin = dvec3(7.0);  // the slot past the row stays untouched
                    gen.row(x0, y, n, row.data());
                    for (int i = 0; i < n; ++i) {
                        const Ray one = gen(x0 + i, y);
                        const Ray& r = row[std::size_t(i)];
                        ASSERT_TRUE(r.origin == one.origin && r.direction == one.direction)
                            << "x " << x0 + i << " y " << y << " of a row of " << n;
                    }
                    EXPECT_EQ(row[std::size_t(n)].origin, dvec3(7.0));
                }
    }
}
