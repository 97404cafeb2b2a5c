// `octrace export`: surfels as a PLY point cloud, read back with the tests' own PLY reader.
#include "../PlyTestReader.h"
#include "CliRunner.h"

#include <cmath>
#include <cstdlib>

using namespace octrace::testcli;
using octrace::test::parsePly;
using octrace::test::PlyCloud;

namespace {

/// The number after "\"key\": " in a stats JSON text.
double jsonNumber(const std::string& js, const std::string& key) {
    const auto at = js.find("\"" + key + "\": ");
    if (at == std::string::npos) {
        ADD_FAILURE() << "no " << key << " in " << js;
        return 0.0;
    }
    return std::strtod(js.c_str() + at + key.size() + 4, nullptr);
}

/// "X,Y,Z" after "\"key\": \"" in a stats JSON text.
std::vector<double> jsonVec3(const std::string& js, const std::string& key) {
    const auto at = js.find("\"" + key + "\": \"");
    if (at == std::string::npos) {
        ADD_FAILURE() << "no " << key << " in " << js;
        return {0.0, 0.0, 0.0};
    }
    const char* p = js.c_str() + at + key.size() + 5;
    std::vector<double> v;
    for (int i = 0; i < 3; ++i) {
        char* end = nullptr;
        v.push_back(std::strtod(p, &end));
        p = end + 1;
    }
    return v;
}

bool hasComment(const PlyCloud& c, const std::string& text) {
    for (const auto& line : c.comments)
        if (line.find(text) != std::string::npos) return true;
    return false;
}

/// Exports and renders the same surface; checks the cloud against the render's stats:
/// one vertex per boundary voxel, every vertex inside the surface's bounds, unit normals.
PlyCloud exportAndCompare(const std::vector<std::string>& surfaceArgs, const Scratch& s) {
    std::vector<std::string> exp = {"export"}, ren = {"render"};
    exp.insert(exp.end(), surfaceArgs.begin(), surfaceArgs.end());
    ren.insert(ren.end(), surfaceArgs.begin(), surfaceArgs.end());
    exp.insert(exp.end(), {"-o", s.path("cloud.ply")});
    ren.insert(ren.end(), {"--size", "32x24", "--stats", s.path("stats.json"), "-o", s.path("image.png")});
    const Result e = run(exp), r = run(ren);
    EXPECT_EQ(e.code, 0) << e.err;
    EXPECT_EQ(r.code, 0) << r.err;
    const PlyCloud cloud = parsePly(slurp(s.path("cloud.ply")));
    const std::string js = slurp(s.path("stats.json"));
    EXPECT_EQ(cloud.format, "binary_little_endian");
    EXPECT_EQ(cloud.trailingBytes, 0u);
    EXPECT_EQ(double(cloud.vertices.size()), jsonNumber(js, "boundary_voxels"));
    const auto lo = jsonVec3(js, "surface_bounds_min"), hi = jsonVec3(js, "surface_bounds_max");
    const char* axes[] = {"x", "y", "z"};
    for (std::size_t i = 0; i < cloud.vertices.size(); ++i) {
        for (int a = 0; a < 3; ++a) {
            const double slack = 1e-4 * (hi[std::size_t(a)] - lo[std::size_t(a)]);
            EXPECT_GT(cloud.at(i, axes[a]), lo[std::size_t(a)] - slack) << "vertex " << i;
            EXPECT_LT(cloud.at(i, axes[a]), hi[std::size_t(a)] + slack) << "vertex " << i;
        }
        EXPECT_NEAR(std::hypot(cloud.at(i, "nx"), cloud.at(i, "ny"), cloud.at(i, "nz")), 1.0, 1e-6);
        EXPECT_GT(cloud.at(i, "radius"), 0.0);
        if (::testing::Test::HasFailure()) break;
    }
    return cloud;
}

}  // namespace

