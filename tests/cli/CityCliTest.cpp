// City inputs through the CLI: CityJSON rendered (terrain and buildings in one octree, every
// renderer agreeing with the reference), its CRS in `info`, and the options' errors.
#include "CliRunner.h"

#include <gtest/gtest.h>

using namespace octrace::testcli;

namespace {
const std::string kCube = std::string(OCTRACE_TEST_DATA) + "/city/cube.city.json";
}

TEST(CliCity, RendersDelftTerrainAndBuildingsExactlyAsTheReference) {
    if (!haveShared("city/delft.json")) GTEST_SKIP() << "shared data absent: " << sharedData("city/delft.json");
    for (const char* renderer : {"full", "direct"}) {
        Scratch s;
        Result r = run({"render", sharedData("city/delft.json"), "--depth", "8", "--size", "320x240", "--renderer", renderer,
                        "--verify", "--stats", s.path("st.json"), "-o", s.path("delft.png")});
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_NE(r.err.find("160 solids with an open shell"), std::string::npos) << r.err;  // reported, still drawn
        const std::string js = slurp(s.path("st.json"));
        if (std::string(renderer) == "full") EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
        else EXPECT_NE(js.find("\"hit_agreement\": 1,"), std::string::npos) << js;
        EXPECT_NE(js.find("\"variable\": \"city\""), std::string::npos) << js;
        EXPECT_TRUE(std::filesystem::exists(s.path("delft.png")));
    }
}

