#include "CliRunner.h"

#include <regex>

using namespace octrace::testcli;

TEST(Cli, HelpAndVersionExitZero) {
    EXPECT_EQ(run({"--help"}).code, 0);
    Result v = run({"--version"});
    EXPECT_EQ(v.code, 0);
    EXPECT_NE(v.out.find("octrace "), std::string::npos);
    for (const char* cmd : {"render", "export", "info", "sample"}) {
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
                            "--region", "--vertical-scale", "--projection", "--ortho-height", "--lod", "--level",
                            "--max-memory"})
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
        // Options a renderer would silently ignore.
        {"render", "analytic:sphere", "-o", "x.png", "--renderer", "samet", "--colour-coherence"},
        {"render", "analytic:sphere", "-o", "x.png", "--renderer", "direct", "--colour-coherence"},
        {"render", "analytic:sphere", "-o", "x.png", "--renderer", "beam", "--lod", "2"},
        {"export"},
        {"export", "analytic:sphere"},
        {"export", "analytic:sphere", "analytic:torus", "-o", "x.ply"},
        {"export", "analytic:sphere", "-o", "x.obj"},
        {"export", "analytic:sphere", "-o", "x.ply", "--format", "obj"},
        {"export", "analytic:sphere", "-o", "x.ply", "--bogus"},
        {"export", "analytic:sphere", "-o", "x.ply", "--level", "0"},
        {"export", "analytic:sphere", "-o", "x.ply", "--depth", "5", "--level", "6"},
        {"export", "analytic:sphere", "-o", "x.ply", "--ascii=yes"},
        {"export", "analytic:sphere", "-o", "x.ply", "--colormap", "rainbowish"},
        {"export", "analytic:sphere", "-o", "x.ply", "--iso", "abc"},
        {"export", "analytic:sphere", "-o", "x.ply", "--region", "0,10,0,10"},
        {"info"},
    };
    for (const auto& c : cases) {
        Result r = run(c);
        std::string joined;
        for (const auto& a : c) joined += a + " ";
        EXPECT_EQ(r.code, 2) << joined << "\n" << r.err;
        EXPECT_NE(r.err.find("--help"), std::string::npos) << joined << "\n" << r.err;
        EXPECT_FALSE(std::filesystem::exists("x.png"));
        EXPECT_FALSE(std::filesystem::exists("x.ply"));
        EXPECT_FALSE(std::filesystem::exists("x.obj"));
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

TEST(Cli, DirectRendererReportsHitAgreementAndDepthErrorAgainstTheReference) {
    Scratch s;
    for (const char* projection : {"perspective", "ortho"}) {
        const std::string stats = s.path(std::string("direct_") + projection + ".json");
        Result r = run({"render", "analytic:torus:33", "--iso", "0", "--depth", "6", "--size", "160x120", "--renderer",
                        "direct", "--projection", projection, "--verify", "--stats", stats, "-o",
                        s.path(std::string("direct_") + projection + ".png")});
        ASSERT_EQ(r.code, 0) << r.err;
        const std::string js = slurp(stats);
        std::smatch m;
        ASSERT_TRUE(std::regex_search(js, m, std::regex("\"hit_agreement\": ([0-9.e+-]+)"))) << js;
        EXPECT_GE(std::stod(m[1]), 0.99) << js;
        ASSERT_TRUE(std::regex_search(js, m, std::regex("\"depth_max_error_voxel_diagonals\": ([0-9.e+-]+)"))) << js;
        EXPECT_LE(std::stod(m[1]), 1.0) << js;
        EXPECT_NE(js.find("\"us_per_ray\": null"), std::string::npos) << js;
        EXPECT_TRUE(std::regex_search(js, std::regex("\"projection\": \"([a-z]+)\"")));
        EXPECT_NE(js.find(projection, js.find("\"projection\"")), std::string::npos) << js;
        EXPECT_NE(r.err.find("voxel footprints drawn"), std::string::npos) << r.err;
    }
}

TEST(Cli, ProjectionMistakesAreUsageErrors) {
    Scratch s;
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"--projection", "fisheye"}, {"--ortho-height", "-1"}, {"--ortho-height", "2"}}) {
        std::vector<std::string> cmd{"render", "analytic:sphere:9", "--depth", "3", "-o", s.path("x.png")};
        cmd.insert(cmd.end(), args.begin(), args.end());
        Result r = run(cmd);
        EXPECT_EQ(r.code, 2) << args[0] << " " << args[1] << ": " << r.err;
        EXPECT_NE(r.err.find(args[0]), std::string::npos) << r.err;
    }
    EXPECT_EQ(countEntries(s.dir()), 0);
}