TEST(CliExport, WritesOneSurfelPerBoundaryVoxelOfTheSphere) {
    Scratch s;
    const PlyCloud cloud = exportAndCompare({"analytic:sphere:33", "--iso", "0", "--depth", "6"}, s);
    ASSERT_GT(cloud.vertices.size(), 1000u);
    // Voxel centres on the sphere of radius 0.7; radius = half the diagonal of a 2/64 voxel.
    for (std::size_t i = 0; i < cloud.vertices.size(); ++i)
        EXPECT_NEAR(std::hypot(cloud.at(i, "x"), cloud.at(i, "y"), cloud.at(i, "z")), 0.7, 2.0 / 64.0 * std::sqrt(3.0));
    EXPECT_FLOAT_EQ(float(cloud.at(0, "radius")), float(0.5 * std::sqrt(3.0) * 2.0 / 64.0));
    // The default look of a field without colours: viridis by height, dark purple at the bottom
    // surfel, yellow at the top; opaque.
    std::size_t bottom = 0, top = 0;
    for (std::size_t i = 0; i < cloud.vertices.size(); ++i) {
        if (cloud.at(i, "z") < cloud.at(bottom, "z")) bottom = i;
        if (cloud.at(i, "z") > cloud.at(top, "z")) top = i;
    }
    EXPECT_LT(cloud.at(bottom, "red"), 100.0);
    EXPECT_LT(cloud.at(bottom, "green"), 40.0);
    EXPECT_GT(cloud.at(bottom, "blue"), 60.0);
    EXPECT_GT(cloud.at(top, "red"), 200.0);
    EXPECT_GT(cloud.at(top, "green"), 200.0);
    EXPECT_LT(cloud.at(top, "blue"), 80.0);
    EXPECT_EQ(cloud.at(0, "alpha"), 255.0);
    for (const char* c : {"octrace ", "input: analytic:sphere:33", "variable: sphere", "iso: 0", "depth: 6"})
        EXPECT_TRUE(hasComment(cloud, c)) << c;
    EXPECT_EQ(countEntries(s.dir()), 3);  // cloud, stats, image: no temporaries
}

TEST(CliExport, WritesTheLevitusTemperatureIsosurface) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    const PlyCloud cloud = exportAndCompare(
        {lev, "--var", "TEMP", "--iso", "10", "--region", "120,180,10,60", "--depth", "8", "--colormap", "viridis"}, s);
    EXPECT_GT(cloud.vertices.size(), 10000u);
    for (const char* c : {"variable: TEMP", "iso: 10", "depth: 8", "colour map viridis", "vertical scale"})
        EXPECT_TRUE(hasComment(cloud, c)) << c;
    // Coloured by height: the deepest and the shallowest surfels differ in colour.
    std::size_t lo = 0, hi = 0;
    for (std::size_t i = 0; i < cloud.vertices.size(); ++i) {
        if (cloud.at(i, "z") < cloud.at(lo, "z")) lo = i;
        if (cloud.at(i, "z") > cloud.at(hi, "z")) hi = i;
    }
    EXPECT_NE(cloud.at(lo, "green"), cloud.at(hi, "green"));
}

TEST(CliExport, WritesAsciiAndCoarserLevels) {
    Scratch s;
    const std::string fine = s.path("fine.ply"), coarse = s.path("coarse.txt");
    Result a = run({"export", "analytic:torus:33", "--iso", "0", "--depth", "6", "--ascii", "--quiet", "-o", fine});
    ASSERT_EQ(a.code, 0) << a.err;
    EXPECT_TRUE(a.err.empty()) << a.err;
    Result b = run({"export", "analytic:torus:33", "--iso", "0", "--depth", "6", "--level", "4", "--format", "ply",
                    "--threads", "1", "-o", coarse});
    ASSERT_EQ(b.code, 0) << b.err;
    const PlyCloud f = parsePly(slurp(fine)), c = parsePly(slurp(coarse));
    EXPECT_EQ(f.format, "ascii");
    EXPECT_EQ(c.format, "binary_little_endian");
    EXPECT_LT(c.vertices.size(), f.vertices.size());
    EXPECT_GT(c.vertices.size(), 50u);
    EXPECT_FLOAT_EQ(float(c.at(0, "radius")), 4.0f * float(f.at(0, "radius")));  // nodes 4 voxels wide
    EXPECT_TRUE(hasComment(c, "level: 4"));
}

// Command-line mistakes of export: in Cli.CommandLineMistakesExitTwoWithAUsageHint.

TEST(CliExport, InputProblemsExitOneNamingTheFileAndWriteNothing) {
    Scratch s;
    const std::string out = s.path("x.ply");
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"/nonexistent/field.nc"}, "/nonexistent/field.nc"},
        {{"analytic:sphere:17", "--iso", "5"}, "outside the value range"},
        {{"analytic:sphere:17", "--var", "pressure"}, "no variable 'pressure'"},
        {{"analytic:sphere:17", "--iso", "0", "--depth", "4", "-o", s.path("no/x.ply")}, "does not exist"},
    };
    for (const auto& [args, message] : cases) {
        std::vector<std::string> command = {"export", "-o", out};
        command.insert(command.end(), args.begin(), args.end());
        const Result r = run(command);
        EXPECT_EQ(r.code, 1) << args[0] << "\n" << r.err;
        EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    }
    EXPECT_EQ(countEntries(s.dir()), 0);
}
