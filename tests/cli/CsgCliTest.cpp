// octrace csg and the cut-away options of render: operands of every kind, exit codes, images.
#include "CliRunner.h"

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
