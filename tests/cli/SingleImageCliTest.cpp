// A single DICOM image (the real CT_small.dcm and MR_small.dcm of ../shared/data/medical):
// `slice` shows it in its own plane, every pixel the window's grey of the stored value after
// the rescale (the stored values read from the file's Pixel Data bytes, not by octrace), with
// the letters of its orientation; another plane, a position off it, and `render` are refused.
#include "CliRunner.h"
#include "../io/DicomPixelData.h"
#include "../io/ImageTestSupport.h"

#include <algorithm>
#include <cmath>

using namespace octrace::testcli;

namespace {

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

int greyByte(double v, double centre, double width) {
    const double g = std::clamp((v - (centre - 0.5 * width)) / width, 0.0, 1.0);
    return int(std::lround(g * 255.0));
}

/// Pixels of `png` (columns x rows, as stored: an axial image with rows along +x and columns
/// along +y is shown as stored) that differ from the window's grey of `values`.
int wrongPixels(const octrace::test::DecodedPng& png, const std::vector<double>& values, int columns, double centre, double width) {
    int wrong = 0;
    for (int y = 0; y < png.height; ++y)
        for (int x = 0; x < png.width; ++x) {
            const int want = greyByte(values[std::size_t(y) * std::size_t(columns) + std::size_t(x)], centre, width);
            for (int c = 0; c < 3; ++c) wrong += png.at(x, y, c) != want;
        }
    return wrong;
}

}  // namespace

// CT_small.dcm: 128 x 128 axial, 0.661468 mm pixels, HU = stored - 1024, no stored window (so
// the image's value range greys it), then the presets and a number pair as for volumes.
TEST(SingleImageCli, ACtImageIsShownInItsOwnPlaneWithTheWindowOfItsHounsfieldUnits) {
    if (!haveShared("medical/CT_small.dcm")) GTEST_SKIP() << "shared data absent: " << sharedData("medical/CT_small.dcm");
    const std::string ct = sharedData("medical/CT_small.dcm");
    std::vector<double> hu = octrace::test::storedPixels16(ct, 128 * 128, false, true);
    ASSERT_EQ(hu.size(), 128u * 128u);
    for (double& v : hu) v -= 1024.0;
    const auto [lo, hi] = std::minmax_element(hu.begin(), hu.end());
    Scratch s;
    struct Case {
        const char* window;
        double centre, width;
    };
    const Case cases[] = {{"", 0.5 * (*lo + *hi), *hi - *lo}, {"soft-tissue", 40.0, 400.0}, {"bone", 400.0, 1800.0}, {"-600,1500", -600.0, 1500.0}};
    for (const Case& c : cases) {
        std::vector<std::string> args = {"slice", ct, "--stats", s.path("st.json"), "-o", s.path("ct.png")};
        if (*c.window) args.insert(args.end(), {"--window", c.window});
        const Result r = run(args);
        ASSERT_EQ(r.code, 0) << r.err;
        const std::string js = slurp(s.path("st.json"));
        EXPECT_TRUE(has(js, "\"plane\": \"axial\"")) << js;
        EXPECT_TRUE(has(js, "\"screen_right\": \"L\"")) << js;
        EXPECT_TRUE(has(js, "\"screen_up\": \"A\"")) << js;
        EXPECT_TRUE(has(js, "\"pixel_size\": 0.661468")) << js;
        EXPECT_TRUE(has(js, "\"valid_pixels\": 16384")) << js;
        if (!*c.window) {
            EXPECT_TRUE(has(js, "\"colour_source\": \"the volume's value range\"")) << js;
        }
        const auto png = octrace::test::decodePng(octrace::test::readBytes(s.path("ct.png")));
        ASSERT_EQ(png.width, 128);
        ASSERT_EQ(png.height, 128);
        EXPECT_EQ(wrongPixels(png, hu, 128, c.centre, c.width), 0) << c.window;
    }
    // The first pixel as a viewer shows it in the soft-tissue window: stored 0xaf = 175, HU -849, black.
    EXPECT_EQ(hu[0], -849.0);
}

