// Tests of the octree model: normal quantization, voxel look-up, structural validation.
#include "octrace/build/AnalyticField.h"
#include "octrace/build/OctreeBuilder.h"
#include "octrace/build/Volume.h"
#include "octrace/octree/Octree.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <functional>
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

/// A copy of `t` with every per-voxel attribute filled (one value each) and the summaries.
Octree withEveryBuffer(const Octree& t) {
    Octree o = t.copy();
    const std::size_t n = o.voxels().size();
    o.setColours(std::vector<std::uint32_t>(n, 0x11223344u));
    o.setVoxelValues(std::vector<float>(n, 2.5f));
    o.setBaked(std::vector<std::uint8_t>(n, 200));
    o.setVoxelMaterials(std::vector<std::uint8_t>(n, std::uint8_t(VoxelMaterial::Floor)));
    o.computeSummaries();
    return o;
}

/// Calls edit(nodes, voxels) on copies of the tree's topology and hands them back: the way a
/// test damages an octree, since the octree keeps its own private.
template <class F>
void editTopology(Octree& t, F&& edit) {
    std::vector<OctreeNode> nodes = t.nodes();
    std::vector<Voxel> voxels = t.voxels();
    edit(nodes, voxels);
    t.setTopology(std::move(nodes), std::move(voxels));
}

const Octree& noiseTree() {
    static const Octree t = buildShellOctree(makeAnalyticField("noise", 33, 5), {5, 0.0, 1});
    return t;
}

/// Index of some node at the level just above the voxels, and of some node at level 1.
std::uint32_t nodeAtLevel(const Octree& t, int wanted) {
    std::uint32_t node = 0;
    for (int level = 0; level < wanted; ++level) node = t.nodes()[node].firstChild;  // first child, always a node
    return node;
}

/// Every (node, level) reachable from the root.
std::vector<std::pair<std::uint32_t, int>> allNodes(const Octree& t) {
    std::vector<std::pair<std::uint32_t, int>> out, stack{{0u, 0}};
    while (!stack.empty()) {
        auto item = stack.back();
        stack.pop_back();
        out.push_back(item);
        const OctreeNode& nd = t.nodes()[item.first];
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
    EXPECT_EQ(visits, t.voxels().size());
    EXPECT_EQ(cells.size(), t.voxels().size());  // every voxel once, at distinct cells
    std::size_t found = 0;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                std::uint32_t i = t.findVoxel(ivec3(x, y, z));
                if (i == 0xFFFFFFFFu) {
                    EXPECT_EQ(cells.count({x, y, z}), 0u);
                } else {
                    ++found;
                    EXPECT_LT(i, t.voxels().size());
                }
            }
    EXPECT_EQ(found, t.voxels().size());
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
    std::vector<OctreeNode> nodes(3);
    nodes[0].childMask = 0b10000001;
    nodes[0].termMask = 0b10000000;
    nodes[0].firstChild = 1;
    nodes[1].childMask = 0b10000001;
    nodes[1].firstChild = 0;
    // nodes[2]: the term, childMask 0.
    t.setTopology(std::move(nodes), std::vector<Voxel>(2));
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
        editTopology(t, [](auto& nodes, auto&) { nodes[0].firstChild = std::uint32_t(nodes.size()); });
        expectInvalid(t, "node index out of range");
    }
    {
        Octree t = copyOf(noiseTree());
        const std::uint32_t leafParent = nodeAtLevel(t, t.depth - 1);
        editTopology(t, [&](auto& nodes, auto& voxels) {
            nodes[leafParent].firstChild = std::uint32_t(voxels.size()) - 1;
            nodes[leafParent].childMask = 0xFF;
        });
        expectInvalid(t, "voxel index out of range");
    }
}

TEST(Octree, ValidateRejectsUnreachableAndSharedNodesAndVoxels) {
    {
        Octree t = copyOf(noiseTree());
        editTopology(t, [](auto& nodes, auto&) { nodes.push_back(nodes[1]); });
        expectInvalid(t, "unreachable node");
    }
    {
        Octree t = copyOf(noiseTree());
        editTopology(t, [](auto&, auto& voxels) { voxels.push_back(Voxel{}); });
        expectInvalid(t, "unreachable voxel");
    }
    {
        // A node pointing back at the root: a cycle.
        Octree t = copyOf(noiseTree());
        const std::uint32_t n1 = nodeAtLevel(t, 1);
        editTopology(t, [&](auto& nodes, auto&) { nodes[n1].firstChild = 0; });
        EXPECT_THROW(t.validate(), Error);
    }
    {
        // Two leaf parents sharing their voxels.
        Octree t = copyOf(noiseTree());
        std::vector<std::uint32_t> leafParents;
        for (auto [n, level] : allNodes(t))
            if (level == t.depth - 1) leafParents.push_back(n);
        ASSERT_GE(leafParents.size(), 2u);
        editTopology(t, [&](auto& nodes, auto&) {
            nodes[leafParents[1]].firstChild = nodes[leafParents[0]].firstChild;
            nodes[leafParents[1]].childMask = nodes[leafParents[0]].childMask;
        });
        expectInvalid(t, "voxel referenced twice");
    }
    {
        // An inner node whose only child is an empty inner node.
        Octree t = copyOf(noiseTree());
        const std::uint32_t n1 = nodeAtLevel(t, 1);
        editTopology(t, [&](auto& nodes, auto&) { nodes[n1].childMask = 0; });
        EXPECT_THROW(t.validate(), Error);
    }
}

