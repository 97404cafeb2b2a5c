#include "octrace/render/ImageCompare.h"

#include "octrace/util/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

using namespace octrace;

namespace {

// The sRGB encoding written out directly, in double precision.
double srgbEncode(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }

Frame uniformFrame(int w, int h, vec4 colour) {
    Frame f(w, h);
    for (auto& p : f.rgba) p = colour;
    return f;
}

}  // namespace

TEST(LinearToSrgb8, MapsHalfLinearTo188) { EXPECT_EQ(linearToSrgb8(0.5f), 188); }

TEST(LinearToSrgb8, MapsEndsAndClampsOutOfRange) {
    EXPECT_EQ(linearToSrgb8(0.0f), 0);
    EXPECT_EQ(linearToSrgb8(1.0f), 255);
    EXPECT_EQ(linearToSrgb8(-0.25f), 0);
    EXPECT_EQ(linearToSrgb8(7.0f), 255);
    EXPECT_EQ(linearToSrgb8(std::numeric_limits<float>::infinity()), 255);
    EXPECT_EQ(linearToSrgb8(-std::numeric_limits<float>::infinity()), 0);
    EXPECT_EQ(linearToSrgb8(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(LinearToSrgb8, UsesTheLinearSegmentNearBlack) {
    // 12.92 · 0.002 · 255 = 6.59 -> 7 (a pure power law would give 28).
    EXPECT_EQ(linearToSrgb8(0.002f), 7);
}

TEST(LinearToSrgb8, RoundsTheTransferFunctionToNearestOnADenseSweep) {
    int checked = 0;
    for (int i = 0; i <= 1000000; ++i) {
        float c = float(i) / 1000000.0f;
        double scaled = srgbEncode(double(c)) * 255.0;
        if (std::abs(scaled - std::floor(scaled) - 0.5) < 1e-6) continue;  // too close to a tie to judge
        ASSERT_EQ(int(linearToSrgb8(c)), int(std::lround(scaled))) << "linear " << c;
        ++checked;
    }
    EXPECT_GT(checked, 999000);
}

TEST(LinearToSrgb8, SwitchesCodeExactlyAtEachRoundingThreshold) {
    // Code k starts at the linear value whose encoding is (k - 0.5) / 255: the float just below
    // that value has code k - 1, the float at or just above it code k (the quantization's look-up
    // table must not move any of these 255 switches).
    for (int k = 1; k <= 255; ++k) {
        const double e = (k - 0.5) / 255.0;
        const double t = e <= 0.04045 ? e / 12.92 : std::pow((e + 0.055) / 1.055, 2.4);
        float at = float(t);
        if (double(at) < t) at = std::nextafter(at, 2.0f);
        const float below = std::nextafter(at, -1.0f);
        ASSERT_EQ(int(linearToSrgb8(below)), k - 1) << "code " << k;
        ASSERT_EQ(int(linearToSrgb8(at)), k) << "code " << k;
    }
    EXPECT_EQ(int(linearToSrgb8(std::nextafter(1.0f, 0.0f))), 255);
}

TEST(LinearToSrgb8, IsMonotonic) {
    int previous = 0;
    for (int i = 0; i <= 100000; ++i) {
        int code = linearToSrgb8(float(i) / 100000.0f);
        ASSERT_GE(code, previous);
        previous = code;
    }
}

TEST(Srgb8ToLinear, RoundTripsEveryCode) {
    for (int k = 0; k <= 255; ++k) EXPECT_EQ(int(linearToSrgb8(srgb8ToLinear(std::uint8_t(k)))), k);
    EXPECT_EQ(srgb8ToLinear(0), 0.0f);
    EXPECT_EQ(srgb8ToLinear(255), 1.0f);
}

TEST(AlphaTo8, RoundsLinearlyAndClamps) {
    EXPECT_EQ(alphaTo8(0.5f), 128);  // 127.5 rounds up
    EXPECT_EQ(alphaTo8(0.25f), 64);  // 63.75
    EXPECT_EQ(alphaTo8(1.0f), 255);
    EXPECT_EQ(alphaTo8(0.0f), 0);
    EXPECT_EQ(alphaTo8(1.5f), 255);
    EXPECT_EQ(alphaTo8(-1.0f), 0);
    EXPECT_EQ(alphaTo8(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(CompareImages, IdenticalFramesHaveInfinitePsnrAndNoDifference) {
    Frame a = uniformFrame(8, 4, vec4(0.2f, 0.5f, 0.9f, 1.0f));
    ImageDifference d = compareImages(a, a);
    EXPECT_EQ(d.differingPixels, 0u);
    EXPECT_TRUE(std::isinf(d.psnrDb) && d.psnrDb > 0);
    EXPECT_EQ(d.maxChannelError, 0.0);
}

TEST(CompareImages, IgnoresDifferencesBelowTheQuantization) {
    Frame a = uniformFrame(4, 4, vec4(0.5f, 0.5f, 0.5f, 1.0f));
    Frame b = uniformFrame(4, 4, vec4(0.50001f, 0.49999f, 0.5f, 1.0f));
    ImageDifference d = compareImages(a, b);
    EXPECT_EQ(d.differingPixels, 0u);
    EXPECT_TRUE(std::isinf(d.psnrDb));
}

TEST(CompareImages, MeasuresOneFullScaleChannelError) {
    Frame a = uniformFrame(2, 2, vec4(0.0f, 0.0f, 0.0f, 1.0f));
    Frame b = a;
    b.rgba[b.pixel(1, 1)].r = 1.0f;
    ImageDifference d = compareImages(a, b);
    EXPECT_EQ(d.differingPixels, 1u);
    EXPECT_EQ(d.maxChannelError, 255.0);
    // MSE over 4 pixels × 3 channels = 255² / 12, so PSNR = 10·log10(12).
    EXPECT_NEAR(d.psnrDb, 10.0 * std::log10(12.0), 1e-12);
}

TEST(CompareImages, CountsAlphaDifferencesButLeavesThemOutOfPsnr) {
    Frame a = uniformFrame(3, 1, vec4(0.3f, 0.3f, 0.3f, 1.0f));
    Frame b = a;
    b.rgba[0].a = 0.0f;
    ImageDifference d = compareImages(a, b);
    EXPECT_EQ(d.differingPixels, 1u);
    EXPECT_EQ(d.maxChannelError, 255.0);
    EXPECT_TRUE(std::isinf(d.psnrDb));
}

TEST(CompareImages, MeasuresInSrgbCodesNotLinearUnits) {
    Frame a = uniformFrame(1, 1, vec4(0.5f, 0.0f, 0.0f, 1.0f));
    Frame b = uniformFrame(1, 1, vec4(0.25f, 0.0f, 0.0f, 1.0f));
    ImageDifference d = compareImages(a, b);
    EXPECT_EQ(d.maxChannelError, double(linearToSrgb8(0.5f) - linearToSrgb8(0.25f)));
}

TEST(CompareImages, RejectsFramesOfDifferentSize) {
    EXPECT_THROW(compareImages(Frame(4, 4), Frame(4, 5)), UsageError);
    Frame broken(2, 2);
    broken.rgba.pop_back();
    EXPECT_THROW(compareImages(broken, Frame(2, 2)), UsageError);
}

TEST(CompareImages, EmptyFramesAreIdentical) {
    ImageDifference d = compareImages(Frame(), Frame());
    EXPECT_EQ(d.differingPixels, 0u);
    EXPECT_TRUE(std::isinf(d.psnrDb));
}

// packSrgb8Rows writes quantizeSrgb8's bytes as 0xAARRGGBB words into rows of any stride, the
// same on 1 and 2 threads, and says whether every alpha is 255.
TEST(PackSrgb8Rows, WritesQuantizeSrgb8sBytesInQtsLayoutIntoRowsOfAnyStride) {
    Frame f(37, 71);  // more rows than one task's 32
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x)
            f.rgba[f.pixel(x, y)] = vec4(float(x) / 36.0f, float(y) / 70.0f, float((x * 7 + y) % 13) / 12.0f - 0.1f, 1.0f);
    const std::vector<std::uint8_t> want = quantizeSrgb8(f, 4);
    for (int threads : {1, 2}) {
        const std::size_t stride = std::size_t(f.width) * 4 + 12;
        std::vector<std::uint8_t> out(stride * std::size_t(f.height), 0xAB);
        EXPECT_TRUE(packSrgb8Rows(f, out.data(), stride, threads));
        for (int y = 0; y < f.height; ++y) {
            for (int x = 0; x < f.width; ++x) {
                std::uint32_t w;
                std::memcpy(&w, out.data() + std::size_t(y) * stride + std::size_t(x) * 4, 4);
                const std::uint8_t* q = want.data() + (std::size_t(y) * std::size_t(f.width) + std::size_t(x)) * 4;
                ASSERT_EQ(w, std::uint32_t(q[3]) << 24 | std::uint32_t(q[0]) << 16 | std::uint32_t(q[1]) << 8 | q[2])
                    << x << "," << y << " on " << threads << " threads";
            }
            for (std::size_t b = std::size_t(f.width) * 4; b < stride; ++b) ASSERT_EQ(out[std::size_t(y) * stride + b], 0xAB);
        }
    }
    f.rgba[f.pixel(20, 60)].a = 0.5f;
    std::vector<std::uint8_t> out(std::size_t(f.width) * std::size_t(f.height) * 4);
    EXPECT_FALSE(packSrgb8Rows(f, out.data(), std::size_t(f.width) * 4, 2));
    EXPECT_EQ(out[(std::size_t(60) * std::size_t(f.width) + 20) * 4 + 3], alphaTo8(0.5f));
    EXPECT_THROW(packSrgb8Rows(f, out.data(), std::size_t(f.width) * 4 - 1, 1), UsageError);
}

// Both conversions remember the last colour (runs of equal colours are converted once): every
// pixel must still get its own codes, whatever comes before it (runs, a colour that differs only
// in alpha or in the sign of a zero, NaN), and the opaque answer must see every alpha.
TEST(PackSrgb8Rows, RunsOfEqualColoursGiveEachPixelItsOwnCodes) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const std::vector<vec4> row = {vec4(nan, 0.2f, 0.3f, nan),     vec4(nan, 0.2f, 0.3f, nan), vec4(0.2f, 0.2f, 0.3f, 1.0f),
                                   vec4(0.2f, 0.2f, 0.3f, 1.0f),  vec4(0.2f, 0.2f, 0.3f, 0.5f), vec4(0.2f, 0.2f, 0.3f, 1.0f),
                                   vec4(0.0f, 0.0f, 0.0f, 1.0f),  vec4(-0.0f, 0.0f, 0.0f, 1.0f), vec4(0.7f, 0.7f, 0.7f, 1.0f),
                                   vec4(0.7f, 0.7f, 0.71f, 1.0f)};
    Frame f(int(row.size()), 3);
    for (int y = 0; y < f.height; ++y)
        for (int x = 0; x < f.width; ++x) f.rgba[f.pixel(x, y)] = row[std::size_t((x + y) % f.width)];
    const std::vector<std::uint8_t> q = quantizeSrgb8(f, 4);
    std::vector<std::uint8_t> packed(std::size_t(f.width) * std::size_t(f.height) * 4);
    EXPECT_FALSE(packSrgb8Rows(f, packed.data(), std::size_t(f.width) * 4, 1));  // NaN and 0.5 alphas
    for (std::size_t i = 0; i < f.rgba.size(); ++i) {
        const vec4& c = f.rgba[i];
        const std::uint8_t want[4] = {linearToSrgb8(c.r), linearToSrgb8(c.g), linearToSrgb8(c.b), alphaTo8(c.a)};
        for (int k = 0; k < 4; ++k) ASSERT_EQ(q[i * 4 + std::size_t(k)], want[k]) << "pixel " << i << " channel " << k;
        std::uint32_t w;
        std::memcpy(&w, packed.data() + i * 4, 4);
        ASSERT_EQ(w, std::uint32_t(want[3]) << 24 | std::uint32_t(want[0]) << 16 | std::uint32_t(want[1]) << 8 | want[2]) << i;
    }
    // Opaque except for the first pixel of a row whose other pixels are equal to it but for alpha.
    Frame g(5, 2);
    for (vec4& c : g.rgba) c = vec4(0.4f, 0.4f, 0.4f, 1.0f);
    g.rgba[g.pixel(0, 1)].a = 0.0f;
    std::vector<std::uint8_t> out(std::size_t(g.width) * std::size_t(g.height) * 4);
    EXPECT_FALSE(packSrgb8Rows(g, out.data(), std::size_t(g.width) * 4, 2));
    g.rgba[g.pixel(0, 1)].a = 1.0f;
    EXPECT_TRUE(packSrgb8Rows(g, out.data(), std::size_t(g.width) * 4, 2));
}