// MR_small.dcm: its stored window 600/1600 by default (values as stored, MR has no rescale),
// the big-endian copy giving the same bytes; --figure draws the letters of an axial image.
TEST(SingleImageCli, AnMrImageIsShownInItsStoredWindowAndAsAFigure) {
    if (!haveShared("medical/MR_small.dcm")) GTEST_SKIP() << "shared data absent: " << sharedData("medical/MR_small.dcm");
    const std::string mr = sharedData("medical/MR_small.dcm");
    const std::vector<double> stored = octrace::test::storedPixels16(mr, 64 * 64, false, true);
    ASSERT_EQ(stored.size(), 64u * 64u);
    Scratch s;
    Result r = run({"slice", mr, "--stats", s.path("st.json"), "-o", s.path("mr.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("st.json"));
    EXPECT_TRUE(has(js, "\"window_centre\": 600,")) << js;
    EXPECT_TRUE(has(js, "\"window_width\": 1600,")) << js;
    EXPECT_TRUE(has(js, "\"colour_source\": \"the file's display window\"")) << js;
    const auto png = octrace::test::decodePng(octrace::test::readBytes(s.path("mr.png")));
    ASSERT_EQ(png.width, 64);
    ASSERT_EQ(png.height, 64);
    EXPECT_EQ(wrongPixels(png, stored, 64, 600.0, 1600.0), 0);

    r = run({"slice", sharedData("medical/MR_small_bigendian.dcm"), "-o", s.path("big.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(octrace::test::readBytes(s.path("big.png")), octrace::test::readBytes(s.path("mr.png")));

    r = run({"slice", mr, "--figure", "--size", "600x500", "--stats", s.path("f.json"), "-o", s.path("f.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string fj = slurp(s.path("f.json"));
    EXPECT_TRUE(has(fj, "\"figure_width\": 600")) << fj;
    EXPECT_TRUE(has(fj, "\"screen_right\": \"L\"")) << fj;
    EXPECT_TRUE(has(fj, "\"screen_up\": \"A\"")) << fj;
}

// One slice: another plane, a position off the image or an index beyond 0 are refused naming
// the image's plane and position, and nothing is written; its own position is accepted as
// printed (-75.7 for the stored -75.699997). `render` refuses it: a surface needs a volume.
// `info` says it is a single image.
TEST(SingleImageCli, OtherPlanesPositionsAndSurfacesAreRefusedPlainly) {
    if (!haveShared("medical/CT_small.dcm")) GTEST_SKIP() << "shared data absent: " << sharedData("medical/CT_small.dcm");
    const std::string ct = sharedData("medical/CT_small.dcm");
    Scratch s;
    Result r = run({"slice", ct, "--plane", "coronal", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_TRUE(has(r.err, ct + ": a single axial image has one slice, its own plane: --plane coronal would cut it along a line"))
        << r.err;
    r = run({"slice", ct, "--at", "-70", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_TRUE(has(r.err, ct + ": a single axial image lies at z = -75.7 mm: --at -70 is off it")) << r.err;
    r = run({"slice", ct, "--index", "1", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_TRUE(has(r.err, "--index 1 is beyond it")) << r.err;
    r = run({"render", ct, "-o", s.path("r.png")});
    EXPECT_EQ(r.code, 1) << r.err;
    EXPECT_TRUE(has(r.err, ct + ": a single 128x128 CT image")) << r.err;
    EXPECT_TRUE(has(r.err, "a surface needs a volume, a series of slices or a multi-frame image")) << r.err;
    EXPECT_EQ(countEntries(s.dir()), 0);

    r = run({"slice", ct, "--at", "-75.7", "--plane", "axial", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 0) << r.err;
    r = run({"info", ct});
    EXPECT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.out, "a single 128x128 CT image")) << r.out;
    EXPECT_TRUE(has(r.out, "128 x 128 x 1")) << r.out;
}
