// octrace render --figure: the PNG's pixel size for a print size and dpi (recorded in pHYs),
// its plot area against the plain render of the same view, and the usage errors.
#include "CliRunner.h"
#include "../io/ImageTestSupport.h"

#include <regex>

using namespace octrace::testcli;

namespace {
std::vector<int> statInts(const std::string& js, const std::string& key) {
    std::smatch m;
    std::vector<int> v;
    if (!std::regex_search(js, m, std::regex("\"" + key + "\": \"?([0-9,]+)\"?"))) return v;
    std::stringstream s(m[1]);
    for (std::string part; std::getline(s, part, ',');) v.push_back(std::stoi(part));
    return v;
}
/// pHYs chunk: pixels per unit x, y and the unit byte.
bool pixelsPerMetre(const std::vector<std::uint8_t>& png, std::uint32_t& ppm) {
    for (std::size_t i = 8; i + 12 <= png.size();) {
        const std::uint32_t len = std::uint32_t(png[i]) << 24 | std::uint32_t(png[i + 1]) << 16 | std::uint32_t(png[i + 2]) << 8 | png[i + 3];
        if (std::string(png.begin() + std::ptrdiff_t(i) + 4, png.begin() + std::ptrdiff_t(i) + 8) == "pHYs" && len == 9) {
            const std::uint8_t* d = png.data() + i + 8;
            ppm = std::uint32_t(d[0]) << 24 | std::uint32_t(d[1]) << 16 | std::uint32_t(d[2]) << 8 | d[3];
            return d[8] == 1;
        }
        i += 12 + len;
    }
    return false;
}
}  // namespace

