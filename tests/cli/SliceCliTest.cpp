// octrace slice: the screen conventions of radiology proved on a DICOM series with an oblique
// acquisition and a marker at a known patient position (never mirrored), pixel bytes equal to
// the display window of the voxel values, real data (the LIDC chest CT as a DICOM series, the
// Levitus temperature at a depth), and the usage errors.
#include "ChestCt.h"
#include "CliRunner.h"
#include "../io/ImageTestSupport.h"

#include "octrace/io/DicomSeriesWriter.h"
#include "octrace/io/FieldReader.h"

#include <cmath>

using namespace octrace::testcli;
using octrace::dvec3;

namespace {

bool has(const std::string& text, const std::string& what) { return text.find(what) != std::string::npos; }

/// A CT acquired coronally and sideways: rows run to the patient's right (-x), columns to the
/// feet (-z), slices towards the front (-y). HU linear in the grid index, and one marker voxel
/// of 3000 HU near the patient's left-anterior-superior corner.
struct ObliqueCt {
    octrace::ScalarField f;
    octrace::ivec3 marker{2, 2, 0};
    static double hu(double i, double j, double k) { return -400.0 + 40.0 * i + 20.0 * j + 30.0 * k; }
    ObliqueCt() {
        f.dims = octrace::ivec3(12, 10, 8);
        f.spacing = dvec3(0.8, 2.0, 0.8);
        f.direction = octrace::dmat3(dvec3(-1, 0, 0), dvec3(0, 0, -1), dvec3(0, -1, 0));
        f.origin = dvec3(30.0, -20.0, 100.0);
        marker.z = f.dims.z - 3;  // k grows towards anterior: the front is the high k
        f.values.resize(f.sampleCount());
        for (int k = 0; k < f.dims.z; ++k)
            for (int j = 0; j < f.dims.y; ++j)
                for (int i = 0; i < f.dims.x; ++i) f.values[f.index(i, j, k)] = float(hu(i, j, k));
        f.values[f.index(marker.x, marker.y, marker.z)] = 3000.0f;
    }
    dvec3 markerWorld() const { return f.worldFromGrid(marker.x, marker.y, marker.z); }
    /// HU at a world point (linear: trilinear interpolation reproduces it).
    double huAt(const dvec3& p) const {
        const dvec3 local = glm::transpose(f.direction) * (p - f.origin);
        return hu(local.x / f.spacing.x, local.y / f.spacing.y, local.z / f.spacing.z);
    }
};

struct Bright {
    int x = -1, y = -1;
};
/// The centre of the white (255) pixels: the marker and its interpolated neighbours.
Bright brightest(const octrace::test::DecodedPng& png) {
    double sx = 0.0, sy = 0.0;
    int n = 0;
    for (int y = 0; y < png.height; ++y)
        for (int x = 0; x < png.width; ++x)
            if (png.at(x, y, 0) == 255) sx += x, sy += y, ++n;
    if (n == 0) return {};
    return {int(std::lround(sx / n)), int(std::lround(sy / n))};
}

int greyByte(double hu, double centre, double width) {
    const double g = std::clamp((hu - (centre - 0.5 * width)) / width, 0.0, 1.0);
    return int(std::lround(g * 255.0));
}

}  // namespace

