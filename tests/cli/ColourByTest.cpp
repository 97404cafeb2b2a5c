// octrace render with a second variable (--colour-by), the colour options and the sea floor
// (--floor), on the Levitus climatology when it is present and on analytic fields.
#include "CliRunner.h"

#include <regex>

using namespace octrace::testcli;

namespace {
double statNumber(const std::string& js, const std::string& key) {
    std::smatch m;
    if (!std::regex_search(js, m, std::regex("\"" + key + "\": ([0-9.e+-]+)"))) return -1.0;
    return std::stod(m[1]);
}
}  // namespace

TEST(ColourBy, LevitusSalinityColouredByTemperatureOverTheFloorMatchesTheReference) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    for (const char* renderer : {"full", "area-exact", "linear-exact"}) {
        Result r = run({"render", lev, "--var", "SALT", "--iso", "34.5", "--colour-by", "TEMP", "--floor", "--region",
                        "120,260,0,65", "--depth", "7", "--size", "240x180", "--renderer", renderer, "--verify", "--stats",
                        s.path("st.json"), "-o", s.path("s.png")});
        ASSERT_EQ(r.code, 0) << r.err;
        const std::string js = slurp(s.path("st.json"));
        EXPECT_EQ(statNumber(js, "mismatched_pixels"), 0.0) << renderer << js;
        EXPECT_EQ(statNumber(js, "max_channel_error"), 0.0) << renderer << js;
        EXPECT_NE(js.find("\"colour_by\": \"TEMP\""), std::string::npos) << js;
        EXPECT_NE(js.find("\"colormap\": \"thermal\""), std::string::npos) << js;  // chosen from the name TEMP
        EXPECT_GT(statNumber(js, "floor_voxels"), 1000.0) << js;
        // The 34.5 isohaline in the North Pacific lies in water between about 2 and 29 degrees.
        EXPECT_GT(statNumber(js, "colour_min"), -2.5) << js;
        EXPECT_LT(statNumber(js, "colour_max"), 30.0) << js;
        EXPECT_LT(statNumber(js, "colour_min"), statNumber(js, "colour_max")) << js;
    }
    // A given range and map are reported as given.
    Result r = run({"render", lev, "--var", "SALT", "--iso", "34.5", "--colour-by", "TEMP", "--colour-range", "0,20",
                    "--colormap", "viridis", "--region", "120,260,0,65", "--depth", "6", "--size", "80x60", "--stats",
                    s.path("r.json"), "-o", s.path("r.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("r.json"));
    EXPECT_EQ(statNumber(js, "colour_min"), 0.0) << js;
    EXPECT_EQ(statNumber(js, "colour_max"), 20.0) << js;
    EXPECT_NE(js.find("\"colormap\": \"viridis\""), std::string::npos) << js;
}

TEST(ColourBy, RefusesAnUnknownVariableAFieldWithoutMaskAndBadRanges) {
    Scratch s;
    Result r = run({"render", "analytic:sphere:9", "--colour-by", "nope", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("nope"), std::string::npos) << r.err;
    r = run({"render", "analytic:sphere:9", "--floor", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("no masked sample"), std::string::npos) << r.err;
    for (const char* range : {"3,1", "1", "1,2,3", "a,b", "nan,1", "-inf,1"}) {
        r = run({"render", "analytic:sphere:9", "--colour-range", range, "-o", s.path("x.png")});
        EXPECT_EQ(r.code, 2) << range;
        EXPECT_NE(r.err.find("--colour-range"), std::string::npos) << r.err;
    }
    r = run({"render", "analytic:sphere:9", "--masked-colour", "2,0,0", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 2);
    EXPECT_FALSE(std::filesystem::exists(s.path("x.png")));
    // An octree file has no field to sample or to take a mask from.
    ASSERT_EQ(run({"build", "analytic:sphere:9", "--iso", "0", "--depth", "4", "-o", s.path("t.oct")}).code, 0);
    r = run({"render", s.path("t.oct"), "--colour-by", "sphere", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--colour-by"), std::string::npos) << r.err;
}

TEST(ColourBy, RenderHelpListsTheNewOptionsWithTheirDefaults) {
    Result h = run({"render", "--help"});
    ASSERT_EQ(h.code, 0);
    for (const char* opt : {"--colour-by VAR", "--colour-range MIN,MAX", "--masked-colour R,G,B", "--floor ", "--floor-colour R,G,B"})
        EXPECT_NE(h.out.find(opt), std::string::npos) << opt;
    for (const char* map : {"thermal", "haline", "speed", "viridis", "grey"}) EXPECT_NE(h.out.find(map), std::string::npos) << map;
}
