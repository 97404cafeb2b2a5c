// octrace csg and the cut-away options of render: operands of every kind, exit codes, images.
#include "CliRunner.h"
#include "../io/ImageTestSupport.h"

#include <gtest/gtest.h>

using namespace octrace::testcli;

namespace {
std::string numberAfter(const std::string& json, const std::string& key) {
    const auto at = json.find("\"" + key + "\": ");
    if (at == std::string::npos) return {};
    const auto start = at + key.size() + 4;
    return json.substr(start, json.find_first_of(",\n}", start) - start);
}
}  // namespace

TEST(CliCsg, CombinesFieldsOctreeFilesAndSolids) {
    Scratch s;
    Result r = run({"build", "analytic:sphere:33", "--iso", "0", "--depth", "6", "--form", "volume", "-o", s.path("s.oct")});
    ASSERT_EQ(r.code, 0) << r.err;
    // An octree file minus a solid; a field (its volume built on the fly) union a solid.
    r = run({"csg", s.path("s.oct"), "difference", "box:0,0,0,1,1,1", "-o", s.path("d.oct"), "--stats", s.path("d.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("d.json"));
    for (const char* k : {"\"operation\": \"difference\"", "\"form\": \"volume\"", "\"csg_ms\"", "\"volume_voxels\""})
        EXPECT_NE(js.find(k), std::string::npos) << k << "\n" << js;
    r = run({"info", s.path("d.oct")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("difference (box:0,0,0,1,1,1)"), std::string::npos) << r.out;
    r = run({"render", s.path("d.oct"), "--size", "160x120", "-o", s.path("d.png"), "--verify", "--stats", s.path("r.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(numberAfter(slurp(s.path("r.json")), "mismatched_pixels"), "0");
    r = run({"csg", "analytic:sphere:33", "union", "cylinder:0,0,-2,0,0,2,0.2", "--iso", "0", "--depth", "6", "-o", s.path("u.oct")});
    ASSERT_EQ(r.code, 0) << r.err;
    // Commutative: the same file whichever operand comes first.
    r = run({"csg", "cylinder:0,0,-2,0,0,2,0.2", "union", "analytic:sphere:33", "--iso", "0", "--depth", "6", "-o", s.path("u2.oct")});
    ASSERT_EQ(r.code, 0) << r.err;
    // The provenance differs (the operand order is stated); compare the octrees by their images.
    ASSERT_EQ(run({"render", s.path("u.oct"), "--size", "120x90", "-o", s.path("u.png")}).code, 0);
    ASSERT_EQ(run({"render", s.path("u2.oct"), "--size", "120x90", "-o", s.path("u2.png")}).code, 0);
    EXPECT_EQ(slurp(s.path("u.png")), slurp(s.path("u2.png")));
    // Two octree files.
    r = run({"csg", s.path("d.oct"), "intersection", s.path("u.oct"), "-o", s.path("i.oct")});
    EXPECT_EQ(r.code, 0) << r.err;
}

TEST(CliCsg, RefusesBadOperandsWithTheRightExitCode) {
    Scratch s;
    ASSERT_EQ(run({"build", "analytic:sphere:17", "--iso", "0", "--depth", "4", "-o", s.path("shell.oct")}).code, 0);
    Result r = run({"csg", s.path("shell.oct"), "union", "box:0,0,0,1,1,1", "-o", s.path("x.oct")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("a shell octree; CSG needs the volume form"), std::string::npos) << r.err;
    r = run({"csg", "box:0,0,0,1,1,1", "union", "sphere:0,0,0,1", "-o", s.path("x.oct")});
    EXPECT_EQ(r.code, 2);
    r = run({"csg", "analytic:sphere:17", "xor", "box:0,0,0,1,1,1", "-o", s.path("x.oct")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("unknown CSG operation 'xor'"), std::string::npos) << r.err;
    r = run({"csg", "analytic:sphere:17", "union", "box:0,0,0,1,1", "-o", s.path("x.oct")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("box: expected 6 numbers, got 5"), std::string::npos) << r.err;
    EXPECT_EQ(run({"csg", "analytic:sphere:17", "union", "-o", s.path("x.oct")}).code, 2);
    EXPECT_EQ(run({"csg", s.path("missing.oct"), "union", "box:0,0,0,1,1,1", "-o", s.path("x.oct")}).code, 1);
    r = run({"csg", "analytic:sphere:17", "intersection", "sphere:5,5,5,1", "--iso", "0", "-o", s.path("x.oct")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("the result is empty"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(s.path("x.oct")));
}

TEST(CliCsg, RenderCutsAndClipsASolidAway) {
    Scratch s;
    const std::vector<std::string> base{"render", "analytic:sphere:33", "--iso", "0", "--depth", "6", "--size", "160x120",
                                        "--camera-pos", "2.5,2,1.5", "--look-at", "0,0,0", "--up", "0,0,1"};
    auto with = [&](std::vector<std::string> extra, const std::string& out) {
        std::vector<std::string> a = base;
        a.insert(a.end(), extra.begin(), extra.end());
        a.push_back("-o");
        a.push_back(s.path(out));
        a.push_back("--verify");
        a.push_back("--stats");
        a.push_back(s.path(out + ".json"));
        return run(a);
    };
    Result r = with({}, "whole.png");
    ASSERT_EQ(r.code, 0) << r.err;
    r = with({"--cut", "box:0,0,0,1,1,1"}, "cut.png");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(numberAfter(slurp(s.path("cut.png.json")), "mismatched_pixels"), "0");
    r = with({"--cut", "sphere:0,0,0,0.5", "--clip"}, "clip.png");
    ASSERT_EQ(r.code, 0) << r.err;
    r = with({"--cut", "halfspace:0,0,0,1,1,1"}, "half.png");
    ASSERT_EQ(r.code, 0) << r.err;
    r = with({"--cut", "cylinder:0,0,-2,0,0,2,0.3"}, "cyl.png");
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* o : {"cut.png", "clip.png", "half.png", "cyl.png"}) EXPECT_NE(slurp(s.path(o)), slurp(s.path("whole.png"))) << o;
    EXPECT_NE(slurp(s.path("cut.png")), slurp(s.path("clip.png")));
    // The clipped sphere of radius 0.5 holds fewer boundary voxels than the sphere of 0.7.
    EXPECT_LT(std::stod(numberAfter(slurp(s.path("clip.png.json")), "boundary_voxels")),
              std::stod(numberAfter(slurp(s.path("whole.png.json")), "boundary_voxels")));
    // Usage errors and a shell octree file that cannot be cut.
    EXPECT_EQ(with({"--cut", "cone:1,2,3"}, "x.png").code, 2);
    EXPECT_EQ(with({"--clip"}, "x.png").code, 2);
    ASSERT_EQ(run({"build", "analytic:sphere:17", "--iso", "0", "--depth", "4", "-o", s.path("shell.oct")}).code, 0);
    r = run({"render", s.path("shell.oct"), "--cut", "box:0,0,0,1,1,1", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("a shell octree cannot be cut"), std::string::npos) << r.err;
}

TEST(CliCsg, OceanMinusTheSeaFloorOfARelief) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf"), etopo = sharedData("ocean/etopo20.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf") || !haveShared("ocean/etopo20.cdf")) GTEST_SKIP() << "shared data absent";
    Scratch s;
    // The water column of the NE Atlantic extended to the grid's bottom, then cut by ETOPO20's
    // sea floor: what lies under the relief and what lies over it make up the whole.
    const std::vector<std::string> field{"--var", "TEMP", "--iso", "2.108", "--region", "-25,5,40,60", "--extend-down", "--depth", "7"};
    auto csgStats = [&](const std::string& op, const std::string& name) {
        std::vector<std::string> a{"csg", lev, op, "relief:" + etopo, "-o", s.path(name + ".oct"), "--stats", s.path(name + ".json")};
        a.insert(a.end(), field.begin(), field.end());
        const Result r = run(a);
        EXPECT_EQ(r.code, 0) << r.err;
        return std::stod(numberAfter(slurp(s.path(name + ".json")), "volume_voxels"));
    };
    std::vector<std::string> whole{"build", lev, "--form", "volume", "-o", s.path("w.oct"), "--stats", s.path("w.json")};
    whole.insert(whole.end(), field.begin(), field.end());
    Result r = run(whole);
    ASSERT_EQ(r.code, 0) << r.err;
    const double water = csgStats("difference", "water"), ground = csgStats("intersection", "ground");
    ASSERT_EQ(run({"csg", s.path("w.oct"), "union", "box:0,0,0,1,1,1", "-o", s.path("w2.oct"), "--stats", s.path("w2.json")}).code, 0);
    const double all = std::stod(numberAfter(slurp(s.path("w2.json")), "volume_voxels"));
    EXPECT_GT(water, 0.3 * all);
    EXPECT_GT(ground, 0.05 * all);
    EXPECT_NEAR((water + ground) / all, 1.0, 0.01);
    // The relief's info names it; rendering the cut agrees with the reference traversal.
    r = run({"info", s.path("water.oct")});
    EXPECT_NE(r.out.find("difference (relief:" + etopo + ")"), std::string::npos) << r.out;
    std::vector<std::string> render{"render", lev, "--cut", "relief:" + etopo, "--size", "160x120", "--verify", "-o", s.path("r.png"),
                                    "--stats", s.path("r.json"), "--camera-pos", "-1500,-3000,-2600", "--look-at", "0,0,100", "--up", "0,0,1"};
    render.insert(render.end(), field.begin(), field.end());
    r = run(render);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(numberAfter(slurp(s.path("r.json")), "mismatched_pixels"), "0");
    // A relief needs a geographic field to be laid into; bad specs are usage errors.
    r = run({"render", s.path("w.oct"), "--cut", "relief:" + etopo, "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("is not a geographic field"), std::string::npos) << r.err;
    EXPECT_EQ(run({"render", lev, "--cut", "relief:", "-o", s.path("x.png")}).code, 2);
    r = run({"render", lev, "--var", "TEMP", "--depth", "5", "--cut", "relief:" + s.path("none.cdf"), "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("no such file"), std::string::npos) << r.err;
    r = run({"render", lev, "--var", "TEMP", "--depth", "5", "--cut", "relief:" + lev, "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("exactly one 2-D variable"), std::string::npos) << r.err;
    r = run({"render", "analytic:sphere:17", "--extend-down", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("--extend-down applies to geographic fields"), std::string::npos) << r.err;
}

TEST(CliCsg, ACutFaceShowsTheWindowGreyOfTheFieldUnderIt) {
    Scratch s;
    // The sphere field is 0.7 - r: cut in half and seen face on, lit from the camera, its cut
    // face is greyed by the window 0..0.7 (centre 0.35, width 0.7): white at the centre,
    // darkening to the rim, as the field does.
    const Result r = run({"render", "analytic:sphere:65", "--iso", "0", "--depth", "7", "--cut", "halfspace:0,0,0,-1,0,0",
                          "--window", "0.35,0.7", "--camera-pos", "3,0,0", "--look-at", "0,0,0", "--up", "0,0,1", "--fov", "30",
                          "--light", "0,0,1", "--size", "101x101", "-o", s.path("w.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const auto png = octrace::test::decodePng(octrace::test::readBytes(s.path("w.png")));
    auto grey = [&](int x) {
        EXPECT_EQ(png.at(x, 50, 0), png.at(x, 50, 1)) << x;
        EXPECT_EQ(png.at(x, 50, 1), png.at(x, 50, 2)) << x;
        return int(png.at(x, 50, 0));
    };
    EXPECT_GT(grey(50), 200);
    // 0.55 from the centre (pixel 85 at 0.804 world units per 50.5 pixels) the field is 0.15.
    EXPECT_LT(grey(85), grey(50) - 80);
    EXPECT_GT(grey(60), grey(70));
    EXPECT_GT(grey(70), grey(80));
}