// Axial from the feet (patient's left on screen right, anterior up), coronal from the front
// (left on the right, superior up), sagittal from the patient's left (anterior on screen left,
// superior up): the marker at the left-anterior-superior corner must land accordingly, and
// every pixel must be the window's grey of the HU at its world position (axis by axis, from
// the convention, not from the program's own geometry).
TEST(SliceCli, ObliqueDicomSeriesIsShownInRadiologyOrientationNeverMirrored) {
    Scratch s;
    const ObliqueCt ct;
    octrace::io::DicomSeriesWriter::write(ct.f, s.path("ct"));
    const dvec3 m = ct.markerWorld();
    const octrace::Box3 box = ct.f.worldBounds();
    struct Case {
        const char* plane;
        int normal;  // world axis
        dvec3 right, down;  // unit world directions of the screen
        bool markerRight, markerUp;
    };
    const Case cases[] = {
        {"axial", 2, dvec3(1, 0, 0), dvec3(0, 1, 0), true, true},
        {"coronal", 1, dvec3(1, 0, 0), dvec3(0, 0, -1), true, true},
        {"sagittal", 0, dvec3(0, 1, 0), dvec3(0, 0, -1), false, true},
    };
    for (const Case& c : cases) {
        const std::string out = s.path(std::string(c.plane) + ".png");
        Result r = run({"slice", s.path("ct"), "--plane", c.plane, "--at", std::to_string(m[c.normal]), "--window", "bone", "-o", out});
        ASSERT_EQ(r.code, 0) << c.plane << "\n" << r.err;
        const auto png = octrace::test::decodePng(octrace::test::readBytes(out));
        // The pixel is the finer in-plane spacing, 0.8 mm; the image spans the grid.
        const double rightLo = std::min(glm::dot(box.lo, c.right), glm::dot(box.hi, c.right));
        const double rightHi = std::max(glm::dot(box.lo, c.right), glm::dot(box.hi, c.right));
        const double downLo = std::min(glm::dot(box.lo, c.down), glm::dot(box.hi, c.down));
        const double downHi = std::max(glm::dot(box.lo, c.down), glm::dot(box.hi, c.down));
        ASSERT_EQ(png.width, int(std::floor((rightHi - rightLo) / 0.8 + 0.5 + 1e-9)) + 1) << c.plane;
        ASSERT_EQ(png.height, int(std::floor((downHi - downLo) / 0.8 + 0.5 + 1e-9)) + 1) << c.plane;
        const Bright b = brightest(png);
        EXPECT_EQ(b.x > png.width / 2, c.markerRight) << c.plane << " marker at pixel " << b.x << "," << b.y;
        EXPECT_EQ(b.y < png.height / 2, c.markerUp) << c.plane << " marker at pixel " << b.x << "," << b.y;
        EXPECT_EQ(png.at(b.x, b.y, 0), 255) << c.plane;
        // The marker's own pixel, from the convention.
        EXPECT_EQ(b.x, int(std::lround((glm::dot(m, c.right) - rightLo) / 0.8))) << c.plane;
        EXPECT_EQ(b.y, int(std::lround((glm::dot(m, c.down) - downLo) / 0.8))) << c.plane;
        // Every pixel away from the marker: the window of the HU there (exact on samples, within
        // one code where two samples 2 mm apart are interpolated).
        int exact = 0, off = 0;
        for (int y = 0; y < png.height; ++y)
            for (int x = 0; x < png.width; ++x) {
                dvec3 p = c.right * (rightLo + 0.8 * x) + c.down * (downLo + 0.8 * y);
                p[c.normal] = m[c.normal];
                if (glm::length(p - m) < 2.5) continue;
                const int want = greyByte(ct.huAt(p), 400.0, 1800.0), got = png.at(x, y, 0);
                EXPECT_EQ(png.at(x, y, 1), got);
                EXPECT_NEAR(got, want, 1) << c.plane << " pixel " << x << "," << y;
                exact += got == want;
                off += got != want;
            }
        EXPECT_GT(exact, 20 * off) << c.plane;
    }
}

TEST(SliceCli, TheChestCtAsADicomSeriesIsTheWindowOfItsVoxelsPixelForPixel) {
    if (!haveShared("medical/lidc2_chest_ct.nrrd")) GTEST_SKIP() << "shared data absent";
    Scratch s;
    octrace::io::DicomSeriesWriteOptions o;
    o.shuffleSeed = 5;
    o.window = {40.0, 400.0};  // stored in the files: the default window
    const octrace::ScalarField ct = writeChestCtSeries(s.path("ct"), o);
    for (const char* window : {"", "bone"}) {
        std::vector<std::string> args = {"slice", s.path("ct"), "--index", "70", "--stats", s.path("st.json"), "-o", s.path("ax.png")};
        if (*window) args.insert(args.end(), {"--window", window});
        Result r = run(args);
        ASSERT_EQ(r.code, 0) << r.err;
        const std::string js = slurp(s.path("st.json"));
        EXPECT_TRUE(has(js, "\"plane\": \"axial\"")) << js;
        EXPECT_TRUE(has(js, *window ? "\"window_centre\": 400," : "\"window_centre\": 40,")) << js;
        const double centre = *window ? 400.0 : 40.0, width = *window ? 1800.0 : 400.0;
        const auto png = octrace::test::decodePng(octrace::test::readBytes(s.path("ax.png")));
        ASSERT_EQ(png.width, 256);
        ASSERT_EQ(png.height, 256);
        // Identity direction: screen right is +x (sample i), down is +y (sample j).
        int wrong = 0;
        for (int y = 0; y < 256; ++y)
            for (int x = 0; x < 256; ++x) wrong += png.at(x, y, 0) != greyByte(ct.values[ct.index(x, y, 70)], centre, width);
        EXPECT_EQ(wrong, 0) << window;
    }
}

