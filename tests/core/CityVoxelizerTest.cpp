// Tests of the city model's triangulation and of voxelizeCity against what a box's shell must
// be, counted independently: the cells of the outer layer of a 2^depth grid.
#include "octrace/build/CityModel.h"
#include "octrace/build/CityVoxelizer.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using namespace octrace;

namespace {

double area2d(const std::vector<std::vector<dvec2>>& rings, const std::vector<std::array<std::uint32_t, 3>>& tris) {
    std::vector<dvec2> pts;
    for (const auto& r : rings) pts.insert(pts.end(), r.begin(), r.end());
    double a = 0.0;
    for (const auto& t : tris) {
        const dvec2 p = pts[t[0]], q = pts[t[1]], r = pts[t[2]];
        a += 0.5 * std::abs((q.x - p.x) * (r.y - p.y) - (q.y - p.y) * (r.x - p.x));
    }
    return a;
}

CityModel boxModel(std::uint32_t colour) {
    CityModel m;
    m.objects.push_back({"box", "Building", CityRole::Solid, colour});
    EXPECT_TRUE(m.addPrism({{{0, 0}, {16, 0}, {16, 16}, {0, 16}}}, 0.0, 16.0, 0));
    return m;
}

}  // namespace

TEST(CityModel, TriangulatesAnLShapedPolygonWithAHoleIntoItsArea) {
    // An L (area 100 - 25 = 75) with a 2 x 2 hole (75 - 4 = 71), given clockwise.
    const std::vector<std::vector<dvec2>> rings{{{0, 0}, {0, 10}, {5, 10}, {5, 5}, {10, 5}, {10, 0}},
                                                {{1, 1}, {3, 1}, {3, 3}, {1, 3}}};
    std::vector<std::array<std::uint32_t, 3>> tris;
    ASSERT_TRUE(triangulatePolygon(rings, tris));
    EXPECT_EQ(tris.size(), 10u);  // n + 2h - 2 for n = 10 points, h = 1 hole
    EXPECT_NEAR(area2d(rings, tris), 71.0, 1e-9);
}

TEST(CityModel, RefusesASelfIntersectingPolygon) {
    std::vector<std::array<std::uint32_t, 3>> tris;
    EXPECT_FALSE(triangulatePolygon({{{0, 0}, {10, 10}, {10, 0}, {0, 10}}}, tris));  // a bow tie
    EXPECT_TRUE(tris.empty());
    CityModel m;
    m.objects.push_back({"x", "Building", CityRole::Solid, 0});
    EXPECT_FALSE(m.addPolygon({{{0, 0, 0}, {10, 10, 0}, {10, 0, 0}, {0, 10, 0}}}, 0));
    EXPECT_FALSE(m.addPolygon({{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}}}, 0));  // no area
    EXPECT_TRUE(m.triangles.empty());
}

TEST(CityModel, APrismHasFloorRoofAndWallsOfTheFootprint) {
    CityModel m;
    m.objects.push_back({"p", "Building", CityRole::Solid, 0});
    ASSERT_TRUE(m.addPrism({{{0, 0}, {4, 0}, {4, 3}, {0, 3}, {0, 0}}}, 2.0, 7.0, 0));
    EXPECT_EQ(m.triangles.size(), 2u + 2u + 8u);
    const Box3 b = m.bounds();
    EXPECT_EQ(b.lo, dvec3(0, 0, 2));
    EXPECT_EQ(b.hi, dvec3(4, 3, 7));
    EXPECT_FALSE(m.addPrism({{{0, 0}, {4, 0}, {4, 3}}}, 5.0, 5.0, 0));  // no height
}

TEST(CityVoxelizer, ABoxGivesExactlyTheOuterLayerOfCells) {
    const CityModel m = boxModel(packColour(vec3(1, 0, 0)));
    CityBuildOptions o;
    o.depth = 4;
    Octree t = voxelizeCity(m, o);
    t.validate();
    EXPECT_EQ(t.cubeSide, 16.0);
    const int n = 16;
    std::size_t count = 0;
    t.forEachVoxel([&](const ivec3& c, std::uint32_t) {
        const bool outer = c.x == 0 || c.y == 0 || c.z == 0 || c.x == n - 1 || c.y == n - 1 || c.z == n - 1;
        EXPECT_TRUE(outer) << c.x << "," << c.y << "," << c.z;
        ++count;
    });
    EXPECT_EQ(count, std::size_t(n * n * n - (n - 2) * (n - 2) * (n - 2)));
    ASSERT_TRUE(t.hasColours());
    for (auto c : t.colours()) EXPECT_EQ(c, packColour(vec3(1, 0, 0)));
}

TEST(CityVoxelizer, TheResultDoesNotDependOnTheThreads) {
    CityModel m = boxModel(packColour(vec3(0.5f)));
    m.objects.push_back({"roof", "Building", CityRole::Solid, packColour(vec3(0, 0, 1))});
    ASSERT_TRUE(m.addPolygon({{{0, 0, 16}, {16, 0, 16}, {8, 8, 24}}}, 1));
    CityBuildOptions o;
    o.depth = 7;
    o.threads = 1;
    const Octree a = voxelizeCity(m, o);
    o.threads = 4;
    const Octree b = voxelizeCity(m, o);
    a.validate();
    ASSERT_EQ(a.nodes().size(), b.nodes().size());
    ASSERT_EQ(a.voxels().size(), b.voxels().size());
    for (std::size_t i = 0; i < a.nodes().size(); ++i) EXPECT_EQ(a.nodes()[i].firstChild, b.nodes()[i].firstChild);
    for (std::size_t i = 0; i < a.voxels().size(); ++i) EXPECT_EQ(a.voxels()[i].normal, b.voxels()[i].normal);
    EXPECT_EQ(a.colours(), b.colours());
    EXPECT_EQ(std::set<std::uint32_t>(a.colours().begin(), a.colours().end()).size(), 2u);
}

