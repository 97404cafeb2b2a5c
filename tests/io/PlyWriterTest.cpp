// Tests of the PLY point-cloud writer, read back with the tests' own minimal PLY reader
// (tests/PlyTestReader.h). VTK's vtkPLYReader lives in the IOPLY module, which octrace does
// not link (it links CommonCore, CommonDataModel and IOImage only), so it is not used here.
#include "octrace/io/PlyWriter.h"

#include "../PlyTestReader.h"
#include "ImageTestSupport.h"
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace octrace;
using namespace octrace::io;
using octrace::test::parsePly;
using octrace::test::PlyCloud;
using octrace::test::ScratchDir;

namespace {

std::string text(const std::vector<std::uint8_t>& bytes) { return std::string(bytes.begin(), bytes.end()); }

std::vector<Surfel> someSurfels() {
    std::vector<Surfel> s(3);
    s[0] = {vec3(0.0f, -1.5f, 2.25f), vec3(0.0f, 0.0f, 1.0f), 0.125f, {255, 0, 16, 255}};
    s[1] = {vec3(1e-7f, 12345.678f, -0.1f), glm::normalize(vec3(1.0f, -2.0f, 3.0f)), 1.0f / 3.0f, {1, 2, 3, 4}};
    s[2] = {vec3(-3.0e4f, std::numeric_limits<float>::min(), 7.0f), vec3(-1.0f, 0.0f, 0.0f), 2.5f, {0, 128, 200, 255}};
    return s;
}

/// Every property of every vertex equals the surfel's, exactly (floats read back bit for bit).
void expectSame(const PlyCloud& cloud, const std::vector<Surfel>& surfels) {
    ASSERT_EQ(cloud.vertices.size(), surfels.size());
    const char* names[] = {"x", "y", "z", "nx", "ny", "nz", "red", "green", "blue", "alpha", "radius"};
    ASSERT_EQ(cloud.properties.size(), 11u);
    for (std::size_t p = 0; p < 11; ++p) {
        EXPECT_EQ(cloud.properties[p].name, names[p]);
        EXPECT_EQ(cloud.properties[p].type, p >= 6 && p < 10 ? "uchar" : "float");
    }
    for (std::size_t i = 0; i < surfels.size(); ++i) {
        const Surfel& s = surfels[i];
        const float floats[] = {s.position.x, s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z};
        for (int a = 0; a < 6; ++a) EXPECT_EQ(float(cloud.at(i, names[a])), floats[a]) << names[a] << " of " << i;
        for (int c = 0; c < 4; ++c) EXPECT_EQ(cloud.at(i, names[6 + c]), double(s.rgba[std::size_t(c)])) << names[6 + c];
        EXPECT_EQ(float(cloud.at(i, "radius")), s.radius);
    }
}

}  // namespace

TEST(PlyWriter, WritesBinaryLittleEndianThatReadsBackExactly) {
    const auto surfels = someSurfels();
    const std::string bytes = text(PlyWriter::encode(surfels));
    EXPECT_EQ(bytes.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
    const PlyCloud cloud = parsePly(bytes);
    expectSame(cloud, surfels);
    EXPECT_EQ(cloud.trailingBytes, 0u);
    EXPECT_EQ(cloud.emptyElements, std::vector<std::string>{"face"});
    // 32 bytes per vertex after the header: 7 floats and 4 bytes.
    EXPECT_EQ(bytes.size() - (bytes.find("end_header\n") + 11), 32u * surfels.size());
}

TEST(PlyWriter, WritesAsciiThatReadsBackExactly) {
    const auto surfels = someSurfels();
    PlyWriteOptions options;
    options.ascii = true;
    const std::string bytes = text(PlyWriter::encode(surfels, options));
    EXPECT_EQ(bytes.rfind("ply\nformat ascii 1.0\n", 0), 0u);
    expectSame(parsePly(bytes), surfels);
    EXPECT_NE(bytes.find("\n0 -1.5 2.25 0 0 1 255 0 16 255 0.125\n"), std::string::npos) << bytes;
}

TEST(PlyWriter, PutsTheCommentsInTheHeaderOneLineEach) {
    PlyWriteOptions options;
    options.comments = {"octrace 0.1.0", "input: a\nb.nc", ""};
    const PlyCloud cloud = parsePly(text(PlyWriter::encode(someSurfels(), options)));
    EXPECT_EQ(cloud.comments, (std::vector<std::string>{"octrace 0.1.0", "input: a b.nc", ""}));
    EXPECT_EQ(cloud.vertices.size(), 3u);
}

TEST(PlyWriter, WritesAnEmptyCloud) {
    const PlyCloud cloud = parsePly(text(PlyWriter::encode({})));
    EXPECT_TRUE(cloud.vertices.empty());
    EXPECT_EQ(cloud.properties.size(), 11u);
}

TEST(PlyWriter, WritesTheSurfelsOfAnOctreeToAFile) {
    ScratchDir dir;
    Octree tree = buildShellOctree(makeAnalyticField("sphere", 33), {6, 0.0, 0});
    const std::vector<Surfel> surfels = extractSurfels(tree, RenderSettings{});
    const std::string path = dir.file("sphere.ply");
    PlyWriter::write(surfels, path);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"sphere.ply"});  // no temporary left
    const auto bytes = octrace::test::readBytes(path);
    const PlyCloud cloud = parsePly(text(bytes));
    ASSERT_EQ(cloud.vertices.size(), tree.boundaryVoxels());
    expectSame(cloud, surfels);
    for (std::size_t i = 0; i < cloud.vertices.size(); i += 97) {
        const double r = std::hypot(cloud.at(i, "x"), cloud.at(i, "y"), cloud.at(i, "z"));
        EXPECT_NEAR(r, 0.7, 2.0 * tree.voxelSize()) << "vertex " << i;  // on the sphere of radius 0.7
        EXPECT_NEAR(std::hypot(cloud.at(i, "nx"), cloud.at(i, "ny"), cloud.at(i, "nz")), 1.0, 1e-6);
    }
}

TEST(PlyWriter, ReportsAMissingFolderAndLeavesNoFile) {
    ScratchDir dir;
    const std::string path = dir.file("missing/out.ply");
    try {
        PlyWriter::write(someSurfels(), path);
        FAIL() << "expected OutputError";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
    EXPECT_TRUE(dir.entries().empty());
}

TEST(PlyWriter, LeavesAnExistingFileUntouchedWhenWritingFails) {
    ScratchDir dir;
    std::filesystem::create_directory(dir.path() / "taken.ply");
    EXPECT_THROW(PlyWriter::write(someSurfels(), dir.file("taken.ply")), OutputError);
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"taken.ply"});
    EXPECT_TRUE(std::filesystem::is_directory(dir.path() / "taken.ply"));
}
