// octrace build and .oct inputs: build once, then render, export and info read the file; the
// image is the one rendered from the field itself; every damaged byte is refused (exit 1).
#include "CliRunner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

using namespace octrace::testcli;

namespace {
std::string readBytes(const std::string& p) { return slurp(p); }
void writeBytes(const std::string& p, const std::string& b) {
    std::ofstream f(p, std::ios::binary | std::ios::trunc);
    f << b;
}
}  // namespace

TEST(CliOctreeFile, BuildThenRenderGivesTheSameImageAsTheField) {
    Scratch s;
    const std::vector<std::string> field{"analytic:torus:33", "--iso", "0", "--depth", "6"};
    std::vector<std::string> build{"build"};
    build.insert(build.end(), field.begin(), field.end());
    for (const char* x : {"-o", ""}) build.push_back(x);
    build.back() = s.path("t.oct");
    build.push_back("--stats");
    build.push_back(s.path("build.json"));
    Result r = run(build);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("shell octree, depth 6"), std::string::npos) << r.err;
    EXPECT_NE(slurp(s.path("build.json")).find("\"file_bytes\""), std::string::npos);

    std::vector<std::string> direct{"render"};
    direct.insert(direct.end(), field.begin(), field.end());
    for (const char* x : {"--size", "160x120", "-o"}) direct.push_back(x);
    direct.push_back(s.path("field.png"));
    ASSERT_EQ(run(direct).code, 0);
    r = run({"render", s.path("t.oct"), "--size", "160x120", "-o", s.path("file.png"), "--verify", "--stats", s.path("r.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(readBytes(s.path("field.png")), readBytes(s.path("file.png")));
    EXPECT_NE(slurp(s.path("r.json")).find("\"mismatched_pixels\": 0,"), std::string::npos);

    r = run({"info", s.path("t.oct")});
    ASSERT_EQ(r.code, 0) << r.err;
    // Version 3: a field's octree carries corner values for smooth surfaces (chunk CRNR).
    for (const char* t : {"octrace octree file, version 3", "form: shell", "depth: 6", "variable: torus", "source: analytic:torus:33",
                          "TREE:", "NORM:", "CRNR:"})
        EXPECT_NE(r.out.find(t), std::string::npos) << t << "\n" << r.out;

    r = run({"export", s.path("t.oct"), "-o", s.path("t.ply")});
    EXPECT_EQ(r.code, 0) << r.err;
    // Options that choose the field do not apply to an octree file.
    r = run({"render", s.path("t.oct"), "--iso", "0.1", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--iso does not apply to the octree file"), std::string::npos) << r.err;
}

TEST(CliOctreeFile, EveryDamagedByteIsRefusedWithExitOne) {
    Scratch s;
    const std::string good = s.path("good.oct"), bad = s.path("bad.oct");
    ASSERT_EQ(run({"build", "analytic:sphere:9", "--iso", "0", "--depth", "2", "-o", good, "--quiet"}).code, 0);
    const std::string bytes = readBytes(good);
    ASSERT_GT(bytes.size(), 60u);
    ASSERT_LT(bytes.size(), 600u);  // with the corner values of smooth surfaces (chunk CRNR)
    // Every byte is flipped in turn by tests/io/OctreeFileTest.cpp (library level: an InputError
    // naming the file, which the CLI maps to exit 1); here a byte in every 11 (a process start
    // per byte costs too long), which reaches the signature, version, header, each chunk's
    // header, data and checksum.
    for (std::size_t i = 0; i < bytes.size(); i += (i < 16 ? 1 : 11)) {
        std::string b = bytes;
        b[i] = char(b[i] ^ 0x10);
        writeBytes(bad, b);
        Result r = run({"info", bad});
        EXPECT_EQ(r.code, 1) << "byte " << i;
        EXPECT_EQ(r.err.rfind("octrace: error: " + bad + ": ", 0), 0u) << "byte " << i << ": " << r.err;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;  // one line
    }
    // Truncated and from the future.
    writeBytes(bad, bytes.substr(0, bytes.size() - 5));
    Result r = run({"render", bad, "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
    std::string future = bytes;
    future[8] = 7;
    writeBytes(bad, future);
    r = run({"render", bad, "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_NE(r.err.find("written by a newer octrace (octree file format version 7"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(s.path("x.png")));
}

TEST(CliOctreeFile, BuildsTheLevitusShellAndReadsItBack) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    Result r = run({"build", lev, "--var", "TEMP", "--iso", "10", "--region", "120,180,10,60", "--depth", "8", "-o", s.path("l.oct")});
    ASSERT_EQ(r.code, 0) << r.err;
    r = run({"render", s.path("l.oct"), "--size", "200x150", "-o", s.path("l.png"), "--verify", "--stats", s.path("l.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("l.json"));
    EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
    EXPECT_NE(js.find("\"variable\": \"TEMP\""), std::string::npos) << js;
    r = run({"info", s.path("l.oct")});
    EXPECT_NE(r.out.find("region 120,180,10,60"), std::string::npos) << r.out;
}

TEST(CliOctreeFile, VolumeFormIsStoredAndDrawnByItsShell) {
    Scratch s;
    Result r = run({"build", "analytic:sphere:33", "--iso", "0", "--depth", "6", "--form", "volume", "-o", s.path("v.oct"),
                    "--stats", s.path("v.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("volume octree, depth 6"), std::string::npos) << r.err;
    EXPECT_NE(slurp(s.path("v.json")).find("\"form\": \"volume\""), std::string::npos);
    r = run({"info", s.path("v.oct")});
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* t : {"form: volume", "inside: value >= iso", "TERM:"}) EXPECT_NE(r.out.find(t), std::string::npos) << t << "\n" << r.out;
    // Drawn by its shell: the same image as the shell of the field, and as the reference.
    r = run({"render", s.path("v.oct"), "--size", "160x120", "-o", s.path("v.png"), "--verify", "--stats", s.path("r.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(slurp(s.path("r.json")).find("\"mismatched_pixels\": 0,"), std::string::npos);
    // A volume octree has no corner values: its shell draws voxel, as the field's does when asked.
    ASSERT_EQ(run({"render", "analytic:sphere:33", "--iso", "0", "--depth", "6", "--size", "160x120", "--surface", "voxel", "-o",
                   s.path("f.png")}).code, 0);
    EXPECT_EQ(slurp(s.path("v.png")), slurp(s.path("f.png")));
    // The outside of the sphere, inside below: caps on the cube's faces hide the sphere.
    r = run({"render", "analytic:sphere:33", "--iso", "0", "--depth", "6", "--form", "volume", "--inside", "below", "--size",
             "160x120", "-o", s.path("b.png"), "--verify", "--stats", s.path("b.json")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(slurp(s.path("b.json")).find("\"mismatched_pixels\": 0,"), std::string::npos);
    EXPECT_NE(slurp(s.path("b.png")), slurp(s.path("f.png")));
    // Usage errors.
    EXPECT_EQ(run({"build", "analytic:sphere:33", "--form", "solid", "-o", s.path("x.oct")}).code, 2);
    r = run({"build", "analytic:sphere:33", "--inside", "below", "-o", s.path("x.oct")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("--inside applies to --form volume"), std::string::npos) << r.err;
    r = run({"render", s.path("v.oct"), "--form", "volume", "-o", s.path("x.png")});
    EXPECT_EQ(r.code, 2);
}