TEST(CityVoxelizer, TerrainTakesTheTextureWhereItHasData) {
    CityModel m;
    m.objects.push_back({"ground", "TINRelief", CityRole::Terrain, packColour(vec3(0, 1, 0))});
    ASSERT_TRUE(m.addPolygon({{{0, 0, 0}, {8, 0, 0}, {8, 8, 0}, {0, 8, 0}}}, 0));
    // Left half red, right half without data.
    m.texture.origin = dvec2(0, 8);
    m.texture.pixel = dvec2(4, 8);
    m.texture.width = 2;
    m.texture.height = 1;
    m.texture.rgba = {packColour(vec3(1, 0, 0)), 0};
    CityBuildOptions o;
    o.depth = 3;
    const Octree t = voxelizeCity(m, o);
    ASSERT_TRUE(t.hasColours());
    std::size_t red = 0, green = 0;
    t.forEachVoxel([&](const ivec3& c, std::uint32_t i) {
        const bool left = t.voxelBox(c).centre().x < 4.0;
        EXPECT_EQ(t.colours()[i], packColour(left ? vec3(1, 0, 0) : vec3(0, 1, 0)));
        (left ? red : green)++;
    });
    EXPECT_GT(red, 0u);
    EXPECT_EQ(red, green);
}

TEST(CityVoxelizer, RefusesABadDepthAndAModelWithoutArea) {
    CityModel m = boxModel(0);
    CityBuildOptions o;
    o.depth = 0;
    EXPECT_THROW(voxelizeCity(m, o), UsageError);
    CityModel flat;
    flat.objects.push_back({"x", "Building", CityRole::Solid, 0});
    flat.vertices = {{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
    flat.triangles.push_back({{0, 1, 2}, 0});
    o.depth = 4;
    EXPECT_THROW(voxelizeCity(flat, o), EmptyResultError);
}

TEST(CityVoxelizer, TerrainStopsAtTheTerrainDepthAndBuildingsGoToTheDepth) {
    // Ground 64 x 64 at z = 1 and a 16 x 16 x 16 building on it, in a 64-unit cube.
    CityModel m;
    m.objects.push_back({"ground", "TINRelief", CityRole::Terrain, packColour(vec3(0, 1, 0))});
    m.objects.push_back({"house", "Building", CityRole::Solid, packColour(vec3(1, 0, 0))});
    ASSERT_TRUE(m.addPolygon({{{0, 0, 1}, {64, 0, 1}, {64, 64, 1}, {0, 64, 1}}}, 0));
    ASSERT_TRUE(m.addPrism({{{8, 8}, {24, 8}, {24, 24}, {8, 24}}}, 1.0, 17.0, 1));
    ASSERT_TRUE(m.addPolygon({{{0, 0, 64}, {1, 0, 64}, {0, 1, 64}}}, 1));  // a mast: makes the cube 64 high
    CityBuildOptions o;
    o.depth = 6;
    const Octree uniform = voxelizeCity(m, o);
    EXPECT_FALSE(uniform.hasCoarseLeaves());
    o.terrainDepth = 3;
    Octree mixed = voxelizeCity(m, o);
    mixed.validate();
    ASSERT_TRUE(mixed.hasCoarseLeaves());
    ASSERT_TRUE(mixed.hasColours());
    EXPECT_LT(mixed.voxels().size(), uniform.voxels().size() / 2);
    // Every leaf of the building's shell is a voxel; coarse leaves are cubes of level 3 (side 8)
    // or, in level-3 nodes shared with the house, deeper, that only the ground crosses: green.
    std::set<std::array<int, 3>> fine;
    std::size_t level3 = 0;
    mixed.forEachLeaf([&](const ivec3& c, int shift, std::uint32_t v) {
        if (shift == 0) {
            fine.insert({c.x, c.y, c.z});
            return;
        }
        const int side = 1 << shift;
        level3 += shift == 3;
        EXPECT_LE(shift, 3);
        EXPECT_EQ(c.z, 0);  // the ground's level
        const bool meetsHouse = c.x <= 24 && c.x + side >= 8 && c.y <= 24 && c.y + side >= 8;  // closed boxes
        EXPECT_FALSE(meetsHouse) << c.x << "," << c.y << " side " << side;
        EXPECT_EQ(mixed.colours()[v], packColour(vec3(0, 1, 0)));
        EXPECT_EQ(mixed.findVoxel(c + ivec3(side - 1)), v);
    });
    EXPECT_EQ(level3, 64u - 16u);  // 8 x 8 ground cubes less the 4 x 4 the house's closed box touches
    uniform.forEachVoxel([&](const ivec3& c, std::uint32_t v) {
        if (uniform.colours()[v] == packColour(vec3(1, 0, 0))) {
            EXPECT_TRUE(fine.count({c.x, c.y, c.z})) << c.x << "," << c.y << "," << c.z;
        }
    });
    // The summaries count each coarse leaf once; the bounds cover the coarse leaves whole.
    mixed.computeSummaries();
    EXPECT_EQ(mixed.summaries()[0].voxelCount, mixed.voxels().size());
    ivec3 lo, hi;
    mixed.occupiedCells(lo, hi);
    EXPECT_EQ(lo, ivec3(0));
    EXPECT_EQ(hi, ivec3(63));
    // The same at terrain depth = depth: uniform.
    o.terrainDepth = 6;
    EXPECT_EQ(voxelizeCity(m, o).voxels().size(), uniform.voxels().size());
    o.terrainDepth = -1;
    EXPECT_THROW(voxelizeCity(m, o), UsageError);
}
