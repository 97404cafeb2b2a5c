#include "CliRunner.h"

#include <regex>

using namespace octrace::testcli;

TEST(Cli, HelpAndVersionExitZero) {
    EXPECT_EQ(run({"--help"}).code, 0);
    Result v = run({"--version"});
    EXPECT_EQ(v.code, 0);
    EXPECT_NE(v.out.find("octrace "), std::string::npos);
    for (const char* cmd : {"render", "info", "sample"}) {
        Result h = run({cmd, "--help"});
        EXPECT_EQ(h.code, 0) << cmd;
        EXPECT_NE(h.out.find("usage:"), std::string::npos) << cmd;
    }
}

TEST(Cli, RenderHelpStatesADefaultForEveryOptionThatHasOne) {
    Result h = run({"render", "--help"});
    ASSERT_EQ(h.code, 0);
    for (const char* opt : {"--var", "--iso", "--depth", "--renderer", "--size", "--camera-pos", "--look-at", "--up", "--fov",
                            "--threads", "--stats", "--verify", "--background", "--light", "--colour", "--colormap",
                            "--region", "--vertical-scale", "--max-memory"})
        EXPECT_NE(h.out.find(opt), std::string::npos) << opt;
    // Every option line that takes a value says its default (or that it is required).
    std::istringstream in(h.out);
    std::vector<std::string> all;
    for (std::string l; std::getline(in, l);) {
        if (!all.empty() && l.rfind("      ", 0) == 0) all.back() += l;  // wrapped help text
        else all.push_back(l);
    }
    for (const std::string& line : all) {
        if (line.rfind("  --", 0) != 0 && line.rfind("  -o", 0) != 0) continue;
        bool takesValue = std::regex_search(line, std::regex("^  --?[a-z-]+ [A-Z]"));
        if (takesValue && line.find("--stats") == std::string::npos && line.find("-o ") == std::string::npos) {
            EXPECT_TRUE(line.find("default") != std::string::npos) << line;
        }
    }
}

TEST(Cli, CommandLineMistakesExitTwoWithAUsageHint) {
    const std::vector<std::vector<std::string>> cases = {
        {"frobnicate"},
        {"render"},
        {"render", "analytic:sphere"},
        {"render", "analytic:sphere", "-o", "x.png", "--bogus"},
        {"render", "analytic:sphere", "-o", "x.png", "--size", "12x"},
        {"render", "analytic:sphere", "-o", "x.png", "--size", "0x10"},
        {"render", "analytic:sphere", "-o", "x.png", "--iso", "abc"},
        {"render", "analytic:sphere", "-o", "x.png", "--depth", "99"},
        {"render", "analytic:sphere", "-o", "x.png", "--renderer", "magic"},
        {"render", "analytic:sphere", "-o", "x.png", "--fov", "180"},
        {"render", "analytic:sphere", "-o", "x.png", "--background", "1,2,3"},
        {"render", "analytic:sphere", "-o", "x.png", "--light", "0,0,0"},
        {"render", "analytic:sphere", "-o", "x.png", "--colormap", "rainbowish"},
        {"render", "analytic:sphere", "-o", "x.png", "--region", "1,2,3"},
        {"render", "analytic:sphere", "-o", "x.jpg"},
        {"render", "analytic:sphere", "-o", "x.png", "--depth"},
        {"info"},
    };
    for (const auto& c : cases) {
        Result r = run(c);
        std::string joined;
        for (const auto& a : c) joined += a + " ";
        EXPECT_EQ(r.code, 2) << joined << "\n" << r.err;
        EXPECT_NE(r.err.find("--help"), std::string::npos) << joined << "\n" << r.err;
        EXPECT_FALSE(std::filesystem::exists("x.png"));
    }
}

TEST(Cli, ProblemsWithTheInputExitOneNamingTheFile) {
    Scratch s;
    const std::string out = s.path("o.png");
    Result missing = run({"render", "/nonexistent/field.nc", "-o", out});
    EXPECT_EQ(missing.code, 1);
    EXPECT_NE(missing.err.find("/nonexistent/field.nc"), std::string::npos) << missing.err;
    Result iso = run({"render", "analytic:sphere:17", "--iso", "5", "-o", out});
    EXPECT_EQ(iso.code, 1);
    EXPECT_NE(iso.err.find("outside the value range"), std::string::npos) << iso.err;
    Result var = run({"render", "analytic:sphere:17", "--var", "pressure", "-o", out});
    EXPECT_EQ(var.code, 1);
    EXPECT_NE(var.err.find("pressure"), std::string::npos) << var.err;
    EXPECT_FALSE(std::filesystem::exists(out));
    // One line of message, no crash.
    EXPECT_EQ(std::count(iso.err.begin(), iso.err.end(), '\n'), 1) << iso.err;
}

