// .oct octree files: exact round trips (shell and volume form), every flipped byte and every
// truncation refused, future versions refused, CRC-32C against its published check value.
#include "octree/Crc32c.h"
#include "octree/VoxelNeighbours.h"
#include "IoTestSupport.h"
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/io/FieldReader.h"
#include "octrace/io/OctreeFile.h"
#include "octrace/lighting/Bake.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>

using namespace octrace;

namespace {

Octree smallTree(const std::string& name = "torus", int samples = 17, int depth = 4) {
    const ScalarField f = makeAnalyticField(name, samples);
    BuildOptions o;
    o.depth = depth;
    o.iso = 0.0;
    Octree t = buildShellOctree(f, o);
    t.setMetadata(octree_key::kSource, "analytic:" + name);
    return t;
}

/// Every voxel's cell and normal, every term's cell and level: what a file must keep.
std::map<std::tuple<int, int, int, int>, std::uint32_t> contents(const Octree& t) {
    std::map<std::tuple<int, int, int, int>, std::uint32_t> m;
    for (int level = 1; level <= t.depth; ++level)
        t.forEachAtLevel(level, [&](const ivec3& c, std::uint32_t i) {
            if (level == t.depth) m[{level, c.x, c.y, c.z}] = t.voxels()[i].normal ^ (t.baked().empty() ? 0u : std::uint32_t(t.baked()[i]) << 24 | 0x5A5A5Au);
            else if (t.nodes()[i].childMask == 0) m[{level, c.x, c.y, c.z}] = 0xFFFFFFFFu;  // a term
        });
    return m;
}

void expectSame(const Octree& a, const Octree& b) {
    EXPECT_EQ(a.depth, b.depth);
    EXPECT_EQ(a.form, b.form);
    EXPECT_EQ(a.cubeOrigin, b.cubeOrigin);
    EXPECT_EQ(a.cubeSide, b.cubeSide);
    EXPECT_EQ(a.iso, b.iso);
    EXPECT_EQ(a.insideBelow, b.insideBelow);
    EXPECT_EQ(a.fieldName(), b.fieldName());
    EXPECT_EQ(a.fieldUnits(), b.fieldUnits());
    EXPECT_EQ(a.source(), b.source());
    EXPECT_EQ(a.crs(), b.crs());
    EXPECT_EQ(a.nodes().size(), b.nodes().size());
    EXPECT_EQ(a.voxels().size(), b.voxels().size());
    EXPECT_EQ(contents(a), contents(b));
}

}  // namespace

TEST(Crc32c, MatchesThePublishedCheckValue) {
    // RFC 3720 B.4 / the CRC catalogue: CRC-32C("123456789") = 0xE3069283.
    const char* s = "123456789";
    EXPECT_EQ(io::detail::crc32c(s, 9), 0xE3069283u);
    // 32 bytes of zeros (RFC 3720 B.4): 0x8A9136AA; and continuing a CRC in pieces.
    const std::vector<std::uint8_t> zeros(32, 0);
    EXPECT_EQ(io::detail::crc32c(zeros.data(), zeros.size()), 0x8A9136AAu);
    EXPECT_EQ(io::detail::crc32c(s + 4, 5, io::detail::crc32c(s, 4)), 0xE3069283u);
}

TEST(OctreeFile, RoundTripsExactly) {
    for (const std::string& name : analyticFieldNames()) {
        const Octree t = smallTree(name, 33, 6);
        const auto bytes = io::encodeOctreeFile(t);
        io::OctreeFileInfo info;
        const Octree back = io::decodeOctreeFile(bytes, "mem.oct", 0, &info);
        SCOPED_TRACE(name);
        expectSame(t, back);
        EXPECT_EQ(info.version, 1u);  // no baked light: readable by version 1 readers
        EXPECT_EQ(info.voxels, t.voxels().size());
        EXPECT_EQ(info.fileBytes, bytes.size());
        // Written again, the same bytes.
        EXPECT_EQ(io::encodeOctreeFile(back), bytes);
    }
}

