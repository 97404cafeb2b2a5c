// Sphere scenes through the CLI: molecule files, SphereFlake and random spheres traced in the
// object octree by reference, samet and beam (each verified against the reference and the brute
// force), voxelized for the voxel renderers, octrace info, and the usage and input errors.
#include "CliRunner.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

using namespace octrace::testcli;

namespace {

/// The number after "KEY": in a stats JSON (NaN when absent).
double statNumber(const std::string& js, const std::string& key) {
    const auto p = js.find("\"" + key + "\": ");
    if (p == std::string::npos) return std::nan("");
    return std::strtod(js.c_str() + p + key.size() + 4, nullptr);
}

/// Renders INPUT with RENDERER and --verify; returns the stats.
std::string renderVerified(const Scratch& s, const std::string& input, const std::string& renderer,
                           const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args{"render", input, "--renderer", renderer, "--size", "96x72", "--verify", "--quiet",
                                  "-o", s.path(renderer + ".png"), "--stats", s.path(renderer + ".json")};
    args.insert(args.end(), extra.begin(), extra.end());
    Result r = run(args);
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(std::filesystem::exists(s.path(renderer + ".png")));
    return slurp(s.path(renderer + ".json"));
}

}  // namespace

TEST(SphereCli, EveryTracerHitsWhatTheReferenceAndTheBruteForceHitOnGeneratedScenes) {
    Scratch s;
    for (const std::string input : {"sphereflake:2", "random:400:3"})
        for (const std::string renderer : {"samet", "beam", "reference"}) {
            const std::string js = renderVerified(s, input, renderer, {"--samples", "4"});
            EXPECT_EQ(statNumber(js, "mismatched_pixels"), 0.0) << input << " " << renderer << js;
            EXPECT_EQ(statNumber(js, "mismatched_pixels_brute_force"), 0.0) << input << " " << renderer << js;
            EXPECT_GT(statNumber(js, "hits"), 0.0) << js;
            EXPECT_NE(js.find("\"octree\": \"object\""), std::string::npos) << js;
            EXPECT_EQ(statNumber(js, "samples"), 4.0);
            EXPECT_EQ(statNumber(js, "pixels"), 96.0 * 72.0);
        }
}

TEST(SphereCli, SamplesMultiplyTheRaysAndOptionsReachTheTracer) {
    Scratch s;
    const std::string one = renderVerified(s, "sphereflake:2", "beam", {"--leaf-objects", "2", "--shadows", "off", "--bounces", "0"});
    EXPECT_EQ(statNumber(one, "secondary_rays"), 0.0) << one;  // no shadow, no bounce
    EXPECT_EQ(statNumber(one, "leaf_objects"), 2.0);
    const std::string many = renderVerified(s, "sphereflake:2", "samet", {"--samples", "9", "--bounces", "3"});
    // Rays count the samples that meet the scene cube: about 9 times as many (the edge of the
    // cube's silhouette cuts some pixels' samples apart).
    EXPECT_NEAR(statNumber(many, "rays") / statNumber(one, "rays"), 9.0, 0.05);
    EXPECT_GT(statNumber(many, "secondary_rays"), 0.0);
    EXPECT_GT(statNumber(one, "octree_nodes"), 1.0);
}

TEST(SphereCli, RendersHaemoglobinAsAtoms) {
    const std::string pdb = sharedData("molecule/4HHB.pdb");
    if (!haveShared("molecule/4HHB.pdb")) GTEST_SKIP() << "shared data absent: " << pdb;
    Scratch s;
    for (const std::string renderer : {"beam", "samet"}) {
        const std::string js = renderVerified(s, pdb, renderer);
        EXPECT_EQ(statNumber(js, "spheres"), 4779.0) << js;
        EXPECT_EQ(statNumber(js, "mismatched_pixels"), 0.0) << js;
        EXPECT_EQ(statNumber(js, "mismatched_pixels_brute_force"), 0.0) << js;
        EXPECT_NE(js.find("\"units\": \"angstrom\""), std::string::npos) << js;
    }
    Result info = run({"info", pdb});
    EXPECT_EQ(info.code, 0) << info.err;
    EXPECT_NE(info.out.find("spheres: 4779"), std::string::npos) << info.out;
    EXPECT_NE(info.out.find("not in Bondi 1964) for: FE"), std::string::npos) << info.out;
}