TEST(Octree, ValidateRejectsBadMasksAndGeometry) {
    {
        // On an inner node that has an empty child slot.
        Octree t = copyOf(noiseTree());
        std::uint32_t node = 0xFFFFFFFFu;
        for (auto [n, level] : allNodes(t))
            if (level < t.depth - 1 && t.nodes()[n].childMask != 0xFF) node = n;
        ASSERT_NE(node, 0xFFFFFFFFu);
        editTopology(t, [&](auto& nodes, auto&) { nodes[node].termMask = std::uint8_t(~nodes[node].childMask); });
        expectInvalid(t, "term bit without child bit");
    }
    {
        Octree t = copyOf(noiseTree());
        const std::uint32_t leafParent = nodeAtLevel(t, t.depth - 1);
        editTopology(t, [&](auto& nodes, auto&) {
            nodes[leafParent].termMask = nodes[leafParent].childMask & std::uint8_t(-nodes[leafParent].childMask);
        });
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
    // lose nothing. Every per-voxel buffer filled, every well-known metadata key set and one
    // that is not well known.
    Octree t = withEveryBuffer(noiseTree());
    const std::size_t n = t.voxels().size();
    t.setMetadata(octree_key::kFieldName, "temp");
    t.setMetadata(octree_key::kFieldUnits, "degC");
    t.iso = 10.0;
    t.insideBelow = true;
    t.setMetadata(octree_key::kSource, "a.nc");
    t.setMetadata(octree_key::kCrs, "EPSG:7415");
    t.setMetadata(octree_key::kValueName, "salt");
    t.setMetadata(octree_key::kValueUnits, "psu");
    t.setMetadata(octree_key::kValueStandardName, "sea_water_salinity");
    t.setMetadata("operator", "someone");
    ASSERT_EQ(t.metadata().size(), 8u);
    const Octree c = t.copy();
    EXPECT_EQ(c.nodes().size(), t.nodes().size());
    EXPECT_EQ(c.voxels().size(), n);
    EXPECT_EQ(c.colours(), t.colours());
    EXPECT_EQ(c.voxelValues(), t.voxelValues());
    EXPECT_EQ(c.baked(), t.baked());
    EXPECT_EQ(c.voxelMaterials(), t.voxelMaterials());
    EXPECT_EQ(c.summaries().size(), t.summaries().size());
    EXPECT_EQ(c.bytes(), t.bytes());
    const Octree e = t.emptyCopy();
    for (const Octree* o : {&c, &e}) {
        EXPECT_EQ(o->depth, t.depth);
        EXPECT_EQ(o->cubeOrigin, t.cubeOrigin);
        EXPECT_EQ(o->cubeSide, t.cubeSide);
        EXPECT_EQ(o->form, t.form);
        EXPECT_EQ(o->iso, t.iso);
        EXPECT_EQ(o->insideBelow, t.insideBelow);
        EXPECT_EQ(o->metadata(), t.metadata());  // every key, the unknown one too
        EXPECT_EQ(o->fieldName(), "temp");
        EXPECT_EQ(o->fieldUnits(), "degC");
        EXPECT_EQ(o->source(), "a.nc");
        EXPECT_EQ(o->crs(), "EPSG:7415");
        EXPECT_EQ(o->valueName(), "salt");
        EXPECT_EQ(o->valueUnits(), "psu");
        EXPECT_EQ(o->valueStandardName(), "sea_water_salinity");
        EXPECT_EQ(o->metadata("operator"), "someone");
    }
    EXPECT_TRUE(e.nodes().empty() && e.voxels().empty() && e.colours().empty() && e.voxelValues().empty() &&
                e.baked().empty() && e.voxelMaterials().empty() && e.summaries().empty());
}

// ---------------------------------------------------------------------------------------------
// Invariants: attribute lengths, setTopology, metadata

namespace {
/// The message of the Error that f throws; fails the test when it throws none.
template <class F>
std::string errorOf(F&& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no Error thrown";
    return {};
}
}  // namespace

TEST(Octree, AttributeSettersRefuseAWrongLengthNamingTheAttributeAndBothLengths) {
    Octree t = copyOf(noiseTree());
    const std::size_t n = t.voxels().size();
    const std::string wrong = std::to_string(n + 1) + " entries", right = "one per voxel (" + std::to_string(n) + ")";
    for (const auto& [name, set] : std::vector<std::pair<std::string, std::function<void()>>>{
             {"'colours'", [&] { t.setColours(std::vector<std::uint32_t>(n + 1)); }},
             {"'voxel values'", [&] { t.setVoxelValues(std::vector<float>(n + 1)); }},
             {"'baked light'", [&] { t.setBaked(std::vector<std::uint8_t>(n + 1)); }},
             {"'voxel materials'", [&] { t.setVoxelMaterials(std::vector<std::uint8_t>(n + 1)); }}}) {
        const std::string message = errorOf(set);
        EXPECT_NE(message.find(name), std::string::npos) << message;
        EXPECT_NE(message.find(wrong), std::string::npos) << message;
        EXPECT_NE(message.find(right), std::string::npos) << message;
    }
    // Refused: nothing was set. Empty or one per voxel: accepted.
    EXPECT_TRUE(t.colours().empty() && t.voxelValues().empty() && t.baked().empty() && t.voxelMaterials().empty());
    t.setVoxelValues(std::vector<float>(n, 1.0f));
    EXPECT_EQ(t.voxelValues().size(), n);
    EXPECT_NO_THROW(t.validate());
    t.setVoxelValues({});
    EXPECT_TRUE(t.voxelValues().empty());
    // setAttributes checks all four and sets none of them when one is wrong.
    VoxelAttributes a;
    a.colours.assign(n, 7u);
    a.baked.assign(n - 1, 1);
    EXPECT_NE(errorOf([&] { t.setAttributes(a); }).find("'baked light' has " + std::to_string(n - 1)), std::string::npos);
    EXPECT_TRUE(t.colours().empty());
    a.baked.assign(n, 1);
    t.setAttributes(a);
    EXPECT_EQ(t.colours(), a.colours);
    EXPECT_EQ(t.baked(), a.baked);
    // takeAttributes hands them over and leaves none.
    const VoxelAttributes taken = t.takeAttributes();
    EXPECT_EQ(taken.colours, a.colours);
    EXPECT_TRUE(t.colours().empty() && t.baked().empty());
}

TEST(Octree, SetTopologyKeepsAttributesOfTheNewVoxelCountAndDropsTheOthersAndTheSummaries) {
    Octree t = withEveryBuffer(noiseTree());
    const std::size_t n = t.voxels().size();
    ASSERT_TRUE(t.hasSummaries());
    // The same voxel count (here: new normals): every attribute kept, the summaries dropped.
    std::vector<Voxel> voxels = t.voxels();
    for (Voxel& v : voxels) v.normal = encodeNormal(vec3(1, 0, 0));
    t.setTopology(std::vector<OctreeNode>(t.nodes()), std::move(voxels));
    EXPECT_EQ(t.colours().size(), n);
    EXPECT_EQ(t.voxelValues().size(), n);
    EXPECT_EQ(t.baked().size(), n);
    EXPECT_EQ(t.voxelMaterials().size(), n);
    EXPECT_EQ(t.material(0), VoxelMaterial::Floor);
    EXPECT_TRUE(t.summaries().empty());
    EXPECT_FALSE(t.hasSummaries());
    EXPECT_NO_THROW(t.validate());
    // Another voxel count: every attribute dropped.
    editTopology(t, [](auto&, auto& voxels) { voxels.push_back(Voxel{}); });
    EXPECT_EQ(t.voxels().size(), n + 1);
    EXPECT_TRUE(t.colours().empty() && t.voxelValues().empty() && t.baked().empty() && t.voxelMaterials().empty());
    EXPECT_FALSE(t.hasColours());
    EXPECT_EQ(t.material(0), VoxelMaterial::Surface);
    // setVoxelNormal changes one normal in place, nothing else.
    t.setVoxelNormal(3, 12345u);
    EXPECT_EQ(t.voxels()[3].normal, 12345u);
    EXPECT_EQ(t.voxels().size(), n + 1);
}

TEST(Octree, MetadataHoldsNoEmptyValueAndReadsAbsentKeysAsEmpty) {
    Octree t;
    EXPECT_TRUE(t.metadata().empty());
    EXPECT_EQ(t.crs(), "");
    EXPECT_EQ(t.metadata("anything"), "");
    t.setMetadata(octree_key::kCrs, "EPSG:7415");
    t.setMetadata(octree_key::kSource, "a.nc");
    EXPECT_EQ(t.crs(), "EPSG:7415");
    EXPECT_EQ(t.metadata(octree_key::kCrs), "EPSG:7415");
    t.setMetadata(octree_key::kCrs, "EPSG:28992");  // replaces
    EXPECT_EQ(t.crs(), "EPSG:28992");
    t.setMetadata(octree_key::kCrs, "");  // removes: absent and empty are one
    EXPECT_EQ(t.crs(), "");
    EXPECT_EQ(t.metadata().count(std::string(octree_key::kCrs)), 0u);
    // Ordered by key, so that listings are stable.
    t.setMetadata("b", "2");
    t.setMetadata("a", "1");
    std::vector<std::string> keys;
    for (const auto& [k, v] : t.metadata()) keys.push_back(k);
    EXPECT_EQ(keys, (std::vector<std::string>{"a", "b", "source"}));
}
