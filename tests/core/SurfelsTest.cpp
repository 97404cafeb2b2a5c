// Tests of the surfel export: one surfel per boundary voxel (or per node of a coarser level),
// at the box's centre, with the voxel's unit normal, the half-diagonal radius and the colour
// the renderers use, in forEachVoxel's order, the same for any thread count.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/render/Shading.h"
#include "octrace/render/Surfels.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

using namespace octrace;

namespace {

const Octree& torusWithSummaries() {
    static const Octree t = [] {
        Octree tree = buildShellOctree(makeAnalyticField("torus", 33), {6, 0.0, 0});
        tree.computeSummaries();
        return tree;
    }();
    return t;
}

std::array<std::uint8_t, 4> srgb8(vec3 linear) {
    return {linearToSrgb8(linear.r), linearToSrgb8(linear.g), linearToSrgb8(linear.b), 255};
}

bool sameBytes(const std::vector<Surfel>& a, const std::vector<Surfel>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Surfel)) == 0;
}

}  // namespace

TEST(Surfels, OnePerBoundaryVoxelAtItsCentreWithItsUnitNormalInForEachVoxelOrder) {
    const Octree& tree = torusWithSummaries();
    const std::vector<Surfel> surfels = extractSurfels(tree, RenderSettings{});
    ASSERT_EQ(surfels.size(), tree.boundaryVoxels());
    const float radius = float(0.5 * std::sqrt(3.0) * tree.voxelSize());
    std::size_t i = 0;
    tree.forEachVoxel([&](const ivec3& cell, std::uint32_t voxel) {
        const Surfel& s = surfels[i++];
        const dvec3 centre = tree.voxelBox(cell).centre();
        for (int a = 0; a < 3; ++a) EXPECT_FLOAT_EQ(s.position[a], float(centre[a])) << "surfel " << i - 1;
        EXPECT_EQ(s.normal, decodeNormal(tree.voxels()[voxel].normal));
        EXPECT_NEAR(glm::length(s.normal), 1.0f, 1e-6f);
        EXPECT_FLOAT_EQ(s.radius, radius);
        EXPECT_EQ(s.rgba[3], 255);
    });
    // The torus (major radius 0.6, minor 0.25 in [-1,1]^3): every centre within a voxel
    // diagonal of it, and every normal pointing away from the core circle.
    for (const Surfel& s : surfels) {
        const vec3 onCircle = glm::length(vec3(s.position.x, s.position.y, 0.0f)) > 0.0f
                                  ? 0.6f * glm::normalize(vec3(s.position.x, s.position.y, 0.0f))
                                  : vec3(0.0f);
        const vec3 out = s.position - onCircle;
        EXPECT_NEAR(glm::length(out), 0.25f, 2.0f * radius);
        EXPECT_GT(glm::dot(s.normal, glm::normalize(out)), 0.8f);
    }
}

TEST(Surfels, AreTheSameForAnyThreadCount) {
    const Octree& tree = torusWithSummaries();
    RenderSettings one, all;
    one.threads = 1;
    one.colormap = all.colormap = "viridis";
    EXPECT_TRUE(sameBytes(extractSurfels(tree, one), extractSurfels(tree, all)));
    EXPECT_TRUE(sameBytes(extractSurfels(tree, one, 4), extractSurfels(tree, all, 4)));
}

TEST(Surfels, HaveTheAlbedoTheRenderersShadeWith) {
    const Octree& tree = torusWithSummaries();
    // With ambient 1 and no diffuse light, the shader's colour is the albedo itself.
    RenderSettings unlit;
    unlit.ambient = 1.0f;
    unlit.diffuse = 0.0f;
    const Camera camera = Camera::framing(tree.occupiedBounds(), 64, 48);
    for (const std::string map : {"", "viridis", "coolwarm"}) {
        unlit.colormap = map;
        const Shader shader(tree, camera, unlit);
        const std::vector<Surfel> surfels = extractSurfels(tree, unlit);
        std::size_t i = 0;
        tree.forEachVoxel([&](const ivec3& cell, std::uint32_t voxel) {
            EXPECT_EQ(surfels[i++].rgba, srgb8(vec3(shader.shade(voxel, cell)))) << map;
        });
        const std::vector<Surfel> coarse = extractSurfels(tree, unlit, 3);
        i = 0;
        tree.forEachAtLevel(3, [&](const ivec3&, std::uint32_t node) {
            EXPECT_EQ(coarse[i++].rgba, srgb8(vec3(shader.shadeNode(node)))) << map;
        });
    }
    RenderSettings blue;
    blue.colour = vec3(0.1f, 0.2f, 0.9f);
    EXPECT_EQ(extractSurfels(tree, blue).front().rgba, srgb8(blue.colour));
}

TEST(Surfels, AtACoarserLevelOnePerNonEmptyNodeAtItsCentreWithTheSummary) {
    const Octree& tree = torusWithSummaries();
    for (int level = 0; level < tree.depth; ++level) {
        const std::vector<Surfel> surfels = extractSurfels(tree, RenderSettings{}, level);
        const double side = tree.cubeSide / double(1 << level);
        std::size_t i = 0, voxels = 0;
        tree.forEachAtLevel(level, [&](const ivec3& cell, std::uint32_t node) {
            const Surfel& s = surfels.at(i++);
            const dvec3 centre = tree.cubeOrigin + (dvec3(cell) + 0.5) * side;
            for (int a = 0; a < 3; ++a) EXPECT_FLOAT_EQ(s.position[a], float(centre[a]));
            EXPECT_EQ(s.normal, decodeNormal(tree.summaries()[node].normal));
            EXPECT_NEAR(glm::length(s.normal), 1.0f, 1e-6f);
            EXPECT_FLOAT_EQ(s.radius, surfelRadius(side));
            voxels += tree.summaries()[node].voxelCount;
        });
        EXPECT_EQ(i, surfels.size()) << "level " << level;
        EXPECT_EQ(voxels, tree.boundaryVoxels()) << "level " << level;  // every voxel under one surfel
    }
    EXPECT_EQ(extractSurfels(tree, RenderSettings{}, 0).size(), 1u);
    EXPECT_TRUE(sameBytes(extractSurfels(tree, RenderSettings{}, tree.depth), extractSurfels(tree, RenderSettings{})));
}

TEST(Surfels, RefuseALevelTheTreeCannotGive) {
    const Octree& tree = torusWithSummaries();
    EXPECT_THROW(extractSurfels(tree, RenderSettings{}, tree.depth + 1), UsageError);
    RenderSettings badMap;
    badMap.colormap = "rainbowish";
    EXPECT_THROW(extractSurfels(tree, badMap), UsageError);
    const Octree plain = buildShellOctree(makeAnalyticField("sphere", 17), {4, 0.0, 0});
    EXPECT_THROW(extractSurfels(plain, RenderSettings{}, 2), UsageError);  // no summaries
    EXPECT_EQ(extractSurfels(plain, RenderSettings{}).size(), plain.boundaryVoxels());
    EXPECT_TRUE(extractSurfels(Octree{}, RenderSettings{}).empty());
}
