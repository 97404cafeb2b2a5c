#include "octrace/render/ImageCompare.h"

#include "octrace/util/Error.h"
#include "octrace/util/Parallel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

namespace octrace {
namespace {

double srgbToLinear(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

// Quantizing through the inverse: code k starts where the encoded value reaches k − 0.5,
// i.e. at linear srgbToLinear((k − 0.5)/255). Comparing against these 255 thresholds rounds
// to nearest without a pow() per channel, and gives the same code on every machine for a
// given input (no dependence on how the caller's libm rounds pow near a tie).
// Instead of a binary search over them, a value in [0, 1) starts from the code of the lower
// end of its 1/4096 bucket and steps over the (at most two) thresholds inside the bucket: the
// same count of thresholds at or below the value, found in a look-up and a compare or two.
struct SrgbTables {
    static constexpr int kBuckets = 4096;
    std::array<double, 256> thresholds{};  // thresholds[k-1]: smallest linear value with code >= k; [255] = +inf
    std::array<float, 256> toLinear{};
    std::array<std::uint8_t, kBuckets> bucketCode{};  // code of linear value i / kBuckets
    SrgbTables() {
        for (int k = 1; k <= 255; ++k) thresholds[std::size_t(k - 1)] = srgbToLinear((k - 0.5) / 255.0);
        thresholds[255] = std::numeric_limits<double>::infinity();
        for (int k = 0; k <= 255; ++k) toLinear[std::size_t(k)] = float(srgbToLinear(k / 255.0));
        for (int i = 0; i < kBuckets; ++i)
            bucketCode[std::size_t(i)] = std::uint8_t(
                std::upper_bound(thresholds.begin(), thresholds.end() - 1, double(i) / kBuckets) - thresholds.begin());
    }
};

const SrgbTables& tables() {
    static const SrgbTables t;
    return t;
}

struct Rgba8 {
    std::array<std::uint8_t, 4> c;
};

Rgba8 quantize(const vec4& v) {
    return {{linearToSrgb8(v.r), linearToSrgb8(v.g), linearToSrgb8(v.b), alphaTo8(v.a)}};
}

void checkFrame(const Frame& f, const char* which) {
    std::size_t n = std::size_t(std::max(f.width, 0)) * std::size_t(std::max(f.height, 0));
    if (f.width < 0 || f.height < 0 || f.rgba.size() != n)
        throw UsageError(std::string("compareImages: frame ") + which + " holds " + std::to_string(f.rgba.size()) +
                         " colour values for " + std::to_string(f.width) + "x" + std::to_string(f.height) +
                         " pixels");
}

}  // namespace

namespace {

inline std::uint8_t toSrgb8(const SrgbTables& t, float linear) {
    if (!(linear > 0.0f)) return 0;  // also NaN
    if (linear >= 1.0f) return 255;
    // linear * 4096 is exact (a power of two) and below 4096: truncation is the bucket.
    std::size_t code = t.bucketCode[std::size_t(linear * float(SrgbTables::kBuckets))];
    while (t.thresholds[code] <= double(linear)) ++code;  // thresholds[255] = inf stops it
    return std::uint8_t(code);
}

}  // namespace

std::uint8_t linearToSrgb8(float linear) { return toSrgb8(tables(), linear); }

std::uint32_t packSrgb8(const vec4& v) {
    const SrgbTables& t = tables();
    return std::uint32_t(toSrgb8(t, v.r)) | std::uint32_t(toSrgb8(t, v.g)) << 8 | std::uint32_t(toSrgb8(t, v.b)) << 16 |
           std::uint32_t(alphaTo8(v.a)) << 24;
}

float srgb8ToLinear(std::uint8_t code) { return tables().toLinear[code]; }

std::uint8_t alphaTo8(float alpha) {
    if (!(alpha > 0.0f)) return 0;  // also NaN
    if (alpha >= 1.0f) return 255;
    return std::uint8_t(std::floor(double(alpha) * 255.0 + 0.5));
}

namespace {
/// A colour as A << 24 | R << 16 | G << 8 | B (toSrgb8, alphaTo8), the last one remembered: a run
/// of equal colours (the background, a flat face) is converted once.
class PackMemo {
public:
    explicit PackMemo(const SrgbTables& t) : t_(t) {}
    std::uint32_t argb(const vec4& c) {
        if (!have_ || std::memcmp(&c, &last_, sizeof(vec4)) != 0) {
            have_ = true;
            last_ = c;
            packed_ = std::uint32_t(alphaTo8(c.a)) << 24 | std::uint32_t(toSrgb8(t_, c.r)) << 16 |
                      std::uint32_t(toSrgb8(t_, c.g)) << 8 | std::uint32_t(toSrgb8(t_, c.b));
        }
        return packed_;
    }

private:
    const SrgbTables& t_;
    vec4 last_{0.0f};
    std::uint32_t packed_ = 0;
    bool have_ = false;
};
}  // namespace

bool needsAlphaChannel(const Frame& frame, bool forced) {
    if (forced) return true;
    for (const vec4& c : frame.rgba)
        if (!(c.a >= 1.0f)) return true;  // NaN alpha counts as not opaque
    return false;
}

namespace {
void checkQuantized(const Frame& frame, const char* what) {
    if (frame.width < 0 || frame.height < 0 ||
        frame.rgba.size() != std::size_t(std::max(frame.width, 0)) * std::size_t(std::max(frame.height, 0)))
        throw UsageError(std::string(what) + ": the frame holds " + std::to_string(frame.rgba.size()) +
                         " colour values for " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                         " pixels");
}
}  // namespace

std::vector<std::uint8_t> quantizeSrgb8(const Frame& frame, int channels) {
    if (channels != 3 && channels != 4) throw UsageError("quantizeSrgb8: 3 or 4 channels, not " + std::to_string(channels));
    checkQuantized(frame, "quantizeSrgb8");
    std::vector<std::uint8_t> out(frame.rgba.size() * std::size_t(channels));
    std::uint8_t* px = out.data();
    PackMemo memo(tables());
    for (const vec4& c : frame.rgba) {
        const std::uint32_t v = memo.argb(c);
        px[0] = std::uint8_t(v >> 16);
        px[1] = std::uint8_t(v >> 8);
        px[2] = std::uint8_t(v);
        if (channels == 4) px[3] = std::uint8_t(v >> 24);
        px += channels;
    }
    return out;
}

bool packSrgb8Rows(const Frame& frame, std::uint8_t* out, std::size_t stride, int threads) {
    checkQuantized(frame, "packSrgb8Rows");
    if (stride < std::size_t(frame.width) * 4)
        throw UsageError("packSrgb8Rows: rows of " + std::to_string(stride) + " bytes cannot hold " +
                         std::to_string(frame.width) + " pixels");
    const SrgbTables& t = tables();
    constexpr std::size_t kRows = 32;  // rows per task
    const std::size_t h = std::size_t(frame.height), w = std::size_t(frame.width);
    std::vector<std::uint8_t> opaque((h + kRows - 1) / kRows, 1);
    parallelFor(opaque.size(), threads, [&](std::size_t task) {
        for (std::size_t y = task * kRows; y < std::min(h, (task + 1) * kRows); ++y) {
            const vec4* c = frame.rgba.data() + y * w;
            std::uint32_t* row = reinterpret_cast<std::uint32_t*>(out + y * stride);
            std::uint32_t alphas = 0xFFu;
            PackMemo memo(t);
            for (std::size_t x = 0; x < w; ++x) {
                row[x] = memo.argb(c[x]);
                alphas &= row[x] >> 24;
            }
            if (alphas != 0xFFu) opaque[task] = 0;
        }
    });
    return std::all_of(opaque.begin(), opaque.end(), [](std::uint8_t o) { return o != 0; });
}

ImageDifference compareImages(const Frame& a, const Frame& b) {
    checkFrame(a, "a");
    checkFrame(b, "b");
    if (a.width != b.width || a.height != b.height)
        throw UsageError("compareImages: frames differ in size (" + std::to_string(a.width) + "x" +
                         std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                         std::to_string(b.height) + ")");

    ImageDifference d;
    std::uint64_t sumSquares = 0;  // exact: at most 3·255² per pixel
    int maxError = 0;
    for (std::size_t i = 0; i < a.rgba.size(); ++i) {
        Rgba8 pa = quantize(a.rgba[i]);
        Rgba8 pb = quantize(b.rgba[i]);
        if (pa.c != pb.c) ++d.differingPixels;
        for (int ch = 0; ch < 4; ++ch) {
            int e = std::abs(int(pa.c[std::size_t(ch)]) - int(pb.c[std::size_t(ch)]));
            maxError = std::max(maxError, e);
            if (ch < 3) sumSquares += std::uint64_t(e * e);
        }
    }
    d.maxChannelError = maxError;
    if (sumSquares == 0) {
        d.psnrDb = std::numeric_limits<double>::infinity();
    } else {
        double mse = double(sumSquares) / (3.0 * double(a.rgba.size()));
        d.psnrDb = 10.0 * std::log10(255.0 * 255.0 / mse);
    }
    return d;
}

}  // namespace octrace
