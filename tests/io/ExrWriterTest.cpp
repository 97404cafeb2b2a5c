#include "octrace/io/ExrWriter.h"

#include "ImageTestSupport.h"
#include "octrace/util/Error.h"

#include <OpenEXR/ImfThreading.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

using namespace octrace;
using octrace::io::ExrWriter;
using octrace::test::readExr;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

Frame sampleFrame(int w, int h, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::uniform_real_distribution<float> dist(0.001f, 5000.0f);
    Frame f(w, h);
    for (std::size_t i = 0; i < f.rgba.size(); ++i) {
        f.rgba[i] = vec4(u(rng), u(rng), u(rng), u(rng));
        f.depth[i] = (i % 3 == 0) ? kInf : dist(rng);
    }
    return f;
}

}  // namespace

TEST(ExrWriter, WritesHalfRgbaAndFloatZWithZipCompression) {
    octrace::test::ScratchDir dir;
    ExrWriter::write(sampleFrame(7, 5, 1), dir.file("out.exr"));
    auto exr = readExr(dir.file("out.exr"));
    EXPECT_EQ(exr.width, 7);
    EXPECT_EQ(exr.height, 5);
    EXPECT_EQ(exr.compression, Imf::ZIP_COMPRESSION);
    std::map<std::string, Imf::PixelType> expected{
        {"R", Imf::HALF}, {"G", Imf::HALF}, {"B", Imf::HALF}, {"A", Imf::HALF}, {"Z", Imf::FLOAT}};
    EXPECT_EQ(exr.channelTypes, expected);
}

TEST(ExrWriter, StoresDepthExactlyWithInfinityForMisses) {
    Frame f(4, 2);  // every depth starts at +inf
    f.depth[f.pixel(1, 0)] = 1.0f;
    f.depth[f.pixel(2, 0)] = 123.456789f;
    f.depth[f.pixel(3, 0)] = std::nextafter(2.0f, 3.0f);  // not representable as half
    f.depth[f.pixel(0, 1)] = 1e-30f;
    f.depth[f.pixel(1, 1)] = 3.0e38f;
    octrace::test::ScratchDir dir;
    ExrWriter::write(f, dir.file("z.exr"));
    auto exr = readExr(dir.file("z.exr"));
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) EXPECT_EQ(exr.at("Z", x, y), f.depth[f.pixel(x, y)]) << x << "," << y;
    EXPECT_TRUE(std::isinf(exr.at("Z", 0, 0)) && exr.at("Z", 0, 0) > 0);
    EXPECT_TRUE(std::isinf(exr.at("Z", 3, 1)));
}

TEST(ExrWriter, StoresLinearColourAsNearestHalf) {
    Frame f(3, 2);
    f.rgba[f.pixel(0, 0)] = vec4(0.5f, 0.25f, 2.0f, 1.0f);  // exact in half, HDR kept
    f.rgba[f.pixel(1, 0)] = vec4(0.1f, 0.7f, 0.0f, 0.3f);
    f.rgba[f.pixel(2, 1)] = vec4(-0.5f, 1000.0f, 1e-3f, 0.0f);
    octrace::test::ScratchDir dir;
    ExrWriter::write(f, dir.file("c.exr"));
    auto exr = readExr(dir.file("c.exr"));
    const char* names[4] = {"R", "G", "B", "A"};
    for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 3; ++x)
            for (int c = 0; c < 4; ++c)
                EXPECT_EQ(exr.at(names[c], x, y), float(Imath::half(f.rgba[f.pixel(x, y)][c])))
                    << names[c] << " at " << x << "," << y;
    EXPECT_EQ(exr.at("R", 0, 0), 0.5f);  // linear: no sRGB encoding in EXR
    EXPECT_EQ(exr.at("B", 0, 0), 2.0f);
    EXPECT_EQ(exr.at("A", 0, 0), 1.0f);
    EXPECT_EQ(exr.at("G", 2, 1), 1000.0f);
}

TEST(ExrWriter, PutsRowZeroAtTheTop) {
    Frame f(1, 2);
    f.depth[0] = 1.0f;
    f.depth[1] = 2.0f;
    octrace::test::ScratchDir dir;
    ExrWriter::write(f, dir.file("rows.exr"));
    auto exr = readExr(dir.file("rows.exr"));
    EXPECT_EQ(exr.at("Z", 0, 0), 1.0f);
    EXPECT_EQ(exr.at("Z", 0, 1), 2.0f);
}

TEST(ExrWriter, GivesIdenticalBytesForTheSameFrame) {
    Frame f = sampleFrame(96, 40, 9);
    Frame copy = f;
    auto once = ExrWriter::encode(f);
    EXPECT_FALSE(once.empty());
    EXPECT_EQ(once, ExrWriter::encode(copy));

    octrace::test::ScratchDir dir;
    ExrWriter::write(f, dir.file("a.exr"));
    ExrWriter::write(copy, dir.file("b.exr"));
    EXPECT_EQ(octrace::test::readBytes(dir.file("a.exr")), once);
    EXPECT_EQ(octrace::test::readBytes(dir.file("b.exr")), once);
}

TEST(ExrWriter, GivesIdenticalBytesWhateverOpenExrThreadCount) {
    Frame f = sampleFrame(64, 100, 4);  // several ZIP blocks of 16 lines
    const int before = Imf::globalThreadCount();
    Imf::setGlobalThreadCount(0);
    auto serial = ExrWriter::encode(f);
    Imf::setGlobalThreadCount(4);
    auto threaded = ExrWriter::encode(f);
    Imf::setGlobalThreadCount(before);
    EXPECT_EQ(serial, threaded);
}

TEST(ExrWriter, RejectsAFrameWithoutDepthForEveryPixel) {
    Frame f(4, 4);
    f.depth.clear();
    EXPECT_THROW(ExrWriter::encode(f), OutputError);
    EXPECT_THROW(ExrWriter::encode(Frame()), OutputError);
    octrace::test::ScratchDir dir;
    EXPECT_THROW(ExrWriter::write(f, dir.file("nodepth.exr")), OutputError);
    EXPECT_TRUE(dir.entries().empty());
}
