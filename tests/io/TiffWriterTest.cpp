#include "octrace/io/TiffWriter.h"

#include "ImageTestSupport.h"
#include "octrace/io/ImageWriter.h"
#include "octrace/io/PngWriter.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>
#include <tiffio.h>

using namespace octrace;
using octrace::test::readBytes;
using octrace::test::ScratchDir;

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

struct DecodedTiff {
    std::uint32_t width = 0, height = 0;
    std::uint16_t samples = 0, bits = 0, photometric = 0, extra = 0;
    std::vector<std::uint8_t> pixels;  // as stored, samples per pixel
};

/// libtiff's reader, scanline by scanline (no conversion).
DecodedTiff decodeTiff(const std::string& path) {
    DecodedTiff d;
    TIFF* tif = TIFFOpen(path.c_str(), "r");
    if (!tif) {
        ADD_FAILURE() << "libtiff cannot open " << path;
        return d;
    }
    TIFFGetField(tif, TIFFTAG_IMAGEWIDTH, &d.width);
    TIFFGetField(tif, TIFFTAG_IMAGELENGTH, &d.height);
    TIFFGetField(tif, TIFFTAG_SAMPLESPERPIXEL, &d.samples);
    TIFFGetField(tif, TIFFTAG_BITSPERSAMPLE, &d.bits);
    TIFFGetField(tif, TIFFTAG_PHOTOMETRIC, &d.photometric);
    std::uint16_t* types = nullptr;
    if (TIFFGetField(tif, TIFFTAG_EXTRASAMPLES, &d.extra, &types) && d.extra == 1) d.extra = types[0] == EXTRASAMPLE_UNASSALPHA ? 1 : 99;
    d.pixels.resize(std::size_t(d.width) * d.height * d.samples);
    for (std::uint32_t y = 0; y < d.height; ++y)
        if (TIFFReadScanline(tif, d.pixels.data() + std::size_t(y) * d.width * d.samples, y, 0) != 1)
            ADD_FAILURE() << "row " << y << " unreadable";
    TIFFClose(tif);
    return d;
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
