#include "octrace/io/PngWriter.h"

#include "ImageTestSupport.h"
#include "octrace/render/ImageCompare.h"
#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace octrace;
using octrace::io::ImageWriteOptions;
using octrace::io::PngWriter;
using octrace::test::decodePng;

namespace {

Frame opaqueFrame(int w, int h, vec3 colour) {
    Frame f(w, h);
    for (auto& p : f.rgba) p = vec4(colour, 1.0f);
    return f;
}

Frame randomFrame(int w, int h, unsigned seed, bool withAlpha) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-0.1f, 1.1f);
    Frame f(w, h);
    for (auto& p : f.rgba) p = vec4(u(rng), u(rng), u(rng), withAlpha ? u(rng) : 1.0f);
    return f;
}

}  // namespace

TEST(PngWriter, EncodesHalfLinearGreyAs188) {
    Frame f = opaqueFrame(3, 2, vec3(0.5f));
    f.rgba[f.pixel(1, 0)] = vec4(0.0f, 1.0f, 0.0f, 1.0f);
    auto png = decodePng(PngWriter::encode(f));
    ASSERT_EQ(png.width, 3);
    ASSERT_EQ(png.height, 2);
    ASSERT_EQ(png.channels, 3);
    EXPECT_EQ(png.at(0, 0, 0), 188);
    EXPECT_EQ(png.at(0, 0, 1), 188);
    EXPECT_EQ(png.at(2, 1, 2), 188);
    EXPECT_EQ(png.at(1, 0, 0), 0);
    EXPECT_EQ(png.at(1, 0, 1), 255);
    EXPECT_EQ(png.at(1, 0, 2), 0);
}

TEST(PngWriter, QuantizesExactlyLikeImageCompare) {
    Frame f = randomFrame(37, 23, 7, true);
    auto png = decodePng(PngWriter::encode(f));
    ASSERT_EQ(png.channels, 4);
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) {
            const vec4 c = f.rgba[f.pixel(x, y)];
            ASSERT_EQ(png.at(x, y, 0), linearToSrgb8(c.r)) << x << "," << y;
            ASSERT_EQ(png.at(x, y, 1), linearToSrgb8(c.g)) << x << "," << y;
            ASSERT_EQ(png.at(x, y, 2), linearToSrgb8(c.b)) << x << "," << y;
            ASSERT_EQ(png.at(x, y, 3), alphaTo8(c.a)) << x << "," << y;
        }
}

TEST(PngWriter, PutsRowZeroAtTheTop) {
    Frame f = opaqueFrame(1, 2, vec3(0.0f));
    f.rgba[f.pixel(0, 0)] = vec4(1.0f, 0.0f, 0.0f, 1.0f);
    auto png = decodePng(PngWriter::encode(f));
    EXPECT_EQ(png.at(0, 0, 0), 255);
    EXPECT_EQ(png.at(0, 1, 0), 0);
}

TEST(PngWriter, ClampsOutOfRangeAndNanColour) {
    Frame f = opaqueFrame(1, 1, vec3(0.0f));
    f.rgba[0] = vec4(-3.0f, 42.0f, std::numeric_limits<float>::quiet_NaN(), 1.0f);
    auto png = decodePng(PngWriter::encode(f));
    EXPECT_EQ(png.at(0, 0, 0), 0);
    EXPECT_EQ(png.at(0, 0, 1), 255);
    EXPECT_EQ(png.at(0, 0, 2), 0);
}

TEST(PngWriter, WritesRgbWhenEveryPixelIsOpaque) {
    Frame f = opaqueFrame(4, 4, vec3(0.25f));
    f.rgba[3].a = 2.0f;  // more than opaque still counts as opaque
    EXPECT_EQ(decodePng(PngWriter::encode(f)).channels, 3);
}

