// Tests of the octree model: normal quantization, voxel look-up, structural validation.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/build/Volume.h"
#include "octrace/octree/Octree.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <random>
#include <set>
#include <tuple>

using namespace octrace;

namespace {

double angleDegrees(dvec3 a, dvec3 b) {
    return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

/// Worst angle between n and its decoded code, in degrees (computed in double).
double roundTripError(dvec3 n) {
    n = glm::normalize(n);
    const vec3 d = decodeNormal(encodeNormal(vec3(n)));
    return angleDegrees(n, dvec3(d));
}

Octree copyOf(const Octree& t) { return t.copy(); }

const Octree& noiseTree() {
    static const Octree t = buildShellOctree(makeAnalyticField("noise", 33, 5), {5, 0.0, 1});
    return t;
}

/// Index of some node at the level just above the voxels, and of some node at level 1.
std::uint32_t nodeAtLevel(const Octree& t, int wanted) {
    std::uint32_t node = 0;
    for (int level = 0; level < wanted; ++level) node = t.nodes[node].firstChild;  // first child, always a node
    return node;
}

/// Every (node, level) reachable from the root.
std::vector<std::pair<std::uint32_t, int>> allNodes(const Octree& t) {
    std::vector<std::pair<std::uint32_t, int>> out, stack{{0u, 0}};
    while (!stack.empty()) {
        auto item = stack.back();
        stack.pop_back();
        out.push_back(item);
        const OctreeNode& nd = t.nodes[item.first];
        if (item.second == t.depth - 1) continue;
        for (int i = 0; i < std::popcount(unsigned(nd.childMask)); ++i)
            stack.push_back({nd.firstChild + std::uint32_t(i), item.second + 1});
    }
    return out;
}

void expectInvalid(const Octree& t, const std::string& why) {
    try {
        t.validate();
        ADD_FAILURE() << "validate() accepted an octree with: " << why;
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(why), std::string::npos) << e.what();
    }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Normals

TEST(OctreeNormal, RoundTripsRandomUnitVectorsWithinAHundredthOfADegree) {
    std::mt19937_64 rng(17);
    std::normal_distribution<double> g(0.0, 1.0);
    double worst = 0.0, worstBelow = 0.0;
    int below = 0;
    for (int i = 0; i < 500000; ++i) {
        dvec3 n(g(rng), g(rng), g(rng));
        if (!(glm::length(n) > 1e-9)) continue;
        const double e = roundTripError(n);
        worst = std::max(worst, e);
        if (n.z < 0) {
            ++below;
            worstBelow = std::max(worstBelow, e);
        }
    }
    std::cout << "[          ] normal round trip: worst " << worst << " deg (z<0: " << worstBelow << " deg)\n";
    EXPECT_GT(below, 200000);
    EXPECT_LT(worst, 0.01);
    EXPECT_LT(worstBelow, 0.01);
}

TEST(OctreeNormal, RoundTripsAxesDiagonalsAndVectorsNearTheFold) {
    std::vector<dvec3> special;
    for (int a = 0; a < 3; ++a)
        for (double s : {1.0, -1.0}) {
            dvec3 v(0.0);
            v[a] = s;
            special.push_back(v);
        }
    for (int x = -1; x <= 1; ++x)
        for (int y = -1; y <= 1; ++y)
            for (int z = -1; z <= 1; ++z)
                if (x || y || z) special.push_back(dvec3(x, y, z));
    // Close to the equator z = 0, where the lower hemisphere is folded over the upper one.
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
    for (int i = 0; i < 20000; ++i) {
        double a = angle(rng), z = std::ldexp(1.0, -int(rng() % 40)) * ((rng() & 1) ? 1.0 : -1.0);
        special.push_back(dvec3(std::cos(a), std::sin(a), z));
        special.push_back(dvec3(std::cos(a), std::sin(a), 0.0));
    }
    for (const dvec3& n : special) EXPECT_LT(roundTripError(n), 0.01) << n.x << "," << n.y << "," << n.z;
    // Opposite vectors stay opposite (two-sided shading and inward/outward tests rely on it).
    for (const dvec3& n : special) {
        const dvec3 a(decodeNormal(encodeNormal(vec3(n)))), b(decodeNormal(encodeNormal(vec3(-n))));
        EXPECT_LT(angleDegrees(a, -b), 0.02);
    }
}

TEST(OctreeNormal, DecodesToUnitVectors) {
    std::mt19937 rng(1);
    for (int i = 0; i < 100000; ++i) {
        vec3 d = decodeNormal(std::uint32_t(rng()));
        EXPECT_NEAR(glm::length(dvec3(d)), 1.0, 1e-6);
    }
    // The zero vector is stored as something harmless (+z), never NaN.
    vec3 z = decodeNormal(encodeNormal(vec3(0.0f)));
    EXPECT_TRUE(std::isfinite(z.x) && std::isfinite(z.y) && std::isfinite(z.z));
}

// ---------------------------------------------------------------------------------------------
// Look-up and traversal helpers

TEST(Octree, FindVoxelAgreesWithForEachVoxelOnEveryCell) {
    const Octree& t = noiseTree();
    const int n = 1 << t.depth;
    std::set<std::tuple<int, int, int>> cells;
    std::size_t visits = 0;
    t.forEachVoxel([&](const ivec3& c, std::uint32_t i) {
        ++visits;
        cells.insert({c.x, c.y, c.z});
        EXPECT_EQ(t.findVoxel(c), i) << c.x << "," << c.y << "," << c.z;
    });
    EXPECT_EQ(visits, t.voxels.size());
    EXPECT_EQ(cells.size(), t.voxels.size());  // every voxel once, at distinct cells
    std::size_t found = 0;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                std::uint32_t i = t.findVoxel(ivec3(x, y, z));
                if (i == 0xFFFFFFFFu) {
                    EXPECT_EQ(cells.count({x, y, z}), 0u);
                } else {
                    ++found;
                    EXPECT_LT(i, t.voxels.size());
                }
            }
    EXPECT_EQ(found, t.voxels.size());
    for (ivec3 c : {ivec3(-1, 0, 0), ivec3(0, n, 0), ivec3(0, 0, n + 5), ivec3(-7)}) EXPECT_EQ(t.findVoxel(c), 0xFFFFFFFFu);
}

TEST(Octree, MapsTheCubeToOctreeSpaceAndCellsToWorldBoxes) {
    const Octree& t = noiseTree();
    const double L = double(1 << Octree::kIntBits);
    const dvec3 lo = t.toOctreeSpace(t.cubeOrigin), hi = t.toOctreeSpace(t.cubeOrigin + dvec3(t.cubeSide));
    for (int a = 0; a < 3; ++a) {
        EXPECT_NEAR(lo[a], 0.0, 1e-9);
        EXPECT_NEAR(hi[a], L, 1e-9);
    }
    Box3 b = t.voxelBox(ivec3(3, 0, 31));
    EXPECT_NEAR(b.size().x, t.voxelSize(), 1e-15);
    EXPECT_NEAR(t.toOctreeSpace(b.lo).x, 3 * L / 32, 1e-9);
    EXPECT_NEAR(t.toOctreeSpace(b.hi).z, L, 1e-9);
    const dvec3 p(0.123, -0.4, 0.77);
    const dvec3 back = t.worldFromOctreeSpace(t.toOctreeSpace(p));
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(back[a], p[a], 1e-12);
}

TEST(Octree, HandlesInteriorTermsInTheVolumeForm) {
    // Depth 2 by hand: root children 0 (a node with voxels 0 and 7) and 7 (an interior term).
    Octree t;
    t.depth = 2;
    t.form = OctreeForm::Volume;
    t.nodes.resize(3);
    t.nodes[0].childMask = 0b10000001;
    t.nodes[0].termMask = 0b10000000;
    t.nodes[0].firstChild = 1;
    t.nodes[1].childMask = 0b10000001;
    t.nodes[1].firstChild = 0;
    // nodes[2]: the term, childMask 0.
    t.voxels.resize(2);
    EXPECT_NO_THROW(t.validate());
    EXPECT_EQ(t.findVoxel(ivec3(0, 0, 0)), 0u);
    EXPECT_EQ(t.findVoxel(ivec3(1, 1, 1)), 1u);
    EXPECT_EQ(t.findVoxel(ivec3(2, 2, 2)), 0xFFFFFFFFu);  // inside the term: not a boundary voxel
    EXPECT_EQ(t.findVoxel(ivec3(3, 3, 3)), 0xFFFFFFFFu);
    int n = 0;
    t.forEachVoxel([&](const ivec3&, std::uint32_t) { ++n; });
    EXPECT_EQ(n, 2);
}

// ---------------------------------------------------------------------------------------------
// validate()

TEST(Octree, ValidatePassesOnBuiltOctrees) {
    EXPECT_NO_THROW(noiseTree().validate());
    Octree one = buildShellOctree(makeAnalyticField("sphere", 9), {1, 0.0, 1});
    EXPECT_NO_THROW(one.validate());
}

TEST(Octree, ValidateRejectsIndicesOutOfRange) {
    {
        Octree t = copyOf(noiseTree());
        t.nodes[0].firstChild = std::uint32_t(t.nodes.size());
        expectInvalid(t, "node index out of range");
    }
    {
        Octree t = copyOf(noiseTree());
        const std::uint32_t leafParent = nodeAtLevel(t, t.depth - 1);
        t.nodes[leafParent].firstChild = std::uint32_t(t.voxels.size()) - 1;
        t.nodes[leafParent].childMask = 0xFF;
        expectInvalid(t, "voxel index out of range");
    }
}

TEST(Octree, ValidateRejectsUnreachableAndSharedNodesAndVoxels) {
    {
        Octree t = copyOf(noiseTree());
        t.nodes.push_back(t.nodes[1]);
        expectInvalid(t, "unreachable node");
    }
    {
        Octree t = copyOf(noiseTree());
        t.voxels.push_back(Voxel{});
        expectInvalid(t, "unreachable voxel");
    }
    {
        // A node pointing back at the root: a cycle.
        Octree t = copyOf(noiseTree());
        const std::uint32_t n1 = nodeAtLevel(t, 1);
        t.nodes[n1].firstChild = 0;
        EXPECT_THROW(t.validate(), Error);
    }
    {
        // Two leaf parents sharing their voxels.
        Octree t = copyOf(noiseTree());
        std::vector<std::uint32_t> leafParents;
        for (auto [n, level] : allNodes(t))
            if (level == t.depth - 1) leafParents.push_back(n);
        ASSERT_GE(leafParents.size(), 2u);
        t.nodes[leafParents[1]].firstChild = t.nodes[leafParents[0]].firstChild;
        t.nodes[leafParents[1]].childMask = t.nodes[leafParents[0]].childMask;
        expectInvalid(t, "voxel referenced twice");
    }
    {
        // An inner node whose only child is an empty inner node.
        Octree t = copyOf(noiseTree());
        t.nodes[nodeAtLevel(t, 1)].childMask = 0;
        EXPECT_THROW(t.validate(), Error);
    }
}

TEST(Octree, ValidateRejectsBadMasksAndGeometry) {
    {
        // On an inner node that has an empty child slot.
        Octree t = copyOf(noiseTree());
        std::uint32_t node = 0xFFFFFFFFu;
        for (auto [n, level] : allNodes(t))
            if (level < t.depth - 1 && t.nodes[n].childMask != 0xFF) node = n;
        ASSERT_NE(node, 0xFFFFFFFFu);
        t.nodes[node].termMask = std::uint8_t(~t.nodes[node].childMask);
        expectInvalid(t, "term bit without child bit");
    }
    {
        Octree t = copyOf(noiseTree());
        const std::uint32_t leafParent = nodeAtLevel(t, t.depth - 1);
        t.nodes[leafParent].termMask = t.nodes[leafParent].childMask & std::uint8_t(-t.nodes[leafParent].childMask);
        expectInvalid(t, "interior voxel in a shell octree");  // allowed in the volume form only
    }
    for (int depth : {0, Octree::kMaxDepth + 1}) {
        Octree t = copyOf(noiseTree());
        t.depth = depth;
        expectInvalid(t, "depth out of range");
    }
    {
        Octree t = copyOf(noiseTree());
        t.cubeSide = 0.0;
        expectInvalid(t, "cube side");
    }
    {
        Octree t;
        t.depth = 3;
        expectInvalid(t, "no root node");
    }
}

TEST(Octree, CopyKeepsEveryBufferAndAllProvenanceAndEmptyCopyOnlyTheProvenance) {
    // The one copy of an octree: a build (csg, extractShell, the tests) that starts from it must
    // lose nothing. Every per-voxel buffer filled, every provenance member set.
    Octree t = copyOf(noiseTree());
    const std::size_t n = t.voxels.size();
    t.colours.assign(n, 0x11223344u);
    t.voxelValues.assign(n, 2.5f);
    t.baked.assign(n, 200);
    t.voxelMaterials.assign(n, std::uint8_t(VoxelMaterial::Floor));
    t.computeSummaries();
    t.fieldName = "temp";
    t.fieldUnits = "degC";
    t.iso = 10.0;
    t.insideBelow = true;
    t.source = "a.nc";
    t.crs = "EPSG:7415";
    t.valueName = "salt";
    t.valueUnits = "psu";
    t.valueStandardName = "sea_water_salinity";
    const Octree c = t.copy();
    EXPECT_EQ(c.nodes.size(), t.nodes.size());
    EXPECT_EQ(c.voxels.size(), n);
    EXPECT_EQ(c.colours, t.colours);
    EXPECT_EQ(c.voxelValues, t.voxelValues);
    EXPECT_EQ(c.baked, t.baked);
    EXPECT_EQ(c.voxelMaterials, t.voxelMaterials);
    EXPECT_EQ(c.summaries.size(), t.summaries.size());
    EXPECT_EQ(c.bytes(), t.bytes());
    const Octree e = t.emptyCopy();
    for (const Octree* o : {&c, &e}) {
        EXPECT_EQ(o->depth, t.depth);
        EXPECT_EQ(o->cubeOrigin, t.cubeOrigin);
        EXPECT_EQ(o->cubeSide, t.cubeSide);
        EXPECT_EQ(o->form, t.form);
        EXPECT_EQ(o->fieldName, t.fieldName);
        EXPECT_EQ(o->fieldUnits, t.fieldUnits);
        EXPECT_EQ(o->iso, t.iso);
        EXPECT_EQ(o->insideBelow, t.insideBelow);
        EXPECT_EQ(o->source, t.source);
        EXPECT_EQ(o->crs, t.crs);
        EXPECT_EQ(o->valueName, t.valueName);
        EXPECT_EQ(o->valueUnits, t.valueUnits);
        EXPECT_EQ(o->valueStandardName, t.valueStandardName);
    }
    EXPECT_TRUE(e.nodes.empty() && e.voxels.empty() && e.colours.empty() && e.voxelValues.empty() && e.baked.empty() &&
                e.voxelMaterials.empty() && e.summaries.empty());
}