TEST(Cli, RefusalsNameTheRenderersThatHonourTheOption) {
    Scratch s;
    Result r = run({"render", "analytic:sphere", "-o", s.path("x.png"), "--renderer", "samet", "--colour-coherence"});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("(use full, linear, area, linear-exact or area-exact)"), std::string::npos) << r.err;
    r = run({"render", "analytic:sphere", "-o", s.path("x.png"), "--renderer", "beam", "--level", "3"});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("(use full, tile, reference, reference-unquantized, direct or direct-f2b)"), std::string::npos) << r.err;
    const Result h = run({"render", "--help"});
    EXPECT_NE(h.out.find("renderers full, tile, reference, reference-unquantized, direct or direct-f2b"), std::string::npos);
}

TEST(Cli, ColourOptionsWithoutColourCoherenceAreToldToChangeNothing) {
    Scratch s;
    // full: a discrete ray caster, which reads them with --colour-coherence (tile, the default, never).
    Result r = run({"render", "analytic:sphere", "--iso", "0", "--depth", "5", "--size", "64x48", "--renderer", "full",
                    "--colour-tolerance", "5", "--colour-fill-background", "-o", s.path("a.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("--colour-tolerance has no effect without --colour-coherence"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("--colour-fill-background has no effect without --colour-coherence"), std::string::npos) << r.err;
    r = run({"render", "analytic:sphere", "--iso", "0", "--depth", "5", "--size", "64x48", "--renderer", "samet",
             "--colour-tolerance", "5", "-o", s.path("c.png")});
    EXPECT_NE(r.err.find("--colour-tolerance has no effect on renderer samet (only on the discrete ray casters)"), std::string::npos) << r.err;
    // A +colour name turns colour coherence on as --colour-coherence does: the same image and
    // stats (renderer area+colour, the tolerance recorded) both ways.
    r = run({"render", "analytic:sphere", "--iso", "0", "--depth", "5", "--size", "64x48", "--renderer", "area+colour",
             "--colour-tolerance", "5", "-o", s.path("b.png"), "--stats", s.path("b.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err.find("no effect"), std::string::npos) << r.err;
    r = run({"render", "analytic:sphere", "--iso", "0", "--depth", "5", "--size", "64x48", "--renderer", "area",
             "--colour-coherence", "--colour-tolerance", "5", "-o", s.path("d.png"), "--stats", s.path("d.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err.find("no effect"), std::string::npos) << r.err;
    EXPECT_EQ(slurp(s.path("b.png")), slurp(s.path("d.png")));
    for (const char* json : {"b.json", "d.json"}) {
        const std::string stats = slurp(s.path(json));
        EXPECT_NE(stats.find("\"renderer\": \"area+colour\""), std::string::npos) << stats;
        EXPECT_NE(stats.find("\"colour_tolerance\": 5"), std::string::npos) << stats;
    }
}

TEST(Cli, BranchUpIsRecordedWarnedAboutWhereUselessAndRangeChecked) {
    Scratch s;
    Result r = run({"render", "analytic:sphere", "--iso", "0", "--depth", "5", "--size", "64x48", "--renderer", "area",
                    "--branch-up", "2", "--stats", s.path("a.json"), "-o", s.path("a.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err.find("no effect"), std::string::npos) << r.err;
    EXPECT_NE(slurp(s.path("a.json")).find("\"branch_up\": 2"), std::string::npos);
    r = run({"render", "analytic:sphere", "--iso", "0", "--depth", "5", "--size", "64x48", "--branch-up", "1", "-o",
             s.path("b.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("--branch-up has no effect on renderer tile"), std::string::npos) << r.err;
    r = run({"render", "analytic:sphere", "--renderer", "linear", "--branch-up", "-1", "-o", s.path("c.png")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--branch-up"), std::string::npos) << r.err;
}

TEST(Cli, MissCoherenceIsOnByDefaultRecordedWarnedAboutWhereUselessAndChecked) {
    Scratch s;
    const std::vector<std::string> torus = {"render", "analytic:torus", "--iso", "0", "--depth", "6", "--size", "96x72",
                                            "--renderer", "area"};
    auto with = [&](std::vector<std::string> extra, const std::string& name) {
        std::vector<std::string> args = torus;
        extra.insert(extra.end(), {"--stats", s.path(name + ".json"), "-o", s.path(name + ".png")});
        args.insert(args.end(), extra.begin(), extra.end());
        return run(args);
    };
    Result r = with({}, "on");
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string on = slurp(s.path("on.json"));
    EXPECT_NE(on.find("\"miss_coherence\": \"on\""), std::string::npos) << on;
    EXPECT_NE(on.find("\"miss_filled\": "), std::string::npos) << on;
    EXPECT_EQ(on.find("\"miss_filled\": 0"), std::string::npos) << "the torus's hole lies between misses";
    r = with({"--miss-coherence", "off"}, "off");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err.find("no effect"), std::string::npos) << r.err;
    const std::string off = slurp(s.path("off.json"));
    EXPECT_NE(off.find("\"miss_coherence\": \"off\""), std::string::npos) << off;
    EXPECT_NE(off.find("\"miss_filled\": 0"), std::string::npos) << off;
    for (const char* renderer : {"full", "area-exact"}) {
        r = run({"render", "analytic:torus", "--iso", "0", "--depth", "5", "--size", "64x48", "--renderer", renderer,
                 "--miss-coherence", "on", "-o", s.path("w.png")});
        ASSERT_EQ(r.code, 0) << r.err;
        EXPECT_NE(r.err.find("--miss-coherence has no effect on renderer " + std::string(renderer)), std::string::npos) << r.err;
    }
    r = run({"render", "analytic:torus", "--renderer", "area", "--miss-coherence", "maybe", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--miss-coherence: choose on or off"), std::string::npos) << r.err;
}

TEST(Cli, VerifyTellsWhenItStartsAndPrintsTheImageDifference) {
    Scratch s;
    const Result r = run({"render", "analytic:sphere", "--iso", "0", "--depth", "6", "--size", "120x90", "--renderer",
                          "area+colour", "--verify", "-o", s.path("v.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("verifying: rendering the frame again with the reference traversal"), std::string::npos) << r.err;
    EXPECT_TRUE(std::regex_search(r.err, std::regex("PSNR [0-9.inf]+ dB \\(max channel error [0-9]+\\)"))) << r.err;
}

TEST(Cli, MultiResolutionRendersTheSameCutAsTheReferenceAndReportsItsDifference) {
    Scratch s;
    const std::string stats = s.path("lod.json");
    Result r = run({"render", "analytic:noise:33", "--iso", "0", "--depth", "7", "--size", "200x150", "--lod", "6", "--verify",
                    "--stats", stats, "-o", s.path("lod.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(stats);
    EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(js, m, std::regex("\"lod_psnr_db\": ([0-9.e+-]+)"))) << js;
    EXPECT_GT(std::stod(m[1]), 10.0);
    EXPECT_NE(js.find("\"lod\": 6,"), std::string::npos) << js;
    // Renderers without a multi-resolution mode, and levels below the octree, are refused up front.
    Result bad = run({"render", "analytic:noise:33", "--iso", "0", "--depth", "7", "--renderer", "area", "--lod", "2", "-o",
                      s.path("bad.png")});
    EXPECT_EQ(bad.code, 2);
    EXPECT_NE(bad.err.find("multi-resolution"), std::string::npos) << bad.err;
    Result deep = run({"render", "analytic:noise:33", "--depth", "5", "--level", "6", "-o", s.path("deep.png")});
    EXPECT_EQ(deep.code, 2);
    EXPECT_NE(deep.err.find("--level"), std::string::npos) << deep.err;
}