TEST(PngWriter, WritesStraightAlphaWhenAnyPixelIsTranslucent) {
    Frame f = opaqueFrame(2, 1, vec3(0.5f));
    f.rgba[1] = vec4(0.5f, 0.5f, 0.5f, 0.5f);
    auto png = decodePng(PngWriter::encode(f));
    ASSERT_EQ(png.channels, 4);
    EXPECT_EQ(png.at(0, 0, 3), 255);
    EXPECT_EQ(png.at(1, 0, 3), 128);  // 127.5 rounds up; alpha is linear, not sRGB-encoded
    EXPECT_EQ(png.at(1, 0, 0), 188);  // straight: colour not multiplied by alpha
}

TEST(PngWriter, WritesAlphaWhenAskedEvenIfOpaque) {
    Frame f = opaqueFrame(2, 2, vec3(1.0f));
    ImageWriteOptions options;
    options.alpha = true;
    auto png = decodePng(PngWriter::encode(f, options));
    ASSERT_EQ(png.channels, 4);
    EXPECT_EQ(png.at(1, 1, 3), 255);
}

TEST(PngWriter, KeepsFullyTransparentPixelsColour) {
    Frame f = opaqueFrame(1, 1, vec3(0.0f));
    f.rgba[0] = vec4(1.0f, 0.5f, 0.0f, 0.0f);
    auto png = decodePng(PngWriter::encode(f));
    ASSERT_EQ(png.channels, 4);
    EXPECT_EQ(png.at(0, 0, 0), 255);
    EXPECT_EQ(png.at(0, 0, 1), 188);
    EXPECT_EQ(png.at(0, 0, 3), 0);
}

TEST(PngWriter, MarksTheFileAsSrgbWithoutTimeStamp) {
    auto bytes = PngWriter::encode(opaqueFrame(2, 2, vec3(0.1f)));
    EXPECT_TRUE(octrace::test::hasPngChunk(bytes, "sRGB"));
    EXPECT_TRUE(octrace::test::hasPngChunk(bytes, "IEND"));
    EXPECT_FALSE(octrace::test::hasPngChunk(bytes, "tIME"));
    EXPECT_FALSE(octrace::test::hasPngChunk(bytes, "tEXt"));
}

TEST(PngWriter, GivesIdenticalBytesForTheSameFrame) {
    Frame f = randomFrame(64, 48, 3, true);
    Frame copy = f;
    EXPECT_EQ(PngWriter::encode(f), PngWriter::encode(copy));

    octrace::test::ScratchDir dir;
    PngWriter::write(f, dir.file("a.png"));
    PngWriter::write(copy, dir.file("b.png"));
    auto a = octrace::test::readBytes(dir.file("a.png"));
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a, octrace::test::readBytes(dir.file("b.png")));
    EXPECT_EQ(a, PngWriter::encode(f));
}

TEST(PngWriter, WritesAFileLibpngReadsAndLeavesNoTemporary) {
    octrace::test::ScratchDir dir;
    Frame f = opaqueFrame(5, 3, vec3(0.5f));
    PngWriter::write(f, dir.file("out.png"));
    EXPECT_EQ(dir.entries(), std::vector<std::string>{"out.png"});
    auto png = decodePng(octrace::test::readBytes(dir.file("out.png")));
    EXPECT_EQ(png.width, 5);
    EXPECT_EQ(png.at(4, 2, 1), 188);
}

TEST(PngWriter, RejectsEmptyOrInconsistentFrames) {
    EXPECT_THROW(PngWriter::encode(Frame()), OutputError);
    Frame broken(3, 3);
    broken.rgba.resize(8);
    EXPECT_THROW(PngWriter::encode(broken), OutputError);

    octrace::test::ScratchDir dir;
    try {
        PngWriter::write(Frame(), dir.file("empty.png"));
        FAIL() << "expected OutputError";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find("empty.png"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
    }
    EXPECT_TRUE(dir.entries().empty());
}

TEST(PngWriter, TurnsLibpngErrorsIntoOutputError) {
    Frame tooWide(1000001, 1);  // beyond libpng's default width limit of 10^6
    try {
        PngWriter::encode(tooWide);
        FAIL() << "expected OutputError";
    } catch (const OutputError& e) {
        EXPECT_NE(std::string(e.what()).find("PNG"), std::string::npos) << e.what();
    }
}
