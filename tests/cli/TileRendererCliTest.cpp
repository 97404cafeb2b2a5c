// The tile renderer on the real data through the CLI: `--verify` finds 0 mismatched pixels and
// the PNG bytes equal `full`'s, for 1 and 2 threads and two tile sizes, on the Levitus isotherm
// (default framing and Table 1's camera), the chest CT and the Delft city (per-region depth:
// coarse leaves); the fields with voxel and with smooth surfaces (`--surface` given to both:
// tile, not a paper renderer, draws smooth surfaces of fields by default, full voxels).
// Each scene is built once into an octree file that the renders read. Skipped without
// ../shared/data.
#include "CliRunner.h"

using namespace octrace::testcli;

namespace {

// `input` is an input and its build options. Unless `mixedDepth` (octree files do not hold
// coarse leaves yet), the octree is built once into an octree file (with its corner values) and
// the five renders below read it, so that the test's time goes to rendering, not to reading and
// building the same input five times. `view` is what the renders add (camera, surface).
void expectTileEqualsFull(const std::string& name, std::vector<std::string> input, const std::vector<std::string>& view,
                          bool mixedDepth = false) {
    SCOPED_TRACE(name);
    Scratch s;
    std::vector<std::string> scene{"render"};
    if (mixedDepth) {
        scene.insert(scene.end(), input.begin(), input.end());
    } else {
        input.insert(input.begin(), "build");
        input.insert(input.end(), {"--compression", "1", "--quiet", "-o", s.path("scene.oct")});
        const Result built = run(input);
        ASSERT_EQ(built.code, 0) << built.err;
        scene.push_back(s.path("scene.oct"));
    }
    scene.insert(scene.end(), view.begin(), view.end());
    scene.insert(scene.end(), {"--size", "400x300", "--quiet"});
    std::vector<std::string> full = scene;
    full.insert(full.end(), {"--renderer", "full", "--threads", "2", "-o", s.path("full.png")});
    Result r = run(full);
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string fullPng = slurp(s.path("full.png"));
    ASSERT_FALSE(fullPng.empty());
    for (const char* threads : {"1", "2"})
        for (const char* tile : {"8", "5"}) {
            SCOPED_TRACE(std::string("threads ") + threads + ", tile " + tile);
            std::vector<std::string> args = scene;
            args.insert(args.end(), {"--renderer", "tile", "--tile-size", tile, "--threads", threads, "--verify",
                                     "--stats", s.path("tile.json"), "-o", s.path("tile.png")});
            r = run(args);
            ASSERT_EQ(r.code, 0) << r.err;
            const std::string js = slurp(s.path("tile.json"));
            EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
            EXPECT_NE(js.find(std::string("\"tile_size\": ") + tile), std::string::npos) << js;
            EXPECT_TRUE(slurp(s.path("tile.png")) == fullPng);
        }
}

}  // namespace

TEST(TileRendererCli, EqualsFullOnTheLevitusIsothermAtTheDefaultFramingAndTable1sCamera) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent: " << lev;
    const std::vector<std::string> scene{lev, "--var", "TEMP", "--iso", "10", "--region", "120,180,10,60", "--depth", "8"};
    const std::vector<std::string> table1{"--camera-pos", "7738.087169,-14069.2494,9870.868124", "--look-at", "0,0,-681.068925",
                                          "--up", "0,0,1", "--fov", "30"};
    for (const std::string surface : {"voxel", "smooth"}) {
        std::vector<std::string> b = table1;
        b.insert(b.end(), {"--surface", surface});
        expectTileEqualsFull("default framing, " + surface, scene, {"--surface", surface});
        expectTileEqualsFull("Table 1 camera, " + surface, scene, b);
    }
}

TEST(TileRendererCli, EqualsFullOnTheChestCtAndTheCity) {
    if (!haveShared("medical/lidc2_chest_ct.nrrd") || !haveShared("city/delft.json"))
        GTEST_SKIP() << "shared data absent: " << sharedData("medical");
    for (const std::string surface : {"voxel", "smooth"})
        expectTileEqualsFull("chest CT, " + surface, {sharedData("medical/lidc2_chest_ct.nrrd"), "--iso", "100", "--depth", "8"},
                             {"--surface", surface});
    expectTileEqualsFull("Delft", {sharedData("city/delft.json"), "--depth", "9", "--terrain-depth", "7"}, {}, true);
}
