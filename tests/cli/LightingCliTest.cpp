// Baked lighting on the command line: build --bake keeps it in the file, render uses it unless
// --lighting dynamic, render --lighting baked bakes when the octree has none.
#include "CliRunner.h"

#include <gtest/gtest.h>

using namespace octrace::testcli;

TEST(CliLighting, BakedLightIsStoredAndUsedUnlessDynamicIsAsked) {
    Scratch s;
    Result r = run({"build", "analytic:torus:33", "--iso", "0", "--depth", "6", "--bake", "--bake-light", "dir:0,0,1",
                    "--bake-light", "point:2,2,2,0.5", "--bake-ao", "4", "-o", s.path("t.oct"), "--stats", s.path("b.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(slurp(s.path("b.json")).find("\"bake_ms\""), std::string::npos);
    r = run({"info", s.path("t.oct")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("version 3"), std::string::npos) << r.out;  // baked light and corner values (CRNR)
    EXPECT_NE(r.out.find("LITE:"), std::string::npos) << r.out;
    const std::vector<std::string> common{"--size", "120x90", "--verify"};
    auto render = [&](std::vector<std::string> args, const std::string& out) {
        args.insert(args.end(), common.begin(), common.end());
        for (const std::string& x : {std::string("-o"), s.path(out), std::string("--stats"), s.path(out + ".json")}) args.push_back(x);
        return run(args);
    };
    r = render({"render", s.path("t.oct")}, "baked.png");
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("baked.png.json"));
    EXPECT_NE(js.find("\"lighting\": \"baked\""), std::string::npos) << js;
    EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
    r = render({"render", s.path("t.oct"), "--lighting", "dynamic"}, "dynamic.png");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(slurp(s.path("dynamic.png.json")).find("\"lighting\": \"dynamic\""), std::string::npos);
    EXPECT_NE(slurp(s.path("baked.png")), slurp(s.path("dynamic.png")));
    // From the field: --lighting baked bakes first (default lights), stating the time.
    r = render({"render", "analytic:torus:33", "--iso", "0", "--depth", "6", "--lighting", "baked"}, "field.png");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(slurp(s.path("field.png.json")).find("\"bake_ms\": 0,"), std::string::npos);
    // --bake with --lighting dynamic would bake for nothing: told, and not baked.
    r = render({"render", "analytic:torus:33", "--iso", "0", "--depth", "6", "--bake", "--lighting", "dynamic"}, "unused.png");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("--bake with --lighting dynamic: nothing baked"), std::string::npos) << r.err;
    EXPECT_NE(slurp(s.path("unused.png.json")).find("\"bake_ms\": 0,"), std::string::npos);
    EXPECT_NE(slurp(s.path("unused.png.json")).find("\"lighting\": \"dynamic\""), std::string::npos);
    // Usage errors.
    EXPECT_EQ(run({"render", "analytic:torus:33", "--lighting", "flat", "-o", s.path("x.png")}).code, 2);
    EXPECT_EQ(run({"build", "analytic:torus:33", "--bake-light", "sun:1,1,1", "-o", s.path("x.oct")}).code, 2);
    EXPECT_EQ(run({"build", "analytic:torus:33", "--bake-shadows", "maybe", "-o", s.path("x.oct")}).code, 2);
    EXPECT_EQ(run({"build", "analytic:torus:33", "--bake", "--form", "volume", "-o", s.path("x.oct")}).code, 2);
}

TEST(CliLighting, ShadowRaysOnVoxelOctreesAreOffByDefaultAndAlikeForEveryExactRenderer) {
    Scratch s;
    auto render = [&](std::vector<std::string> extra, const std::string& out) {
        std::vector<std::string> args{"render", "analytic:torus:33", "--iso", "0", "--depth", "6", "--size", "120x90",
                                      "--light", "1,0.2,0.1", "--verify", "-o", s.path(out), "--stats", s.path(out + ".json")};
        args.insert(args.end(), extra.begin(), extra.end());
        return run(args);
    };
    Result r = render({}, "off.png");
    ASSERT_EQ(r.code, 0) << r.err;
    std::string js = slurp(s.path("off.png.json"));
    EXPECT_NE(js.find("\"shadows\": \"off\""), std::string::npos) << js;
    EXPECT_NE(js.find("\"shadow_rays\": 0,"), std::string::npos) << js;
    for (const char* renderer : {"full", "area-exact", "direct"}) {
        const std::string out = std::string(renderer) + ".png";
        r = render({"--shadows", "on", "--renderer", renderer}, out);
        ASSERT_EQ(r.code, 0) << r.err;
        js = slurp(s.path(out + ".json"));
        EXPECT_NE(js.find("\"shadows\": \"on\""), std::string::npos) << js;
        EXPECT_EQ(js.find("\"shadow_rays\": 0,"), std::string::npos) << js;
        EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
    }
    // The torus shadows its own far side: the light's share is gone there.
    EXPECT_NE(slurp(s.path("full.png")), slurp(s.path("off.png")));
    EXPECT_EQ(slurp(s.path("full.png")), slurp(s.path("area-exact.png")));
    // Baked light keeps its own shadows: --shadows on is told and traces nothing.
    r = render({"--shadows", "on", "--lighting", "baked"}, "baked.png");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("baked light"), std::string::npos) << r.err;
    EXPECT_NE(slurp(s.path("baked.png.json")).find("\"shadow_rays\": 0,"), std::string::npos);
    EXPECT_EQ(render({"--shadows", "yes"}, "x.png").code, 2);
}