TEST(FigureCli, HasThePrintSizeTimesTheDpiAndItsPlotIsThePlainRender) {
    Scratch s;
    // 80 x 60 mm at 200 dpi: 630 x 472 pixels.
    Result r = run({"render", "analytic:torus:33", "--iso", "0", "--depth", "6", "--figure", "--title", "Torus",
                    "--print-size", "80x60mm", "--dpi", "200", "--stats", s.path("f.json"), "-o", s.path("fig.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::vector<std::uint8_t> bytes = octrace::test::readBytes(s.path("fig.png"));
    const auto fig = octrace::test::decodePng(bytes);
    EXPECT_EQ(fig.width, 630);
    EXPECT_EQ(fig.height, 472);
    std::uint32_t ppm = 0;
    ASSERT_TRUE(pixelsPerMetre(bytes, ppm));
    EXPECT_EQ(ppm, 7874u);  // 200 / 0.0254
    const std::string js = slurp(s.path("f.json"));
    const std::vector<int> plot = statInts(js, "figure_plot");
    ASSERT_EQ(plot.size(), 4u) << js;
    // The plain render of the same view at the plot's size.
    r = run({"render", "analytic:torus:33", "--iso", "0", "--depth", "6", "--size",
             std::to_string(plot[2]) + "x" + std::to_string(plot[3]), "-o", s.path("plain.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const auto plain = octrace::test::decodePng(octrace::test::readBytes(s.path("plain.png")));
    ASSERT_EQ(plain.width, plot[2]);
    ASSERT_EQ(plain.height, plot[3]);
    // The bounding box and its labels are drawn over the plot; everywhere else it is the
    // plain render's pixels (io FigureTest checks the exact overlay).
    std::size_t same = 0;
    for (int y = 0; y < plain.height; ++y)
        for (int x = 0; x < plain.width; ++x) {
            bool eq = true;
            for (int c = 0; c < 3; ++c) eq = eq && fig.at(plot[0] + x, plot[1] + y, c) == plain.at(x, y, c);
            same += eq;
        }
    // (The box's edges and its labels, which the figure's fitted margins may bring inside the
    // plot's edge, cover a few percent of it.)
    EXPECT_GT(double(same), 0.9 * plain.width * plain.height);
    EXPECT_LT(double(same), double(plain.width) * plain.height);  // the box is drawn
}

TEST(FigureCli, LevitusFigureHasAColourBarThatFollowsTheColourMap) {
    const std::string lev = sharedData("ocean/levitus_climatology.cdf");
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent: " << lev;
    Scratch s;
    Result r = run({"render", lev, "--var", "SALT", "--iso", "34.5", "--colour-by", "TEMP", "--colormap", "haline",
                    "--region", "120,260,0,65", "--depth", "6", "--figure", "--size", "700x500", "--verify", "--stats",
                    s.path("f.json"), "-o", s.path("fig.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("f.json"));
    EXPECT_NE(js.find("\"mismatched_pixels\": 0,"), std::string::npos) << js;
    const auto fig = octrace::test::decodePng(octrace::test::readBytes(s.path("fig.png")));
    EXPECT_EQ(fig.width, 700);
    EXPECT_EQ(fig.height, 500);
    const std::vector<int> bar = statInts(js, "figure_colour_bar");
    ASSERT_EQ(bar.size(), 4u) << js;
    // Row r of the bar is the map's colour at 1 - (r + 0.5) / height, in 8-bit sRGB: the
    // haline map runs from dark blue (bottom) to pale yellow (top).
    const int x = bar[0] + bar[2] / 2;
    EXPECT_LT(fig.at(x, bar[1] + bar[3] - 1, 0), 60);   // bottom: dark
    EXPECT_GT(fig.at(x, bar[1], 0), 230);               // top: pale
    auto luma = [&](int y) { return 0.2126 * fig.at(x, y, 0) + 0.7152 * fig.at(x, y, 1) + 0.0722 * fig.at(x, y, 2); };
    int darkerUpwards = 0;
    for (int y = bar[1]; y + 1 < bar[1] + bar[3]; ++y) darkerUpwards += luma(y) < luma(y + 1) - 1.5;  // 8-bit rounding
    EXPECT_EQ(darkerUpwards, 0);  // brighter upwards
}

TEST(FigureCli, ASurfaceColouredByHeightGetsAColourBarOfTheMap) {
    Scratch s;
    // Without --colormap the surface has one colour: no bar.
    Result r = run({"render", "analytic:torus:33", "--iso", "0", "--depth", "6", "--figure", "--size", "500x360",
                    "--stats", s.path("plain.json"), "-o", s.path("plain.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(statInts(slurp(s.path("plain.json")), "figure_colour_bar").empty());
    // With a colour map the surface is coloured by height, and the bar shows the map: viridis
    // from dark purple (bottom) to yellow (top), brighter upwards.
    r = run({"render", "analytic:torus:33", "--iso", "0", "--depth", "6", "--colormap", "viridis", "--figure", "--size",
             "500x360", "--stats", s.path("f.json"), "-o", s.path("fig.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("f.json"));
    const std::vector<int> bar = statInts(js, "figure_colour_bar");
    ASSERT_EQ(bar.size(), 4u) << js;
    const auto fig = octrace::test::decodePng(octrace::test::readBytes(s.path("fig.png")));
    const int x = bar[0] + bar[2] / 2;
    EXPECT_LT(fig.at(x, bar[1] + bar[3] - 1, 1), 40);  // bottom: viridis starts at (68, 1, 84)
    EXPECT_GT(fig.at(x, bar[1], 1), 200);              // top: viridis ends at (253, 231, 37)
    auto luma = [&](int y) { return 0.2126 * fig.at(x, y, 0) + 0.7152 * fig.at(x, y, 1) + 0.0722 * fig.at(x, y, 2); };
    int darkerUpwards = 0;
    for (int y = bar[1]; y + 1 < bar[1] + bar[3]; ++y) darkerUpwards += luma(y) < luma(y + 1) - 1.5;
    EXPECT_EQ(darkerUpwards, 0);
}

TEST(FigureCli, RefusesFigureOptionsThatCannotApply) {
    Scratch s;
    for (const std::vector<std::string>& args :
         {std::vector<std::string>{"--title", "x"}, {"--print-size", "80x60mm"}, {"--scale-bar"}, {"--ambient", "1.5"},
          {"--ambient", "-0.1"}, {"--figure", "--print-size", "80x60"},
          {"--figure", "--print-size", "0x60mm"}, {"--figure", "--dpi", "5"}, {"--figure", "--size", "60x40", "--dpi", "600"}}) {
        std::vector<std::string> all{"render", "analytic:sphere:9", "-o", s.path("x.png")};
        all.insert(all.end(), args.begin(), args.end());
        Result r = run(all);
        EXPECT_EQ(r.code, 2) << args[0] << " " << r.err;
        EXPECT_FALSE(std::filesystem::exists(s.path("x.png")));
    }
    Result r = run({"render", "analytic:sphere:9", "--figure", "-o", s.path("x.exr")});
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("a figure is written as PNG or TIFF"), std::string::npos) << r.err;
}

TEST(FigureCli, ATiffFigureHasThePngFiguresPixelsAndDpi) {
    Scratch s;
    const std::vector<std::string> base{"render", "analytic:torus:33", "--iso", "0", "--depth", "6", "--figure",
                                        "--title", "Torus", "--scale-bar", "--size", "400x300", "--dpi", "240"};
    for (const char* out : {"fig.png", "fig.TIF", "fig.tiff"}) {
        std::vector<std::string> args = base;
        args.insert(args.end(), {"-o", s.path(out)});
        Result r = run(args);
        ASSERT_EQ(r.code, 0) << out << ": " << r.err;
    }
    const auto png = octrace::test::decodePng(octrace::test::readBytes(s.path("fig.png")));
    for (const char* out : {"fig.TIF", "fig.tiff"}) {
        const auto tif = octrace::test::decodeTiff(s.path(out));
        EXPECT_EQ(int(tif.width), png.width) << out;
        EXPECT_EQ(int(tif.height), png.height) << out;
        EXPECT_EQ(int(tif.samples), png.channels) << out;
        EXPECT_EQ(tif.pixels, png.pixels) << out;
        EXPECT_EQ(tif.dpi, 240.0f) << out;
    }
}

TEST(FigureCli, ScaleBarIsDrawnInThePlotsLowerLeftCornerOnly) {
    Scratch s;
    const std::vector<std::string> base{"render", "analytic:torus:33", "--iso", "0", "--depth", "6", "--figure",
                                        "--size", "500x400", "--stats", s.path("f.json")};
    std::vector<std::string> with = base, without = base;
    with.insert(with.end(), {"--scale-bar", "-o", s.path("bar.png")});
    without.insert(without.end(), {"-o", s.path("plain.png")});
    ASSERT_EQ(run(without).code, 0);
    Result r = run(with);
    ASSERT_EQ(r.code, 0) << r.err;
    const std::vector<int> plot = statInts(slurp(s.path("f.json")), "figure_plot");
    ASSERT_EQ(plot.size(), 4u);
    const auto a = octrace::test::decodePng(octrace::test::readBytes(s.path("bar.png")));
    const auto b = octrace::test::decodePng(octrace::test::readBytes(s.path("plain.png")));
    ASSERT_EQ(a.width, b.width);
    // Every differing pixel lies in the lower left quarter of the plot (the bar is at most a
    // fifth of its width, its label above it), and there are some.
    std::size_t differ = 0, outside = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            bool d = false;
            for (int c = 0; c < 3; ++c) d = d || a.at(x, y, c) != b.at(x, y, c);
            if (!d) continue;
            ++differ;
            outside += !(x >= plot[0] && x < plot[0] + plot[2] / 2 && y >= plot[1] + plot[3] / 2 && y < plot[1] + plot[3]);
        }
    EXPECT_GT(differ, 50u);
    EXPECT_EQ(outside, 0u);
}

TEST(FigureCli, AmbientLightensTheShadedSideAndDoesNotChangeTheLitOne) {
    Scratch s;
    const std::vector<std::string> base{"render", "analytic:sphere:17", "--iso", "0", "--depth", "6", "--size", "120x120",
                                        "--light", "0,0,1"};
    std::vector<std::string> dim = base, bright = base;
    dim.insert(dim.end(), {"--ambient", "0", "-o", s.path("dim.png")});
    bright.insert(bright.end(), {"--ambient", "0.6", "-o", s.path("bright.png")});
    ASSERT_EQ(run(dim).code, 0);
    ASSERT_EQ(run(bright).code, 0);
    const auto a = octrace::test::decodePng(octrace::test::readBytes(s.path("dim.png")));
    const auto b = octrace::test::decodePng(octrace::test::readBytes(s.path("bright.png")));
    // The sphere's centre faces the light: ambient + (1 - ambient) x 1 = 1 either way. Near its
    // rim the normal turns away from the light: more ambient is brighter there.
    EXPECT_NEAR(double(a.at(60, 60, 0)), double(b.at(60, 60, 0)), 1.0);
    int brighter = 0, rim = 0;
    for (int x = 0; x < 120; ++x) {
        const bool hitA = a.at(x, 60, 0) != 255 || a.at(x, 60, 1) != 255, hitB = b.at(x, 60, 0) != 255 || b.at(x, 60, 1) != 255;
        if (!hitA || !hitB) continue;
        ++rim;
        brighter += b.at(x, 60, 0) > a.at(x, 60, 0) + 2;
    }
    EXPECT_GT(rim, 10);
    EXPECT_GT(brighter, 4);
}