TEST(CliCity, MixedDepthDelftRendersExactlyAsTheReferenceInEveryExactRenderer) {
    if (!haveShared("city/delft.json")) GTEST_SKIP() << "shared data absent: " << sharedData("city/delft.json");
    // Terrain to depth 6, buildings to 9: coarse leaves three levels above the voxels, drawn
    // by the discrete traversals (from the root, from a branch node), the object-order
    // renderers and, multi-resolution, with a cut.
    const std::vector<std::vector<std::string>> runs = {{"full"}, {"linear-exact"}, {"area-exact"}, {"direct"}, {"direct-f2b"},
                                                        {"full", "--lod", "3"}, {"direct", "--lod", "3"}};
    std::string voxels;
    for (const auto& extra : runs) {
        Scratch s;
        std::vector<std::string> args = {"render", sharedData("city/delft.json"), "--depth", "9", "--terrain-depth", "6",
                                         "--size", "320x240", "--verify", "--stats", s.path("st.json"), "-o", s.path("m.png"),
                                         "--renderer"};
        args.insert(args.end(), extra.begin(), extra.end());
        Result r = run(args);
        ASSERT_EQ(r.code, 0) << r.err;
        const std::string js = slurp(s.path("st.json"));
        EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << extra[0] << ": " << js;
        EXPECT_NE(js.find("\"hit_agreement\": 1,"), std::string::npos) << extra[0] << ": " << js;
        const auto at = js.find("\"boundary_voxels\"");
        ASSERT_NE(at, std::string::npos) << js;
        if (voxels.empty()) voxels = js.substr(at, js.find(',', at) - at);
        EXPECT_EQ(js.substr(at, js.find(',', at) - at), voxels);
    }
    Scratch s;
    Result r = run({"render", sharedData("city/delft.json"), "--depth", "9", "--size", "32x24", "--stats", s.path("u.json"), "-o", s.path("u.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("u.json"));
    const auto at = js.find("\"boundary_voxels\": ");
    ASSERT_NE(at, std::string::npos);
    EXPECT_LT(std::stoull(voxels.substr(voxels.find(':') + 1)), std::stoull(js.substr(at + 19)));  // fewer than uniform depth 9
    r = run({"render", kCube, "--depth", "6", "--terrain-depth", "7", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--terrain-depth 7 is deeper than --depth 6"), std::string::npos) << r.err;
    r = run({"build", sharedData("city/delft.json"), "--depth", "6", "--terrain-depth", "3", "-o", s.path("a.oct")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("mixed-depth octree"), std::string::npos) << r.err;
}

TEST(CliCity, RendersBerlinsCityGmlLod2RoofsExactlyAsTheReference) {
    if (!haveShared("city/berlin_open_data_sample_data.citygml"))
        GTEST_SKIP() << "shared data absent: " << sharedData("city/berlin_open_data_sample_data.citygml");
    const std::string berlin = sharedData("city/berlin_open_data_sample_data.citygml");
    Scratch s;
    Result r = run({"render", berlin, "--depth", "8", "--size", "240x180", "--verify", "--stats", s.path("st.json"), "-o", s.path("b.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("st.json"));
    EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
    r = run({"info", berlin});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("crs: EPSG:25833"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("RoofSurface: 61"), std::string::npos) << r.out;
    r = run({"render", berlin, "--lod-select", "1", "-o", s.path("l1.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("no object has a geometry of LoD 1"), std::string::npos) << r.err;
}

TEST(CliCity, InfoShowsTheCrsAndLodSelectAndCrsChangeIt) {
    Result r = run({"info", kCube});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("crs: EPSG:28992"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("x [5, 20]"), std::string::npos) << r.out;
    r = run({"info", kCube, "--lod-select", "1", "--crs", "EPSG:32631"});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("crs: EPSG:32631"), std::string::npos) << r.out;
}

TEST(CliCity, OptionsThatDoNotApplyAndBadValuesAreRefused) {
    Scratch s;
    Result r = run({"render", kCube, "--iso", "3", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--iso does not apply to the city input"), std::string::npos) << r.err;
    r = run({"render", kCube, "--lod-select", "two", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--lod-select: expected a level of detail"), std::string::npos) << r.err;
    r = run({"render", "analytic:sphere:17", "--crs", "EPSG:28992", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--lod-select, --crs, --dem, --texture, --height-attr, --base-attr and --terrain-depth apply to city inputs"), std::string::npos) << r.err;
    r = run({"render", kCube, "--crs", "EPSG:999999", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("unknown coordinate reference system 'EPSG:999999'"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(s.path("a.png")));
}

TEST(CliCity, AnOctreeFileKeepsTheColoursAndTheCrs) {
    Scratch s;
    Result r = run({"build", kCube, "--depth", "6", "-o", s.path("c.oct")});
    ASSERT_EQ(r.code, 0) << r.err;
    r = run({"render", kCube, "--depth", "6", "--size", "160x120", "-o", s.path("direct.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    r = run({"render", s.path("c.oct"), "--size", "160x120", "-o", s.path("file.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(slurp(s.path("direct.png")) == slurp(s.path("file.png")));
    r = run({"render", kCube, "--depth", "6", "--size", "160x120", "--colour", "0.2,0.2,0.9", "-o", s.path("plain.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(slurp(s.path("direct.png")) != slurp(s.path("plain.png")));  // --colour over the per-voxel colours
    r = run({"info", s.path("c.oct")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("COLR"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("EPSG:28992"), std::string::npos) << r.out;
}

TEST(CliCity, RendersADemWithATextureInAnotherCrs) {
    if (!haveShared("city/lux_elev_srtm.tif")) GTEST_SKIP() << "shared data absent: " << sharedData("city/lux_elev_srtm.tif");
    Scratch s;
    const std::string texture = std::string(OCTRACE_TEST_DATA) + "/city/lux_checker_4326.tif";
    Result r = run({"render", sharedData("city/lux_elev_srtm.tif"), "--texture", texture, "--depth", "7", "--size", "200x150",
                    "--verify", "--stats", s.path("st.json"), "-o", s.path("tex.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(slurp(s.path("st.json")).find("\"mismatched_pixels\": 0,"), std::string::npos);
    r = run({"render", sharedData("city/lux_elev_srtm.tif"), "--depth", "7", "--size", "200x150", "-o", s.path("plain.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(slurp(s.path("tex.png")) != slurp(s.path("plain.png")));
    r = run({"info", sharedData("city/lux_elev_srtm.tif"), "--texture", texture});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("crs: EPSG:32632"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("texture: "), std::string::npos) << r.out;
    r = run({"render", sharedData("city/lux_elev_srtm.tif"), "--texture", kCube, "-o", s.path("bad.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("GDAL cannot open it as a raster"), std::string::npos) << r.err;
}

TEST(CliCity, RendersTheLyonFootprintsExactlyAsTheReference) {
    if (!haveShared("city/buildings_lyon1.geojson")) GTEST_SKIP() << "shared data absent: " << sharedData("city/buildings_lyon1.geojson");
    Scratch s;
    Result r = run({"render", sharedData("city/buildings_lyon1.geojson"), "--height-attr", "HAUTEUR", "--base-attr", "Z_MIN_SOL",
                    "--depth", "8", "--size", "240x180", "--verify", "--stats", s.path("st.json"), "-o", s.path("lyon.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("5 footprints without a base (Z_MIN_SOL missing), left out"), std::string::npos) << r.err;
    const std::string js = slurp(s.path("st.json"));
    EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
    r = run({"render", sharedData("city/buildings_lyon1.geojson"), "--height-attr", "ETAGES", "-o", s.path("no.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("no attribute 'ETAGES' (--height-attr)"), std::string::npos) << r.err;
    r = run({"render", kCube, "--height-attr", "h", "-o", s.path("no.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("--height-attr and --base-attr apply to building footprints"), std::string::npos) << r.err;
}
