// octrace slice of 2-D fields (maps) and `--at` in the user's terms: the real ETOPO20 relief,
// the Levitus atlas's top level written as a 2-D file and as OISST lays it out (zlev = 1) by
// tests/data/netcdf/make_maps.py, which must give the atlas's pixels; `--at` longitudes in
// -180..180 and 0..360 alike; refusals saying degrees and metres; `info` and `render` of maps.
#include "CliRunner.h"
#include "../io/ImageTestSupport.h"

#include <cstdio>
#include <cstdlib>

using namespace octrace::testcli;

namespace {

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

std::string testFile(const std::string& rel) { return std::string(OCTRACE_TEST_DATA) + "/" + rel; }

octrace::test::DecodedPng png(const std::string& path) { return octrace::test::decodePng(octrace::test::readBytes(path)); }

/// Pixels whose channels differ by more than `tolerance`, or -1 when the sizes differ.
long differing(const octrace::test::DecodedPng& a, const octrace::test::DecodedPng& b, int tolerance) {
    if (a.width != b.width || a.height != b.height) return -1;
    long n = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x)
            for (int c = 0; c < 3; ++c)
                if (std::abs(int(a.at(x, y, c)) - int(b.at(x, y, c))) > tolerance) {
                    ++n;
                    break;
                }
    return n;
}

double rowMean(const octrace::test::DecodedPng& p, int y0, int y1) {
    double sum = 0.0;
    for (int y = y0; y < y1; ++y)
        for (int x = 0; x < p.width; ++x) sum += p.at(x, y, 0);
    return sum / (double(y1 - y0) * p.width);
}

// `args` sliced into `out` with the view the top-level comparisons share: -2..30 degC, land
// magenta, the Atlantic from 100 W to 20 E, 60 S to 70 N.
Result sliceAtlasView(Scratch& s, std::vector<std::string> args, const std::string& out) {
    for (const char* a : {"--colour-range", "-2,30", "--masked-colour", "1,0,1", "--region", "-100,20,-60,70", "-o"})
        args.push_back(a);
    args.push_back(s.path(out));
    return run(args);
}

}  // namespace

