// The discrete traversal against the reference on octrees built from real data (the Levitus
// atlas, the LIDC chest CT): random rays, half aimed at voxels, lattice rays through node
// corners and edges, eyes inside the cube. Skipped when ../shared/data is absent.
#include "../core/TraversalTestUtil.h"

#include "octrace/build/OctreeBuilder.h"
#include "octrace/io/FieldReader.h"

#include <filesystem>

using namespace octrace;
using namespace octrace::testutil;

namespace {

std::string shared(const std::string& rel) { return std::string(OCTRACE_SHARED_DATA) + "/" + rel; }

void checkTree(const Octree& t, long randomRays) {
    Tally out;
    const VoxelCells cells(t);
    runRays(t, randomRays / 2, 1, [&cells](std::mt19937_64& r, dvec3& o, dvec3& d) { rayAtVoxel(cells, r, o, d); }, out);
    runRays(t, randomRays / 2, 2, [](std::mt19937_64& r, dvec3& o, dvec3& d) { randomRay(r, o, d); }, out);
    runRays(t, 20000, 3, [](std::mt19937_64& r, dvec3& o, dvec3& d) { latticeRay(r, o, d); }, out);
    runRays(t, 20000, 4, [](std::mt19937_64& r, dvec3& o, dvec3& d) { insideRay(r, o, d); }, out);
    EXPECT_EQ(out.mismatches.load(), 0) << "first mismatch: " << out.first;
    EXPECT_GE(double(out.hits) / double(out.rays), 0.4) << out.hits << " hits of " << out.rays;
}

}  // namespace

TEST(DiscreteTraversalRealData, MatchesReferenceOnTheLevitusTemperatureIsosurface) {
    const std::string path = shared("ocean/levitus_climatology.cdf");
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
    io::FieldRequest req;
    req.variable = "TEMP";
    req.hasRegion = true;
    double region[4] = {120, 180, 10, 60};
    std::copy(region, region + 4, req.region);
    ScalarField f = io::readField(path, req);
    Octree t = buildShellOctree(f, {9, 10.0, 0});
    ASSERT_GT(t.boundaryVoxels(), 100000u);
    checkTree(t, 300000);
}

TEST(DiscreteTraversalRealData, MatchesReferenceOnTheChestCtBoneSurface) {
    const std::string path = shared("medical/lidc2_chest_ct.nrrd");
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "shared data absent: " << path;
    ScalarField f = io::readField(path);
    Octree t = buildShellOctree(f, {8, 100.0, 0});
    checkTree(t, 200000);
}
