#include "octrace/io/TiffWriter.h"

#include "ImageTestSupport.h"
#include "octrace/io/ImageWriter.h"
#include "octrace/io/PngWriter.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

using namespace octrace;
using octrace::test::readBytes;
using octrace::test::ScratchDir;
using octrace::test::decodeTiff;
using octrace::test::DecodedTiff;

namespace {

/// A frame with a gradient, a translucent corner and an out-of-range value.
Frame testFrame(int w, int h, bool translucent) {
    Frame f(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const float v = float(x + y * w) / float(w * h);
            f.rgba[f.pixel(x, y)] = vec4(v, 1.0f - v, v * v, translucent && x < 3 ? 0.25f : 1.0f);
        }
    f.rgba[0] = vec4(2.0f, -1.0f, 0.5f, translucent ? 0.0f : 1.0f);
    return f;
}

}  // namespace

TEST(TiffWriter, HoldsThePngsPixels) {
    for (bool translucent : {false, true}) {
        ScratchDir dir;
        const Frame f = testFrame(150, 70, translucent);  // more than one 64-row strip
        io::writeImage(f, dir.file("a.tif"));
        io::writeImage(f, dir.file("a.png"));
        const DecodedTiff t = decodeTiff(dir.file("a.tif"));
        const auto png = test::decodePng(readBytes(dir.file("a.png")));
        EXPECT_EQ(t.width, 150u);
        EXPECT_EQ(t.height, 70u);
        EXPECT_EQ(t.bits, 8);
        EXPECT_EQ(t.photometric, PHOTOMETRIC_RGB);
        EXPECT_EQ(int(t.samples), png.channels);
        EXPECT_EQ(t.extra, translucent ? 1 : 0);  // unassociated alpha, as the PNG's
        EXPECT_EQ(t.pixels, png.pixels);
    }
}

TEST(TiffWriter, AlphaOnRequestAndBytesThatDependOnlyOnTheFrame) {
    io::ImageWriteOptions alpha;
    alpha.alpha = true;
    const Frame f = testFrame(9, 5, false);
    EXPECT_EQ(io::TiffWriter::encode(f), io::TiffWriter::encode(f));
    ScratchDir dir;
    io::TiffWriter::write(f, dir.file("b.TIFF"), alpha);
    EXPECT_EQ(decodeTiff(dir.file("b.TIFF")).samples, 4);
    EXPECT_EQ(readBytes(dir.file("b.TIFF")), io::TiffWriter::encode(f, alpha));
}

TEST(TiffWriter, RefusesAnEmptyFrameAndNamesThePath) {
    ScratchDir dir;
    EXPECT_THROW(io::TiffWriter::encode(Frame()), OutputError);
    try {
        io::writeImage(Frame(), dir.file("c.tif"));
        FAIL() << "expected OutputError";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find("c.tif"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(dir.entries().empty());
}

TEST(TiffWriter, RecordsTheDpiAsAResolutionInInches) {
    ScratchDir dir;
    io::ImageWriteOptions o;
    o.dpi = 300;
    io::writeImage(testFrame(20, 10, false), dir.file("a.tif"), o);
    io::writeImage(testFrame(20, 10, false), dir.file("b.tif"));
    EXPECT_EQ(decodeTiff(dir.file("a.tif")).dpi, 300.0f);
    EXPECT_EQ(decodeTiff(dir.file("b.tif")).dpi, 0.0f);  // none recorded
    EXPECT_EQ(decodeTiff(dir.file("a.tif")).pixels, decodeTiff(dir.file("b.tif")).pixels);
}