// ETOPO20 as a map: one pixel per 20' sample, north up (Antarctica's ice, high, at the bottom
// is brighter in grey than the Arctic Ocean at the top), the Tibetan plateau bright; a figure
// with its colour bar; the summary and stats.
TEST(SliceMapCli, Etopo20IsDrawnAsAMapNorthUp) {
    if (!haveShared("ocean/etopo20.cdf")) GTEST_SKIP() << "shared data absent";
    Scratch s;
    const std::string etopo = sharedData("ocean/etopo20.cdf");
    Result r = run({"slice", etopo, "--colormap", "grey", "--colour-range", "-6000,4000", "--stats", s.path("st.json"), "-o",
                    s.path("e.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("st.json"));
    EXPECT_TRUE(has(js, "\"plane\": \"z\"")) << js;
    EXPECT_TRUE(has(js, "\"variable\": \"ROSE\"")) << js;
    EXPECT_TRUE(has(js, "\"screen_up\": \"+y\"")) << js;
    const auto p = png(s.path("e.png"));
    EXPECT_EQ(p.height, 540);
    EXPECT_GE(p.width, 1080);
    EXPECT_GT(rowMean(p, p.height - 20, p.height), rowMean(p, 0, 20) + 50.0);  // Antarctica below, the Arctic above
    // 88E 31N (Tibet) against 150W 20N (the Pacific): x from the grid's west edge, y from the north.
    const double lonWest = 20.0 + 1.0 / 6.0, latNorth = 90.0 - 1.0 / 6.0, degPerPx = 1.0 / 3.0;  // ETOPO20's first samples
    auto px = [&](double lon, double lat) {
        const int x = int(std::lround(std::fmod(lon - lonWest + 720.0, 360.0) / degPerPx));
        const int y = int(std::lround((latNorth - lat) / degPerPx));
        return int(p.at(x, y, 0));
    };
    EXPECT_GT(px(88.0, 31.0), 200);
    EXPECT_LT(px(-150.0, 20.0), 120);

    r = run({"slice", etopo, "--figure", "--size", "1200x700", "-o", s.path("f.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(png(s.path("f.png")).width, 1200);
}

// The atlas's top level, three ways: the 3-D atlas at 0 m, its level 0 as a 2-D file, and as
// OISST lays it out (time, zlev = 1, packed int16): the same pixels (OISST within its packing).
TEST(SliceMapCli, TwoDimensionalAndSingleLevelFilesGiveTheAtlasTopLevelPixels) {
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent";
    Scratch s;
    auto slice = [&](std::vector<std::string> args, const std::string& out) { return sliceAtlasView(s, args, out); };
    Result r = slice({"slice", sharedData("ocean/levitus_climatology.cdf"), "--var", "TEMP", "--at", "0"}, "atlas.png");
    ASSERT_EQ(r.code, 0) << r.err;
    r = slice({"slice", testFile("netcdf/levitus_sst_2d.nc")}, "map.png");
    ASSERT_EQ(r.code, 0) << r.err;
    r = slice({"slice", testFile("netcdf/oisst_like_zlev.nc")}, "oisst.png");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto atlas = png(s.path("atlas.png")), map = png(s.path("map.png")), oisst = png(s.path("oisst.png"));
    EXPECT_EQ(differing(atlas, map, 0), 0);
    EXPECT_EQ(differing(map, oisst, 1), 0);
    long land = 0;
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) land += map.at(x, y, 0) == 255 && map.at(x, y, 1) == 0 && map.at(x, y, 2) == 255;
    EXPECT_GT(land, map.width * map.height / 10);  // the Americas, Africa, Europe masked
}

TEST(SliceMapCli, OnlyTheMapPlaneOfATwoDimensionalFieldAndNoSurface) {
    Scratch s;
    const std::string sst = testFile("netcdf/levitus_sst_2d.nc");
    Result r = run({"slice", sst, "--plane", "x", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(has(r.err, "--plane x: 'sst' is a 2-D field (a map): only its z plane, the map itself, can be drawn; leave --plane out"))
        << r.err;
    r = run({"slice", sst, "--at", "100", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(has(r.err, "--at 100: 'sst' is a 2-D field, a map at 0 m depth: leave --at out")) << r.err;
    r = run({"render", sst, "--iso", "10", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(has(r.err, "a surface needs a 3-D field; draw the 2-D sst with slice")) << r.err;
    EXPECT_EQ(countEntries(s.dir()), 0);
    r = run({"info", sst});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.out, "sst(lat, lon) Float32 [180 x 360]")) << r.out;
    EXPECT_TRUE(has(r.out, "2-D: a map, drawn by slice only")) << r.out;
    EXPECT_TRUE(has(r.out, "grid of the map sst (whole grid):")) << r.out;
    // An entirely masked map: refused by slice too.
    r = run({"slice", testFile("invalid/invalid_map_all_masked.nc"), "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(has(r.err, "variable 'sst' has no valid sample")) << r.err;
}

// `--at` longitudes as `--region` takes them: -30 and 330 are one meridian on Levitus's
// 20.5..379.5; off-grid positions are told in degrees and metres.
TEST(SliceMapCli, AtTakesLongitudesEitherWayAndRefusesInTheUsersTerms) {
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent";
    Scratch s;
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    Result r = run({"slice", lev, "--var", "TEMP", "--plane", "x", "--at", "-30.5", "--stats", s.path("a.json"), "-o", s.path("a.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.err, "31\u00b0W")) << r.err;
    r = run({"slice", lev, "--var", "TEMP", "--plane", "x", "--at", "329.5", "-o", s.path("b.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(differing(png(s.path("a.png")), png(s.path("b.png")), 0), 0);
    EXPECT_TRUE(has(slurp(s.path("a.json")), "\"grid_index\": 309")) << slurp(s.path("a.json"));  // 329.5E: sample 309 of 20.5..379.5

    const std::pair<std::vector<std::string>, std::string> refused[] = {
        {{"--region", "120,180,10,60", "--plane", "x", "--at", "100"},
         "--at 100: longitude outside the grid, which spans 120.5 .. 179.5 degrees east (-180..180 and 0..360 both accepted)"},
        {{"--region", "120,180,10,60", "--plane", "y", "--at", "5"}, "--at 5: latitude outside the grid, which spans 10.5 .. 59.5 degrees north"},
        {{"--at", "-50"}, "--at -50: 50 m above the sea surface lies outside the grid, whose levels run 0 .. 5000 m depth"},
        {{"--at", "-6"}, "--at -6: 6 m above the sea surface lies outside the grid"},  // beyond half the first step (10 m)
        {{"--at", "6000"}, "--at 6000: 6000 m depth lies outside the grid, whose levels run 0 .. 5000 m depth"},
    };
    for (const auto& [extra, message] : refused) {
        std::vector<std::string> args = {"slice", lev, "--var", "TEMP", "-o", s.path("c.png")};
        args.insert(args.end(), extra.begin(), extra.end());
        r = run(args);
        EXPECT_EQ(r.code, 1) << message;
        EXPECT_TRUE(has(r.err, message)) << r.err;
    }
    r = run({"slice", lev, "--var", "TEMP", "--at", "-4", "-o", s.path("c.png")});  // within half the first step: the surface
    EXPECT_EQ(r.code, 0) << r.err;
}

// Cell bounds and 2-D coordinates of a bipolar-like grid are not fields.
TEST(SliceMapCli, CellBoundsAreRefusedByNameAndNotListedAsFields) {
    Scratch s;
    const std::string bip = testFile("netcdf/bipolar_like.nc");
    Result r = run({"render", bip, "--var", "lon_bnds", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(has(r.err, "variable lon_bnds(y, x, vertices) is the cell bounds of 'lon'")) << r.err;
    r = run({"slice", bip, "--var", "lat", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(has(r.err, "variable lat(y, x) is a coordinate of 'tos'")) << r.err;
    r = run({"info", bip});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.out, "coordinates and cell bounds (not fields):\n  lat(y, x)")) << r.out;
    EXPECT_EQ(countEntries(s.dir()), 0);
}

// A NEMO-like 2-D SST on the tripolar grid (make_curvilinear.py: nemo_sst_2d.nc, the surface of
// tripolar_global.nc) is sliced as a map on the resampled lattice: the same pixels as the 3-D
// file's 0 m slice (within its 0.001 degC packing), land masked.
TEST(SliceMapCli, CurvilinearTwoDimensionalFieldIsDrawnAsTheThreeDimensionalFilesTopLevel) {
    Scratch s;
    auto slice = [&](std::vector<std::string> args, const std::string& out) { return sliceAtlasView(s, args, out); };
    Result r = slice({"slice", testFile("netcdf/nemo_sst_2d.nc")}, "map.png");
    ASSERT_EQ(r.code, 0) << r.err;
    r = slice({"slice", testFile("netcdf/tripolar_global.nc"), "--var", "temp", "--at", "0"}, "top.png");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto map = png(s.path("map.png")), top = png(s.path("top.png"));
    EXPECT_EQ(differing(map, top, 1), 0);
    long land = 0;
    for (int y = 0; y < map.height; ++y)
        for (int x = 0; x < map.width; ++x) land += map.at(x, y, 0) == 255 && map.at(x, y, 1) == 0 && map.at(x, y, 2) == 255;
    EXPECT_GT(land, map.width * map.height / 10);  // the Americas, Africa, Europe masked
    EXPECT_LT(land, map.width * map.height / 2);
    r = run({"info", testFile("netcdf/nemo_sst_2d.nc")});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.out, "2-D: a map, drawn by slice only, curvilinear (2-D nav_lat nav_lon: resampled onto a regular lattice)"))
        << r.out;
    r = run({"render", testFile("netcdf/nemo_sst_2d.nc"), "--iso", "10", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(has(r.err, "a surface needs a 3-D field")) << r.err;
}

// A ROMS-like file on a curvilinear grid with s-levels (make_sigma.py): rendered, and `info`
// says the grid, the formula and how the depths are resampled.
TEST(SliceMapCli, CurvilinearRomsFileWithSLevelsRendersAndInfoSaysHow) {
    Scratch s;
    const std::string roms = testFile("netcdf/roms_curvilinear_nwatlantic.nc");
    Result r = run({"render", roms, "--var", "temp", "--time", "1", "--iso", "10", "--depth", "6", "--size", "160x120",
                    "--stats", s.path("st.json"), "-o", s.path("r.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const auto img = png(s.path("r.png"));
    EXPECT_EQ(img.width, 160);
    r = run({"info", roms, "--var", "temp", "--time", "1"});
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* part : {"s_rho = 20: vertical (positive up), parametric: ocean_s_coordinate_g2",
                             "note: curvilinear grid: 2-D coordinates lon_rho(eta_rho, xi_rho) and lat_rho(eta_rho, xi_rho)",
                             "note: vertical: each column's depths resampled onto the horizontal lattice with the field's weights",
                             "time step 1 of 2 (2000-01-02"})
        EXPECT_TRUE(has(r.out, part)) << "lacks '" << part << "' in\n" << r.out;
}
