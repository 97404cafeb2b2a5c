// The ocean options of the CLI end to end: --var sound_speed, --depth-range and --time on
// render, export and info (the Levitus climatology; skipped without ../shared/data).
#include "CliRunner.h"

using namespace octrace::testcli;

namespace {

const char* kLevitus = "ocean/levitus_climatology.cdf";

}  // namespace

TEST(OceanCli, SoundSpeedIsDerivedFromLevitusTemperatureAndSalinityAndRendered) {
    const std::string lev = sharedData(kLevitus);
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    Result r = run({"render", lev, "--var", "sound_speed", "--iso", "1500", "--region", "120,180,10,60", "--depth", "7",
                    "--size", "320x240", "--verify", "--stats", s.path("v.json"), "-o", s.path("v.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* said : {"sound_speed derived from TEMP ('DEG C', in-situ temperature) and SALT ('PPT', practical "
                             "salinity), pressure from depth 'ZAXLEVITR' and latitude 'YAXLEVITR'",
                             "UNESCO 1983 sound speed (Chen and Millero 1977)"})
        EXPECT_NE(r.err.find(said), std::string::npos) << r.err;
    const std::string js = slurp(s.path("v.json"));
    EXPECT_NE(js.find("\"variable\": \"sound_speed\""), std::string::npos) << js;
    EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
    EXPECT_EQ(js.find("\"hits\": 0,"), std::string::npos) << js;

    Result e = run({"export", lev, "--var", "sound_speed", "--iso", "1500", "--region", "120,180,10,60", "--depth-range",
                    "0,2000", "--depth", "6", "-o", s.path("v.ply")});
    ASSERT_EQ(e.code, 0) << e.err;
    EXPECT_NE(slurp(s.path("v.ply")).find("variable: sound_speed (m/s)"), std::string::npos);
}

TEST(OceanCli, InfoDescribesTheRequestedDerivedFieldInItsDepthRange) {
    const std::string lev = sharedData(kLevitus);
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent: " << lev;
    Result r = run({"info", lev, "--var", "sound_speed", "--region", "120,180,10,60", "--depth-range", "0,1000"});
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* said : {"sound_speed: derived from TEMP and SALT with --var sound_speed",
                             "grid of sound_speed in region 120,180,10,60:", "dims: 60 x 50 x 14",
                             "14 levels 0 .. 1000 m (depth range 0,1000 m)"})
        EXPECT_NE(r.out.find(said), std::string::npos) << said << " in:\n" << r.out;
    EXPECT_NE(r.out.find("  values: 14"), std::string::npos) << r.out;  // 14xx m/s
}

TEST(OceanCli, TimeAndDepthRangeAreCheckedOnTheCommandLineAndAgainstTheFile) {
    const std::string lev = sharedData(kLevitus);
    Scratch s;
    // Malformed values: exit 2 before any file is read.
    Result bad = run({"render", "analytic:sphere", "--time", "2001-13-01", "-o", s.path("x.png")});
    EXPECT_EQ(bad.code, 2) << bad.err;
    bad = run({"render", "analytic:sphere", "--depth-range", "500,100", "-o", s.path("x.png")});
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.err.find("Z0 must be less than Z1"), std::string::npos) << bad.err;
    bad = run({"render", "analytic:sphere", "--time", "3", "-o", s.path("x.png")});
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.err.find("--time applies to NetCDF inputs with a time axis"), std::string::npos) << bad.err;
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent: " << lev;
    Result r = run({"render", lev, "--var", "TEMP", "--time", "1", "-o", s.path("t.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("--time 1: variable TEMP(ZAXLEVITR, YAXLEVITR, XAXLEVITR) has no time axis"), std::string::npos)
        << r.err;
    EXPECT_FALSE(std::filesystem::exists(s.path("t.png")));
    r = run({"render", lev, "--var", "TEMP", "--iso", "10", "--depth-range", "100,120", "-o", s.path("t.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("depth range 100,120 m holds 1 level(s), need at least 2"), std::string::npos) << r.err;
}

TEST(OceanCli, SametAndBeamHitTheReferencesVoxelsOnTheLevitusTemperature) {
    // Paper B's tracers on the voxel octree, on real data: the 10 degC isosurface (Table 1's T
    // scene, its camera), every pixel's hit voxel the reference's, the image full's.
    const std::string lev = sharedData(kLevitus);
    if (!haveShared(kLevitus)) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    const std::vector<std::string> scene{"render", lev, "--var", "TEMP", "--iso", "10", "--region", "120,180,10,60",
                                         "--depth", "8", "--size", "320x240", "--camera-pos", "7738.087169,-14069.2494,9870.868124",
                                         "--look-at", "0,0,-681.068925", "--up", "0,0,1", "--fov", "30", "--quiet"};
    for (const std::string renderer : {"samet", "beam"}) {
        std::vector<std::string> args = scene;
        for (const char* a : {"--renderer", renderer.c_str(), "--baseline", "full", "--verify", "--stats"}) args.push_back(a);
        args.push_back(s.path(renderer + ".json"));
        args.push_back("-o");
        args.push_back(s.path(renderer + ".png"));
        Result r = run(args);
        ASSERT_EQ(r.code, 0) << r.err;
        const std::string js = slurp(s.path(renderer + ".json"));
        EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
        EXPECT_NE(js.find("\"baseline_differing_pixels\": 0,"), std::string::npos) << js;
        EXPECT_EQ(js.find("\"hits\": 0,"), std::string::npos) << js;
    }
}