TEST(SphereCli, VoxelRenderersDrawTheSpheresVoxelized) {
    Scratch s;
    const std::string js = renderVerified(s, "sphereflake:2", "full", {"--depth", "6"});
    EXPECT_EQ(statNumber(js, "mismatched_pixels"), 0.0) << js;
    EXPECT_EQ(statNumber(js, "depth"), 6.0);
    EXPECT_GT(statNumber(js, "boundary_voxels"), 0.0);
    // The reference on the voxelized scene when asked for.
    const std::string ref = renderVerified(s, "random:50", "reference", {"--octree", "voxel", "--depth", "7"});
    EXPECT_GT(statNumber(ref, "boundary_voxels"), 0.0) << ref;
    // samet and beam too: the reference's hit voxel in every pixel, with their own counters.
    for (const std::string renderer : {"samet", "beam"}) {
        const std::string js = renderVerified(s, "sphereflake:2", renderer, {"--octree", "voxel", "--depth", "6"});
        EXPECT_EQ(statNumber(js, "mismatched_pixels"), 0.0) << js;
        EXPECT_GT(statNumber(js, "hits"), 1000.0) << js;
        EXPECT_GT(statNumber(js, "nodes_visited"), 0.0) << js;
        if (renderer == "beam") { EXPECT_GT(statNumber(js, "beams"), 0.0) << js; }
    }
}

TEST(SphereCli, TheVoxelizedSpheresAreTheirDistanceFieldsZeroWithoutAskingForAnIso) {
    Scratch s;
    const std::string stats = s.path("iso.json");
    const Result r = run({"render", "random:40:3", "--octree", "voxel", "--depth", "7", "--size", "64x48", "--stats", stats,
                          "-o", s.path("iso.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(r.err.find("no --iso given"), std::string::npos) << r.err;  // nothing for the user to choose
    EXPECT_EQ(statNumber(slurp(stats), "iso"), 0.0);
}

TEST(SphereCli, InfoDescribesGeneratedScenes) {
    Result r = run({"info", "sphereflake:3", "random:25:9"});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("spheres: 820 (820 reflecting or transmitting)"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("spheres: 25"), std::string::npos) << r.out;
}

TEST(SphereCli, BadSpecsAndOptionsAreUsageErrors) {
    Scratch s;
    const std::string out = s.path("x.png");
    const std::vector<std::vector<std::string>> cases = {
        {"sphereflake:5", "the SphereFlake level must be 1..4"},
        {"random:0", "N must be a number of spheres"},
        {"random:5:-1", "the seed must be a non-negative integer"},
        {"sphereflake:2", "--samples: must be a square number", "--samples", "3"},
        {"sphereflake:2", "--bounces: 17 is outside [0, 16]", "--bounces", "17"},
        {"sphereflake:2", "--shadows: choose on or off", "--shadows", "yes"},
        {"sphereflake:2", "--leaf-objects: 0 is outside [1, 100000]", "--leaf-objects", "0"},
        {"sphereflake:2", "renderer full draws voxel octrees only", "--renderer", "full", "--octree", "object"},
        {"sphereflake:2", "--iso applies to voxel octrees", "--renderer", "beam", "--iso", "0"},
        {"analytic:sphere", "--leaf-objects applies to sphere scenes", "--leaf-objects", "4"},
        {"analytic:sphere", "--samples: must be a square number", "--samples", "8"},
        {"analytic:sphere", "--octree applies to sphere inputs", "--octree", "voxel"},
    };
    for (const auto& c : cases) {
        std::vector<std::string> args{"render", c[0], "-o", out};
        args.insert(args.end(), c.begin() + 2, c.end());
        Result r = run(args);
        EXPECT_EQ(r.code, 2) << c[0] << " " << c[1] << ": " << r.err;
        EXPECT_NE(r.err.find(c[1]), std::string::npos) << r.err;
        EXPECT_FALSE(std::filesystem::exists(out));
    }
}

TEST(SphereCli, BrokenMoleculeFilesGiveOneLineAndNoImage) {
    Scratch s;
    const std::string bad = s.path("bad.pdb"), empty = s.path("empty.cif"), out = s.path("x.png");
    {
        std::ofstream f(bad);
        f << "HEADER\nATOM      1  CA  GLY A   1       1.000   abc     3.000  1.00 20.00           C\n";
    }
    { std::ofstream f(empty); }
    const std::vector<std::pair<std::string, std::string>> cases = {
        {bad, "bad.pdb: line 2: ATOM record: coordinate y (columns 39-46) '   abc  ' is not a finite number"},
        {empty, "empty.cif: file is empty (0 bytes)"},
        {s.path("none.pdb"), "none.pdb: no such file"},
    };
    for (const auto& [file, expect] : cases) {
        for (const std::string renderer : {"beam", "full"}) {
            Result r = run({"render", file, "--renderer", renderer, "-o", out});
            EXPECT_EQ(r.code, 1) << r.err;
            EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
            EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
            EXPECT_FALSE(std::filesystem::exists(out));
        }
    }
    Result r = run({"render", bad, "--renderer", "beam", "--max-memory", "1K", "-o", out});
    EXPECT_EQ(r.code, 1) << r.err;
}
