// --map-projection and the automatic polar stereographic mapping end to end: info and stderr say
// which mapping is used, a polar region renders (and figures with coastlines), a mid-latitude
// one keeps the lon/lat mapping (the Levitus climatology; skipped without ../shared/data).
#include "CliRunner.h"

using namespace octrace::testcli;

namespace {

const char* kLevitus = "ocean/levitus_climatology.cdf";

bool says(const Result& r, const std::string& text) {
    return r.out.find(text) != std::string::npos || r.err.find(text) != std::string::npos;
}

}  // namespace

TEST(PolarCli, InfoSaysWhichMappingIsUsed) {
    const std::string lev = sharedData(kLevitus);
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent: " << lev;
    Result polar = run({"info", lev, "--var", "TEMP", "--region", "-180,180,65,90"});
    ASSERT_EQ(polar.code, 0) << polar.err;
    EXPECT_TRUE(says(polar, "geographic: polar stereographic, north pole, true scale at 71 N")) << polar.out << polar.err;
    EXPECT_TRUE(says(polar, "chosen automatically")) << polar.out;

    Result mid = run({"info", lev, "--var", "TEMP", "--region", "-70,-10,20,55"});
    ASSERT_EQ(mid.code, 0) << mid.err;
    EXPECT_FALSE(says(mid, "polar stereographic")) << mid.out;
    EXPECT_TRUE(says(mid, "x = R (lon - lon0) cos(lat0)")) << mid.out;

    Result forced = run({"info", lev, "--var", "TEMP", "--region", "-180,180,65,90", "--map-projection", "lonlat"});
    ASSERT_EQ(forced.code, 0) << forced.err;
    EXPECT_FALSE(says(forced, "polar stereographic")) << forced.out;
    Result south = run({"info", lev, "--var", "TEMP", "--region", "-70,-10,20,55", "--map-projection", "polar"});
    ASSERT_EQ(south.code, 0) << south.err;
    EXPECT_TRUE(says(south, "`map_projection` polar") || says(south, "--map-projection polar")) << south.out;

    Result bad = run({"info", lev, "--var", "TEMP", "--map-projection", "mercator"});
    EXPECT_EQ(bad.code, 2) << bad.err;
}

TEST(PolarCli, ArcticRendersAndFiguresOnThePolarMapping) {
    const std::string lev = sharedData(kLevitus);
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    Result r = run({"render", lev, "--var", "TEMP", "--iso", "0", "--region", "-180,180,65,90", "--depth", "7",
                    "--vertical-scale", "1500", "--size", "320x240", "--figure", "--stats", s.path("a.json"), "-o",
                    s.path("a.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(says(r, "polar stereographic")) << r.err;
    EXPECT_GT(slurp(s.path("a.png")).size(), 1000u);
    const std::string js = slurp(s.path("a.json"));
    EXPECT_EQ(js.find("\"boundary_voxels\": 0,"), std::string::npos) << js;

    Result sl = run({"slice", lev, "--var", "TEMP", "--region", "-180,180,65,90", "--plane", "z", "--at", "0", "--figure",
                     "-o", s.path("m.png")});
    ASSERT_EQ(sl.code, 0) << sl.err;
    EXPECT_GT(slurp(s.path("m.png")).size(), 1000u);
}