TEST(OctreeFile, VoxelNeighboursAreEachVoxelsFaceNeighboursInFileOrder) {
    // The file's voxel order is Morton order (x highest of each bit triple); each voxel's
    // neighbours at -x, -y, -z found there by their cells, against voxelNeighbours's walk.
    const auto check = [](const Octree& t) {
        std::vector<std::pair<std::uint64_t, ivec3>> cells;
        t.forEachAtLevel(t.depth, [&](const ivec3& c, std::uint32_t) {
            std::uint64_t m = 0;
            for (int b = t.depth - 1; b >= 0; --b)
                m = m << 3 | std::uint64_t((c.x >> b & 1) << 2 | (c.y >> b & 1) << 1 | (c.z >> b & 1));
            cells.push_back({m, c});
        });
        std::sort(cells.begin(), cells.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        std::map<std::tuple<int, int, int>, std::uint32_t> at;
        for (std::size_t i = 0; i < cells.size(); ++i) at[{cells[i].second.x, cells[i].second.y, cells[i].second.z}] = std::uint32_t(i);
        const auto around = io::detail::voxelNeighbours(t);
        ASSERT_EQ(around.size(), cells.size());
        std::size_t found = 0;
        for (std::size_t i = 0; i < cells.size(); ++i)
            for (int a = 0; a < 3; ++a) {
                ivec3 c = cells[i].second;
                c[a] -= 1;
                const auto it = at.find({c.x, c.y, c.z});
                const std::uint32_t want = it == at.end() ? io::detail::kNoNeighbour : it->second;
                ASSERT_EQ(around[i][std::size_t(a)], want) << "voxel " << i << " axis " << a;
                found += want != io::detail::kNoNeighbour;
            }
        EXPECT_GT(found, cells.size());  // the surfaces are connected: most voxels have some
    };
    for (const std::string& name : analyticFieldNames()) {
        SCOPED_TRACE(name);
        check(smallTree(name, 33, 6));
    }
    // The volume form: interior voxels and terms (a term's cells hold no voxel).
    BuildOptions o;
    o.depth = 5;
    o.iso = 0.0;
    o.form = OctreeForm::Volume;
    SCOPED_TRACE("volume");
    const Octree volume = buildOctree(makeAnalyticField("gyroid", 33), o);
    bool term = false;  // an interior term above the voxel level, whose cells hold no voxel
    volume.descend([&](int level, const ivec3&, std::uint32_t, bool isTerm) {
        term |= isTerm && level < volume.depth;
        return level < volume.depth && !isTerm;  // nodes only (a voxel's slot is not a node's)
    });
    ASSERT_TRUE(term);
    check(volume);
}

TEST(OctreeFile, RoundTripsTheVolumeFormWithTerms) {
    // Depth 2 by hand: a node with a boundary voxel and an interior voxel, and an interior term.
    Octree t;
    t.depth = 2;
    t.form = OctreeForm::Volume;
    t.insideBelow = true;
    t.cubeSide = 2.5;
    std::vector<OctreeNode> nodes(3);
    nodes[0].childMask = 0b10000001;
    nodes[0].termMask = 0b10000000;
    nodes[0].firstChild = 1;
    nodes[1].childMask = 0b10000001;
    nodes[1].termMask = 0b00000001;
    std::vector<Voxel> voxels(2);
    voxels[1].normal = 12345;
    t.setTopology(std::move(nodes), std::move(voxels));
    t.validate();
    const auto bytes = io::encodeOctreeFile(t);
    expectSame(t, io::decodeOctreeFile(bytes, "v.oct"));
}

TEST(OctreeFile, KeepsTheMetadataTheFormatStoresAndOnlyThat) {
    // The header's variable, units and source and the 'CRS ' chunk carry four well-known keys;
    // the colour-by value's name and units (like the values themselves) and other keys are not
    // stored (docs/dev/octree-files.md, "In memory").
    Octree t = smallTree();
    t.setMetadata(octree_key::kFieldName, "thetao");
    t.setMetadata(octree_key::kFieldUnits, "degC");
    t.setMetadata(octree_key::kCrs, "EPSG:7415");
    const OctreeMetadata stored = t.metadata();
    ASSERT_EQ(stored.size(), 4u);
    t.setMetadata(octree_key::kValueName, "so");
    t.setMetadata(octree_key::kValueUnits, "psu");
    t.setMetadata("operator", "someone");
    const auto bytes = io::encodeOctreeFile(t);
    io::OctreeFileInfo info;
    const Octree back = io::decodeOctreeFile(bytes, "meta.oct", 0, &info);
    EXPECT_EQ(back.metadata(), stored);
    EXPECT_EQ(back.crs(), "EPSG:7415");
    EXPECT_EQ(info.fieldName, "thetao");
    EXPECT_EQ(info.fieldUnits, "degC");
    EXPECT_EQ(info.source, "analytic:torus");
    // The layout is the one older readers know: a version 1 file, no chunk beyond 'CRS '.
    EXPECT_EQ(info.version, 1u);
    std::vector<std::string> tags;
    for (const auto& c : info.chunks) tags.push_back(c.tag);
    EXPECT_EQ(tags, (std::vector<std::string>{"TREE", "NORM", "CRS "}));
    // Keys that are not stored do not change the bytes.
    Octree plain = t.copy();
    plain.setMetadata(octree_key::kValueName, "");
    plain.setMetadata(octree_key::kValueUnits, "");
    plain.setMetadata("operator", "");
    EXPECT_EQ(io::encodeOctreeFile(plain), bytes);
}

/// Writes `t`, reads it back: the same octree, in format `version`, its last chunk `tag`, and
/// written again to the same bytes. Returns the octree read back.
Octree expectRoundTrip(const Octree& t, std::uint32_t version, const std::string& tag) {
    const auto bytes = io::encodeOctreeFile(t);
    io::OctreeFileInfo info;
    Octree back = io::decodeOctreeFile(bytes, "round.oct", 0, &info);
    expectSame(t, back);
    EXPECT_EQ(info.version, version);
    EXPECT_EQ(info.chunks.back().tag, tag);
    EXPECT_EQ(io::encodeOctreeFile(back), bytes);
    return back;
}

Octree bakedTree() {
    Octree t = smallTree();
    BakeOptions o;
    o.aoRays = 4;
    bakeLighting(t, o);
    return t;
}

TEST(OctreeFile, RoundTripsBakedLightInVersion2) {
    const Octree t = bakedTree();
    ASSERT_EQ(t.baked().size(), t.voxels().size());
    expectRoundTrip(t, 2, "LITE");
}

TEST(OctreeFile, EveryFlippedByteIsDetected) {
  for (const Octree& tree : {smallTree(), bakedTree()}) {
    const auto bytes = io::encodeOctreeFile(tree);
    ASSERT_LT(bytes.size(), 4000u) << "a small file keeps this test quick";
    for (std::size_t i = 0; i < bytes.size(); ++i)
        for (std::uint8_t flip : {std::uint8_t(0x01), std::uint8_t(0x80), std::uint8_t(0xFF)}) {
            auto b = bytes;
            b[i] ^= flip;
            try {
                io::decodeOctreeFile(b, "flipped.oct");
                ADD_FAILURE() << "byte " << i << " xor " << int(flip) << " was not detected";
            } catch (const InputError& e) {
                EXPECT_NE(std::string(e.what()).find("flipped.oct: "), std::string::npos) << e.what();
            }
        }
  }
}

TEST(OctreeFile, EveryTruncationIsDetected) {
    const auto bytes = io::encodeOctreeFile(smallTree());
    for (std::size_t n = 0; n < bytes.size(); ++n) {
        std::vector<std::uint8_t> b(bytes.begin(), bytes.begin() + std::ptrdiff_t(n));
        EXPECT_THROW(io::decodeOctreeFile(b, "short.oct"), FileError) << "cut at " << n;
    }
    auto longer = bytes;
    longer.push_back(0);
    EXPECT_THROW_WITH(io::decodeOctreeFile(longer, "long.oct"), FileError, "long.oct: 1 unexpected bytes after the last chunk");
}

TEST(OctreeFile, RefusesAFutureVersionAndOtherFiles) {
    auto bytes = io::encodeOctreeFile(smallTree());
    bytes[8] = 4;  // version, little-endian, right after the 8-byte signature
    EXPECT_THROW_WITH(io::decodeOctreeFile(bytes, "new.oct"), FileError, "new.oct: written by a newer octrace (octree file format version 4; this octrace reads versions 1 to 3)");
    const std::string text = "CDF\x01 not an octree";
    std::vector<std::uint8_t> other(text.begin(), text.end());
    EXPECT_THROW(io::decodeOctreeFile(other, "x.oct"), FormatNotSupported);
}

TEST(OctreeFile, RefusesAnOctreeOverTheMemoryBudget) {
    const auto bytes = io::encodeOctreeFile(smallTree());
    EXPECT_THROW_WITH(io::decodeOctreeFile(bytes, "big.oct", 1000), LimitError, "big.oct: reading an octree of");
}

TEST(OctreeFile, WritesAtomicallyAndReadsBack) {
    test::TempDir dir;
    const std::string path = dir.file("t.oct");
    const Octree t = smallTree();
    io::writeOctreeFile(path, t);
    EXPECT_TRUE(io::isOctreeFile(path));
    expectSame(t, io::readOctreeFile(path));
    const io::OctreeFileInfo info = io::readOctreeFileInfo(path);
    EXPECT_EQ(info.fileBytes, std::filesystem::file_size(path));
    ASSERT_EQ(info.chunks.size(), 2u);
    EXPECT_EQ(info.chunks[0].tag, "TREE");
    EXPECT_EQ(info.chunks[1].tag, "NORM");
    // A failed write (the target is a folder) leaves what was there untouched.
    std::filesystem::create_directories(dir.file("d.oct"));
    EXPECT_THROW(io::writeOctreeFile(dir.file("d.oct"), t), OutputError);
    EXPECT_TRUE(std::filesystem::is_directory(dir.file("d.oct")));
    EXPECT_THROW_WITH(io::readOctreeFile(dir.file("none.oct")), InputError, "none.oct: no such file");
}


namespace {
Octree cornerTree() {
    const ScalarField f = makeAnalyticField("torus", 17);
    BuildOptions o;
    o.depth = 4;
    o.iso = 0.0;
    o.corners = true;
    return buildShellOctree(f, o);
}
}  // namespace

TEST(OctreeFile, RoundTripsCornerValuesInVersion3) {
    const Octree t = cornerTree();
    ASSERT_EQ(t.corners().size(), t.voxels().size());
    EXPECT_EQ(expectRoundTrip(t, 3, "CRNR").corners(), t.corners());
    // Without corners the file stays version 1, which older readers take.
    Octree plain = t.copy();
    plain.setCorners({});
    EXPECT_EQ(io::encodeOctreeFile(plain)[8], 1u);
}

TEST(OctreeFile, OldFilesStillLoad) {
    // Written by octrace at commit c625571 (tests/data/octree/README.md): format version 1, no
    // corner values; it loads, and the same surface built today has the same cells and normals.
    io::OctreeFileInfo info;
    const Octree old = io::readOctreeFile(test::testData("octree/torus_v1.oct"), 0, &info);
    EXPECT_EQ(info.version, 1u);
    EXPECT_TRUE(old.corners().empty());
    EXPECT_EQ(old.depth, 5);
    EXPECT_EQ(old.voxels().size(), 2040u);
    // Its normals were predicted by that octrace's writer: read back by today's prediction, they
    // are the normals of the same build today.
    BuildOptions o;
    o.depth = 5;
    o.iso = 0.0;
    const Octree today = buildShellOctree(io::readField(std::string(OCTRACE_SAMPLES) + "/torus.nrrd"), o);
    EXPECT_EQ(contents(old), contents(today));
}

TEST(OctreeFile, CornerChunkInAVersion2FileIsRefused) {
    auto bytes = io::encodeOctreeFile(cornerTree());
    bytes[8] = 2;  // claim version 2, which knows no 'CRNR'
    // The header's checksum no longer matches either: fix it so that the chunk check is reached.
    const std::uint32_t h = std::uint32_t(bytes[12]) | std::uint32_t(bytes[13]) << 8 | std::uint32_t(bytes[14]) << 16 |
                            std::uint32_t(bytes[15]) << 24;
    const std::uint32_t crc = io::detail::crc32c(bytes.data(), 16 + h);
    for (int i = 0; i < 4; ++i) bytes[16 + h + std::size_t(i)] = std::uint8_t(crc >> (8 * i));
    try {
        io::decodeOctreeFile(bytes, "v2.oct");
        FAIL() << "accepted";
    } catch (const FileError& e) {
        EXPECT_NE(std::string(e.what()).find("unknown chunk 'CRNR'"), std::string::npos) << e.what();
    }
}