TEST(Cli, AnOutputThatCannotBeWrittenExitsOneAndLeavesNothing) {
    Scratch s;
    Result r = run({"render", "analytic:sphere:17", "--depth", "5", "--size", "64x48", "-o", s.path("no/such/dir/x.png")});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_NE(r.err.find("no/such/dir"), std::string::npos) << r.err;
    EXPECT_EQ(countEntries(s.dir()), 0);
}

TEST(Cli, RendersAnAnalyticSphereToPngAndExrAndWritesStats) {
    Scratch s;
    for (const char* ext : {"png", "exr"}) {
        std::string out = s.path(std::string("sphere.") + ext), stats = s.path(std::string("stats_") + ext + ".json");
        Result r = run({"render", "analytic:sphere:33", "--iso", "0", "--depth", "6", "--size", "160x120", "-o", out,
                        "--stats", stats, "--verify", "--threads", "2"});
        ASSERT_EQ(r.code, 0) << r.err;
        ASSERT_TRUE(std::filesystem::exists(out));
        EXPECT_GT(std::filesystem::file_size(out), 100u);
        std::string js = slurp(stats);
        for (const char* key : {"\"renderer\"", "\"width\"", "\"height\"", "\"threads\"", "\"pixels\"", "\"rays\"",
                                "\"render_ms\"", "\"build_ms\"", "\"load_ms\"", "\"us_per_ray\"", "\"boundary_voxels\"",
                                "\"octree_bytes\"", "\"bytes_per_voxel\"", "\"mismatched_pixels\"", "\"psnr_db\"",
                                "\"max_channel_error\""})
            EXPECT_NE(js.find(key), std::string::npos) << key << "\n" << js;
        EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
        EXPECT_NE(js.find("\"width\": 160,"), std::string::npos) << js;
    }
    EXPECT_EQ(countEntries(s.dir()), 4);  // two images, two stats; no temporaries
}

TEST(Cli, ImagesAreByteIdenticalForOneTwoAndSevenThreads) {
    Scratch s;
    for (const char* ext : {"png", "exr"}) {
        std::string first;
        for (const char* t : {"1", "2", "7"}) {
            std::string out = s.path(std::string("t") + t + "." + ext);
            Result r = run({"render", "analytic:noise:33", "--iso", "0", "--depth", "7", "--size", "200x150", "--threads", t,
                            "-o", out});
            ASSERT_EQ(r.code, 0) << r.err;
            std::string bytes = slurp(out);
            if (first.empty()) first = bytes;
            else EXPECT_TRUE(bytes == first) << ext << " differs with --threads " << t;
        }
    }
}

TEST(Cli, InfoDescribesEachInputAndGoesOnAfterABadOne) {
    Result r = run({"info", "analytic:torus:9", "/nonexistent.nrrd", "analytic:sphere:9"});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.out.find("torus"), std::string::npos);
    EXPECT_NE(r.out.find("sphere"), std::string::npos);
    EXPECT_NE(r.err.find("/nonexistent.nrrd"), std::string::npos);
}

TEST(Cli, RendersTheLevitusTemperatureIsosurfaceExactlyAsTheReference) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    Result r = run({"render", lev, "--var", "TEMP", "--iso", "10", "--region", "120,180,10,60", "--depth", "8", "--size",
                    "400x300", "--verify", "--stats", s.path("st.json"), "-o", s.path("lev.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    std::string js = slurp(s.path("st.json"));
    EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
    EXPECT_NE(js.find("\"variable\": \"TEMP\""), std::string::npos) << js;
    EXPECT_EQ(js.find("\"hits\": 0,"), std::string::npos) << js;
}

TEST(Cli, TheCommittedDataSamplesAreWhatOctraceSampleWrites) {
    Scratch s;
    for (const char* name : {"sphere", "torus"}) {
        std::string out = s.path(std::string(name) + ".nrrd");
        Result r = run({"sample", name, "--samples", "33", "-o", out});
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_TRUE(slurp(out) == slurp(std::string(OCTRACE_SAMPLES) + "/" + name + ".nrrd")) << name;
    }
    // And they render: the torus sample, exactly as the reference.
    Result r = run({"render", std::string(OCTRACE_SAMPLES) + "/torus.nrrd", "--iso", "0", "--depth", "6", "--size", "120x90",
                    "--verify", "--stats", s.path("t.json"), "-o", s.path("t.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(slurp(s.path("t.json")).find("\"mismatched_pixels\": 0,"), std::string::npos);
}