// North up, east right: at the surface the Northwest Pacific is warm in the south (bottom rows)
// and cold in the north; land (Asia, on the west) is masked.
TEST(SliceCli, LevitusTemperatureAtADepthHasNorthUpAndLandMasked) {
    if (!haveShared("ocean/levitus_climatology.cdf")) GTEST_SKIP() << "shared data absent";
    Scratch s;
    Result r = run({"slice", sharedData("ocean/levitus_climatology.cdf"), "--var", "TEMP", "--region", "120,180,10,60", "--at", "0",
                    "--colormap", "grey", "--masked-colour", "1,0,0", "--stats", s.path("st.json"), "-o", s.path("t.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(has(r.err, "0 m depth")) << r.err;
    const auto png = octrace::test::decodePng(octrace::test::readBytes(s.path("t.png")));
    auto masked = [&](int x, int y) { return png.at(x, y, 0) == 255 && png.at(x, y, 1) == 0; };
    double top = 0.0, bottom = 0.0;
    int nTop = 0, nBottom = 0, landWest = 0, landEast = 0;
    for (int y = 0; y < png.height; ++y)
        for (int x = 0; x < png.width; ++x) {
            if (masked(x, y)) {
                (x < png.width / 2 ? landWest : landEast)++;
                continue;
            }
            if (y < png.height / 4) top += png.at(x, y, 0), ++nTop;
            if (y >= 3 * png.height / 4) bottom += png.at(x, y, 0), ++nBottom;
        }
    ASSERT_GT(nTop, 0);
    ASSERT_GT(nBottom, 0);
    EXPECT_GT(bottom / nBottom, top / nTop + 60.0);
    EXPECT_GT(landWest, 4 * landEast);
    EXPECT_GT(landWest, 100);
}

TEST(SliceCli, RefusesWhatDoesNotApply) {
    Scratch s;
    Result r = run({"slice", "analytic:sphere:9", "--plane", "axial", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 2);
    EXPECT_TRUE(has(r.err, "is not in patient coordinates")) << r.err;
    r = run({"slice", "analytic:sphere:9", "--at", "0", "--index", "1", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 2);
    EXPECT_TRUE(has(r.err, "--at and --index")) << r.err;
    r = run({"slice", "analytic:sphere:9", "--at", "1e6", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(has(r.err, "lies outside the grid")) << r.err;
    r = run({"slice", "analytic:sphere:9", "--index", "9", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 2);
    EXPECT_TRUE(has(r.err, "--index: 9 is outside the 9 samples")) << r.err;
    r = run({"slice", "analytic:sphere:9", "--window", "bone", "-o", s.path("a.png")});
    EXPECT_EQ(r.code, 1);
    EXPECT_TRUE(has(r.err, "is a CT preset in Hounsfield units")) << r.err;
    r = run({"slice", "analytic:sphere:9", "-o", s.path("a.jpg")});
    EXPECT_EQ(r.code, 2);
    EXPECT_EQ(countEntries(s.dir()), 0);
    // A plain grid: z seen from above, a colour map over the slice's range.
    r = run({"slice", "analytic:sphere:9", "--plane", "x", "--size", "40x30", "-o", s.path("x.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const auto png = octrace::test::decodePng(octrace::test::readBytes(s.path("x.png")));
    EXPECT_EQ(png.width, 40);
    EXPECT_EQ(png.height, 30);
}

// --figure: the stats name the screen's directions as the letters drawn; the slice inside the
// figure is the plain slice of the same size, pixel for pixel away from the frame drawn round it.
TEST(SliceCli, FigureLettersNameTheScreenDirectionsAndItsSliceIsThePlainSlice) {
    Scratch s;
    const ObliqueCt ct;
    octrace::io::DicomSeriesWriter::write(ct.f, s.path("ct"));
    const char* expected[][3] = {{"axial", "L", "A"}, {"coronal", "L", "S"}, {"sagittal", "P", "S"}};
    for (const auto& e : expected) {
        Result r = run({"slice", s.path("ct"), "--plane", e[0], "--window", "bone", "--figure", "--size", "500x400", "--stats",
                        s.path("f.json"), "-o", s.path("f.png")});
        ASSERT_EQ(r.code, 0) << r.err;
        const std::string js = slurp(s.path("f.json"));
        EXPECT_TRUE(has(js, std::string("\"screen_right\": \"") + e[1] + "\"")) << js;
        EXPECT_TRUE(has(js, std::string("\"screen_up\": \"") + e[2] + "\"")) << js;
        const std::size_t at = js.find("\"figure_slice\": \"");
        ASSERT_NE(at, std::string::npos) << js;
        int x0 = 0, y0 = 0, w = 0, h = 0;
        ASSERT_EQ(std::sscanf(js.c_str() + at + 17, "%d,%d,%d,%d", &x0, &y0, &w, &h), 4) << js;
        const auto fig = octrace::test::decodePng(octrace::test::readBytes(s.path("f.png")));
        EXPECT_EQ(fig.width, 500);
        EXPECT_EQ(fig.height, 400);
        r = run({"slice", s.path("ct"), "--plane", e[0], "--window", "bone", "--size", std::to_string(w) + "x" + std::to_string(h),
                 "--background", "1,1,1", "-o", s.path("p.png")});
        ASSERT_EQ(r.code, 0) << r.err;
        const auto plain = octrace::test::decodePng(octrace::test::readBytes(s.path("p.png")));
        ASSERT_EQ(plain.width, w);
        ASSERT_EQ(plain.height, h);
        int differ = 0, inside = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                if (plain.at(x, y, 0) == 255 && plain.at(x, y, 1) == 255 && plain.at(x, y, 2) == 255) continue;  // background
                ++inside;
                differ += fig.at(x0 + x, y0 + y, 0) != plain.at(x, y, 0);
            }
        EXPECT_GT(inside, w * h / 10) << e[0];
        EXPECT_LT(differ, inside / 20) << e[0];  // the frame's line over the content's edge pixels
    }
}

// A MONOCHROME1 series with its own window: the file's window by default, its grey inverted
// (the marker, the densest voxel, is the darkest pixel).
TEST(SliceCli, Monochrome1SeriesIsShownInvertedInItsOwnWindow) {
    Scratch s;
    const ObliqueCt ct;
    octrace::io::DicomSeriesWriteOptions o;
    o.monochrome1 = true;
    o.window = {0.0, 1000.0};
    octrace::io::DicomSeriesWriter::write(ct.f, s.path("ct"), o);
    const dvec3 m = ct.markerWorld();
    Result r = run({"slice", s.path("ct"), "--at", std::to_string(m.z), "--stats", s.path("st.json"), "-o", s.path("ax.png")});
    ASSERT_EQ(r.code, 0) << r.err;
    const std::string js = slurp(s.path("st.json"));
    EXPECT_TRUE(has(js, "\"window_centre\": 0,")) << js;
    EXPECT_TRUE(has(js, "\"window_inverted\": true")) << js;
    const auto png = octrace::test::decodePng(octrace::test::readBytes(s.path("ax.png")));
    const octrace::Box3 box = ct.f.worldBounds();
    int checked = 0;
    for (int y = 0; y < png.height; ++y)
        for (int x = 0; x < png.width; ++x) {
            const dvec3 p(box.lo.x + 0.8 * x, box.lo.y + 0.8 * y, m.z);
            const int want = glm::length(p - m) < 1e-6 ? 0 : 255 - greyByte(ct.huAt(p), 0.0, 1000.0);
            EXPECT_NEAR(png.at(x, y, 0), want, 1) << x << "," << y;
            ++checked;
        }
    EXPECT_EQ(checked, 12 * 8);
}
