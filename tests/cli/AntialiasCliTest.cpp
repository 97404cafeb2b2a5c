// `--samples N` on voxel scenes: render draws N exact samples per pixel and averages them;
// --verify compares with the reference drawn the same way.
#include "CliRunner.h"
#include "../io/ImageTestSupport.h"

#include <cmath>

using namespace octrace::testcli;

TEST(AntialiasCli, SamplesSmoothTheSilhouetteOfAVoxelSceneAndVerifyStaysExact) {
    Scratch s;
    // One colour (not the default colour map by height), so that a blend with the black
    // background is darker than any shaded surface pixel.
    // Voxel surfaces, which beam (below) draws too.
    const std::vector<std::string> base{"render", "analytic:torus", "--depth", "6", "--size", "160x120", "--background", "0,0,0",
                                        "--colour", "0.85,0.62,0.35", "--surface", "voxel"};
    auto draw = [&](const std::string& out, const std::vector<std::string>& extra) {
        std::vector<std::string> a = base;
        a.insert(a.end(), extra.begin(), extra.end());
        a.insert(a.end(), {"-o", s.path(out)});
        const Result r = run(a);
        EXPECT_EQ(r.code, 0) << r.err;
        return r;
    };
    draw("one.png", {});
    const Result r = draw("four.png", {"--samples", "4", "--verify", "--stats", s.path("four.json")});
    EXPECT_NE(r.err.find("verify: 0 pixels differ from the reference"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("PSNR inf dB"), std::string::npos) << r.err;
    EXPECT_NE(slurp(s.path("four.json")).find("\"samples\": 4"), std::string::npos) << slurp(s.path("four.json"));
    // The same renderer name through beam (another traversal) gives the same bytes.
    draw("beam.png", {"--samples", "4", "--renderer", "beam"});
    EXPECT_EQ(slurp(s.path("beam.png")), slurp(s.path("four.png")));

    // Against the black background, one sample per pixel gives only surface colours and black;
    // four give blends along the silhouette: more distinct grey levels of the red channel, and
    // pixels darker than any surface pixel of the one-sample image but not black.
    const auto one = octrace::test::decodePng(octrace::test::readBytes(s.path("one.png")));
    const auto four = octrace::test::decodePng(octrace::test::readBytes(s.path("four.png")));
    ASSERT_EQ(one.pixels.size(), four.pixels.size());
    int darkestSurface = 255;
    for (std::size_t i = 0; i < one.pixels.size(); i += std::size_t(one.channels)) {
        const int lum = one.pixels[i] + one.pixels[i + 1] + one.pixels[i + 2];
        if (lum > 0) darkestSurface = std::min(darkestSurface, int(one.pixels[i]) + int(one.pixels[i + 1]) + int(one.pixels[i + 2]));
    }
    std::size_t blended = 0;
    for (std::size_t i = 0; i < four.pixels.size(); i += std::size_t(four.channels)) {
        const int lum = four.pixels[i] + four.pixels[i + 1] + four.pixels[i + 2];
        blended += lum > 0 && lum < darkestSurface;
    }
    EXPECT_GT(blended, 50u) << "darkest surface pixel without antialiasing: " << darkestSurface;
}
